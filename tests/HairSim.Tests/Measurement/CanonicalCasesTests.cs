using HairSim.Measurement;

namespace HairSim.Tests.Measurement;

/// <summary>The canonical cases against their analytic answers, for configurations where the answer must be met.</summary>
public class CanonicalCasesTests
{
    private static SimulationSettings Config(ShapeMatchMode mode, float alpha, int substeps, LengthMode length, int iterations = 4)
    {
        var s = new SolverConfiguration(mode, alpha, substeps, length, iterations, BendModel.SourceTriples).ToSettings(null, SolverPath.Reference);
        s.Guards = false;
        return s;
    }

    [Fact]
    public void DefaultsHoldTheHangingStrandsLengthWithinHalfAPercent()
    {
        var r = CanonicalCases.Hanging(new SimulationSettings(), 60);
        Assert.True(r.LengthError < 0.005, $"length error {r.LengthError:P3}");
        Assert.True(r.Straightness < 0.01, $"straightness {r.Straightness:P3}");
    }

    [Fact]
    public void TheSourcesSinglePassSchemeStretchesAHangingStrand()
    {
        // SPEC A.3 with one pass per frame and no length constraint: gravity wins over the goals.
        var one = CanonicalCases.Hanging(Config(ShapeMatchMode.Muller, 1f, 1, LengthMode.None), 60);
        var sixteen = CanonicalCases.Hanging(Config(ShapeMatchMode.Muller, 1f, 16, LengthMode.None), 60);
        Assert.True(one.LengthError > 1.0, $"length error {one.LengthError:P1}");
        Assert.True(sixteen.LengthError < one.LengthError / 20, $"16 substeps: {sixteen.LengthError:P2}");
    }

    [Fact]
    public void PbdChainSettlesOnTheCatenary()
    {
        // α = 0: no bending, a pure chain of distance constraints, which is what the catenary describes.
        var r = CanonicalCases.Catenary(Config(ShapeMatchMode.Muller, 0f, 8, LengthMode.Pbd, 32), 60);
        Assert.True(r.ShapeError < 0.01, $"shape error {r.ShapeError:P2} of the length");
        Assert.True(r.LengthError < 0.01, $"length error {r.LengthError:P2}");
    }

    [Fact]
    public void PendulumSwingsWithTheAnalyticPeriod()
    {
        var r = CanonicalCases.Pendulum(Config(ShapeMatchMode.Muller, 1f, 16, LengthMode.FollowTheLeader), 60);
        Assert.True(r.Defined);
        Assert.True(r.PeriodError < 0.01, $"period {r.Period:F4} s against {r.AnalyticPeriod:F4} s");
        Assert.InRange(r.EnergyRatio, 0.0, 1.0 + 1e-6); // position projection only ever removes energy
    }

    [Fact]
    public void PendulumWithoutALengthPassHasNoPeriod() =>
        Assert.False(CanonicalCases.Pendulum(Config(ShapeMatchMode.Muller, 1f, 4, LengthMode.None), 60).Defined);

    [Fact]
    public void GuardsChangeNothingForTheDefaultsInTheReportCases()
    {
        // The report measures with the guards off; with the defaults at 60 Hz that must be the same run.
        var on = new SimulationSettings();
        var off = new SimulationSettings { Guards = false };
        Assert.Equal(CanonicalCases.Shake(off, 60), CanonicalCases.Shake(on, 60));
        Assert.Equal(CanonicalCases.CollisionSweep(off, 60), CanonicalCases.CollisionSweep(on, 60));
        Assert.Equal(CanonicalCases.Hanging(off, 60), CanonicalCases.Hanging(on, 60));
    }

    [Fact]
    public void TeleportCarriesTheHairWithoutStretch()
    {
        var r = CanonicalCases.Teleport(new SimulationSettings(), 60);
        Assert.Equal(0, r.NonFinite);
        Assert.True(r.PeakStretch < 0.1, $"peak stretch {r.PeakStretch:P1}");
    }
}
