using System.Globalization;

namespace HairSim.Measurement;

/// <summary>
/// The solver choices the error-vs-run-time report compares; everything else stays at its default. Mode and Alpha
/// apply to the source's triple shape matching (<see cref="BendModel.SourceTriples"/>) only.
/// </summary>
public sealed record SolverConfiguration(ShapeMatchMode Mode, float Alpha, int Substeps, LengthMode Length, int LengthIterations = 4,
    BendModel Bend = BendModel.SourceTriples)
{
    /// <summary>Settings with this configuration applied on top of <paramref name="template"/> (defaults if null).</summary>
    public SimulationSettings ToSettings(SimulationSettings? template = null, SolverPath path = SolverPath.Fast)
    {
        var s = template?.Clone() ?? new SimulationSettings();
        s.Bend = Bend; s.Mode = Mode; s.Alpha = Alpha; s.Substeps = Substeps; s.Length = Length; s.LengthIterations = LengthIterations;
        s.Path = path;
        s.Validate();
        return s;
    }

    /// <summary>The configuration the default settings describe.</summary>
    public static SolverConfiguration FromSettings(SimulationSettings s) => new(s.Mode, s.Alpha, s.Substeps, s.Length, s.LengthIterations, s.Bend);

    /// <summary>A configuration of the default bend model (Mode and Alpha at their defaults, unused).</summary>
    public static SolverConfiguration RestShape(int substeps, LengthMode length, int iterations = 4) =>
        new(ShapeMatchMode.Muller, 1f, substeps, length, iterations, BendModel.RestShape);

    /// <summary>A configuration without bending.</summary>
    public static SolverConfiguration Limp(int substeps, LengthMode length, int iterations = 4) =>
        new(ShapeMatchMode.Muller, 1f, substeps, length, iterations, BendModel.Limp);

    public string Label => Bend switch
    {
        BendModel.RestShape => string.Create(CultureInfo.InvariantCulture, $"rest shape ×{Substeps} {LengthLabel}"),
        BendModel.Limp => string.Create(CultureInfo.InvariantCulture, $"limp ×{Substeps} {LengthLabel}"),
        _ => string.Create(CultureInfo.InvariantCulture, $"{(Mode == ShapeMatchMode.Muller ? "Müller" : "literal")} α={Alpha:0.##} ×{Substeps} {LengthLabel}"),
    };

    public string LengthLabel => Length switch
    {
        LengthMode.None => "none",
        LengthMode.FollowTheLeader => "FTL",
        _ => string.Create(CultureInfo.InvariantCulture, $"PBD×{LengthIterations}"),
    };
}
