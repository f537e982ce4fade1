using System.Globalization;

namespace HairSim.Measurement;

/// <summary>The solver choices the error-vs-run-time report compares; everything else stays at its default.</summary>
public sealed record SolverConfiguration(ShapeMatchMode Mode, float Alpha, int Substeps, LengthMode Length, int LengthIterations = 4)
{
    /// <summary>Settings with this configuration applied on top of <paramref name="template"/> (defaults if null).</summary>
    public SimulationSettings ToSettings(SimulationSettings? template = null, SolverPath path = SolverPath.Fast)
    {
        var s = template?.Clone() ?? new SimulationSettings();
        s.Mode = Mode; s.Alpha = Alpha; s.Substeps = Substeps; s.Length = Length; s.LengthIterations = LengthIterations;
        s.Path = path;
        s.Validate();
        return s;
    }

    /// <summary>The configuration the default settings describe.</summary>
    public static SolverConfiguration FromSettings(SimulationSettings s) => new(s.Mode, s.Alpha, s.Substeps, s.Length, s.LengthIterations);

    public string Label => string.Create(CultureInfo.InvariantCulture,
        $"{(Mode == ShapeMatchMode.Muller ? "Müller" : "literal")} α={Alpha:0.##} ×{Substeps} {LengthLabel}");

    public string LengthLabel => Length switch
    {
        LengthMode.None => "none",
        LengthMode.FollowTheLeader => "FTL",
        _ => string.Create(CultureInfo.InvariantCulture, $"PBD×{LengthIterations}"),
    };
}
