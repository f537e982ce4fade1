using System.Numerics;

namespace HairSim.Benchmarks;

/// <summary>Scenes and head motion shared by the benchmarks (the same as the CLI bench command).</summary>
internal static class BenchScenes
{
    public static HairScene Build(int strands, SolverPath path)
    {
        var g = GroomSettings.Reference();
        g.SheetCount = Math.Max(1, strands / g.StrandsPerSheet);
        return GroomBuilder.BuildScene(g, new SimulationSettings { Path = path });
    }

    /// <summary>A head shaking "no" (±40° at 1.5 Hz) while bobbing.</summary>
    public static RigidTransform Shake(float t) =>
        new(new Vector3(0, 0.03f * MathF.Sin(2 * MathF.PI * 2f * t), 0),
            Quaternion.CreateFromAxisAngle(Vector3.UnitY, 0.7f * MathF.Sin(2 * MathF.PI * 1.5f * t)));
}
