using System.Reflection;
using HairSim.Measurement;

namespace HairSim.Tests.Measurement;

public class StabilityGuardsTests
{
    private static SimulationSettings Guarded(SimulationSettings requested, float dt, float move = 0f, float angle = 0f, bool teleported = false)
    {
        var effective = new SimulationSettings();
        StabilityGuards.Apply(requested, effective, dt, move, angle, teleported, 0.35f);
        return effective;
    }

    [Fact]
    public void MullerAlphaAboveOneIsClampedOnlyWithGuards()
    {
        const BendModel source = BendModel.SourceTriples;
        Assert.Equal(1f, Guarded(new SimulationSettings { Bend = source, Alpha = 3f }, 1 / 60f).Alpha);
        Assert.Equal(3f, Guarded(new SimulationSettings { Bend = source, Alpha = 3f, Guards = false }, 1 / 60f).Alpha);
        Assert.Equal(0.5f, Guarded(new SimulationSettings { Bend = source, Alpha = 0.5f }, 1 / 60f).Alpha);
        // The literal force's α is a spring rate (1/s²), not a per-step share: not clamped.
        Assert.Equal(500f, Guarded(new SimulationSettings { Bend = source, Alpha = 500f, Mode = ShapeMatchMode.LiteralForce }, 1 / 60f).Alpha);
        // α belongs to the source's triples: under any other bend model no triple goal pulls, guards or not.
        Assert.Equal(0f, Guarded(new SimulationSettings { Alpha = 0.5f }, 1 / 60f).Alpha);
        Assert.Equal(0f, Guarded(new SimulationSettings { Bend = BendModel.Limp, Alpha = 0.5f, Guards = false }, 1 / 60f).Alpha);
    }

    [Fact]
    public void SmallHairGetsSubstepsShortEnoughForItsSegments()
    {
        // Gravity may move a particle at most 5 % of the mean segment (h²·g ≤ 0.05·ℓ): a doll's 1 cm strand of 16
        // particles (ℓ = 0.67 mm) needs h ≤ 1.84 ms, 10 substeps at 60 Hz; a person's 25 cm strand (ℓ = 16.7 mm) h ≤ 9.2 ms,
        // which the default 4 substeps already meet; a 10 m creature needs none more.
        var effective = new SimulationSettings();
        float Segment(float length) => length / 15f;
        int Substeps(float length, float dt)
        {
            StabilityGuards.Apply(new SimulationSettings(), effective, dt, 0f, 0f, false, length, Segment(length));
            return effective.Substeps;
        }
        double g = new SimulationSettings().Gravity.Length();
        Assert.Equal((int)Math.Ceiling((1 / 60.0) / Math.Sqrt(0.05 * Segment(0.01f) / g)), Substeps(0.01f, 1 / 60f));
        Assert.Equal(10, Substeps(0.01f, 1 / 60f));
        Assert.Equal(4, Substeps(0.25f, 1 / 60f));
        Assert.Equal(4, Substeps(10f, 1 / 60f));
        StabilityGuards.Apply(new SimulationSettings { Guards = false }, effective, 1 / 60f, 0f, 0f, false, 0.01f, Segment(0.01f));
        Assert.Equal(4, effective.Substeps);
        StabilityGuards.Apply(new SimulationSettings { MaxFallPerSubstep = 0f }, effective, 1 / 60f, 0f, 0f, false, 0.01f, Segment(0.01f));
        Assert.Equal(4, effective.Substeps);
    }

    [Fact]
    public void LongFramesGetMoreSubstepsSoTheSubstepStaysShort()
    {
        // Default limit 1/60 s: 4 substeps are enough down to 15 Hz, one substep only at 60 Hz and above.
        Assert.Equal(4, Guarded(new SimulationSettings(), 1 / 15f).Substeps);
        Assert.Equal(1, Guarded(new SimulationSettings { Substeps = 1 }, 1 / 60f).Substeps);
        Assert.Equal(4, Guarded(new SimulationSettings { Substeps = 1 }, 1 / 15f).Substeps);
        Assert.Equal(16, Guarded(new SimulationSettings { MaxSubstep = 1 / 240f }, 1 / 15f).Substeps);
        Assert.Equal(8, Guarded(new SimulationSettings { Substeps = 8 }, 1 / 15f).Substeps);
        Assert.Equal(1, Guarded(new SimulationSettings { Substeps = 1, Guards = false }, 1 / 15f).Substeps);
        Assert.Equal(60, Guarded(new SimulationSettings(), 1f).Substeps);
        Assert.Equal(StabilityGuards.MaxSubsteps, Guarded(new SimulationSettings(), 1 / 60f, 100f).Substeps);
    }

    [Fact]
    public void FastHeadMovesGetMoreSubstepsButTeleportsDoNot()
    {
        // 0.3 m + 0.5 rad × 0.35 m reach = 0.475 m of travel at 2 cm per substep.
        Assert.Equal(24, Guarded(new SimulationSettings(), 1 / 60f, 0.3f, 0.5f).Substeps);
        Assert.Equal(4, Guarded(new SimulationSettings(), 1 / 60f, 0.3f, 0.5f, teleported: true).Substeps);
    }

    [Fact]
    public void PipelineRunsTheGuardedSubsteps()
    {
        var scene = GroomBuilder.BuildScene(CanonicalCases.SmallGroom(8, 2, 1), new SimulationSettings { MaxSubstep = 1 / 240f });
        var sim = new HairSimulation(scene);
        sim.Step(1 / 15f);
        Assert.Equal(16, sim.Pipeline.LastFrame.Substeps);
        Assert.Equal(1 / 240f, sim.Pipeline.LastFrame.H, 6);
        Assert.Equal(4, scene.Settings.Substeps); // the user's settings are left alone
    }

    [Fact]
    public void CopyToCopiesEverySetting()
    {
        var source = new SimulationSettings();
        var target = new SimulationSettings();
        var props = typeof(SimulationSettings).GetProperties(BindingFlags.Public | BindingFlags.Instance);
        foreach (var p in props)
        {
            object value = p.PropertyType == typeof(float) ? 0.123f
                : p.PropertyType == typeof(int) ? 7
                : p.PropertyType == typeof(bool) ? !(bool)p.GetValue(source)!
                : p.PropertyType == typeof(System.Numerics.Vector3) ? new System.Numerics.Vector3(1, 2, 3)
                : p.PropertyType.IsEnum ? Enum.GetValues(p.PropertyType).GetValue(1)!
                : throw new InvalidOperationException($"CopyToCopiesEverySetting does not know how to vary {p.PropertyType} {p.Name}.");
            p.SetValue(source, value);
        }
        source.CopyTo(target);
        foreach (var p in props) Assert.True(Equals(p.GetValue(source), p.GetValue(target)), $"{p.Name} was not copied");
    }

    [Fact]
    public void AlphaClampStopsTheSourcesSchemeFromOscillating()
    {
        // Müller α = 4 with one substep overshoots every goal: without the guard the hair never calms down.
        var s = new SimulationSettings { Bend = BendModel.SourceTriples, Alpha = 4f, Substeps = 1, Length = LengthMode.None, MaxSubstep = 0f, Guards = false };
        var unguarded = StabilityMap.Run(s, 1 / 60f, 16, StabilityScenario.Shake, sheets: 3);
        s.Guards = true;
        var guarded = StabilityMap.Run(s, 1 / 60f, 16, StabilityScenario.Shake, sheets: 3);
        Assert.False(unguarded.EnergyDecays);
        Assert.True(guarded.Finite && guarded.EnergyDecays && guarded.MaxInside == 0);
    }

    [Fact]
    public void HeadTravelGuardKeepsANearTeleportFromTearingTheHair()
    {
        // At 15 Hz, with the substep-length guards off so only the head-travel guard differs; the source's scheme,
        // whose length pass runs before collision (the default bend sweep is inextensible by itself).
        var unguarded = StabilityMap.Run(new SimulationSettings { Bend = BendModel.SourceTriples, Guards = false, MaxSubstep = 0f, MaxFallPerSubstep = 0f }, 1 / 15f, 16, StabilityScenario.NearTeleport);
        var guarded = StabilityMap.Run(new SimulationSettings { Bend = BendModel.SourceTriples, MaxSubstep = 0f, MaxFallPerSubstep = 0f }, 1 / 15f, 16, StabilityScenario.NearTeleport);
        Assert.True(unguarded.WorstElongation >= StabilityResult.StretchLimit, $"unguarded {unguarded.WorstElongation:P1}");
        Assert.True(guarded.Stable, $"guarded {guarded.WorstElongation:P1}, inside {guarded.MaxInside}");
    }
}
