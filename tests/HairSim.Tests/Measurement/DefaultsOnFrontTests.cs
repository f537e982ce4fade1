using HairSim.Measurement;

namespace HairSim.Tests.Measurement;

/// <summary>
/// The deterministic half of "the defaults sit on the Pareto front": no configuration of the report that runs as few
/// substeps as the defaults or fewer (so costs no more per frame: run time grows with substeps, docs/error-vs-runtime.md)
/// has a smaller error. The other half, that every configuration with a smaller error is slower, is timing and is
/// checked by the report command, which exits non-zero when the defaults fall off the front.
/// </summary>
public class DefaultsOnFrontTests
{
    [Fact]
    public void NoConfigurationWithAsFewSubstepsHasASmallerError()
    {
        var defaults = SolverConfiguration.FromSettings(new SimulationSettings());
        var cheaper = ErrorReport.Configurations(quick: false).FindAll(c => c.Substeps <= defaults.Substeps && c != defaults);
        Assert.True(cheaper.Count >= 20, $"only {cheaper.Count} configurations to compare");

        double own = FrontError(defaults);
        Assert.True(double.IsFinite(own) && own > 0, $"defaults' error {own}");
        var errors = new double[cheaper.Count];
        Parallel.For(0, cheaper.Count, i => errors[i] = FrontError(cheaper[i]));
        for (int i = 0; i < cheaper.Count; i++)
            Assert.True(errors[i] > own, $"{cheaper[i].Label}: error {errors[i]:P3} is not above the defaults' {own:P3}");
    }

    /// <summary>The error the front ranks by (<see cref="ReportRow.Error"/>), without the cases it does not rank.</summary>
    private static double FrontError(SolverConfiguration c)
    {
        var s = c.ToSettings();
        s.Guards = false; // as the report: exactly this configuration
        var row = new ReportRow(c, CanonicalCases.Hanging(s, ErrorReport.Hz), default,
            CanonicalCases.Pendulum(s, ErrorReport.Hz), default, CanonicalCases.Shake(s, ErrorReport.Hz), default,
            CanonicalCases.Teleport(s, ErrorReport.Hz), HeldShapeCases.Worst(s, ErrorReport.Hz), default);
        return row.Error;
    }
}
