using System.Numerics;

namespace HairSim.Measurement;

/// <summary>What <see cref="CrossingSheets.Run"/> found: crossings measured, how many of them the upper sheet ended below the lower, the mean gap (as a share of the strand length) and non-finite values.</summary>
public readonly record struct CrossingResult(int Crossings, int Sunk, double MeanGap, int NonFinite)
{
    public double SunkShare => Crossings > 0 ? (double)Sunk / Crossings : double.NaN;
}

/// <summary>
/// Two crossing sheets of limp hair: sheet A (20 strands of 16 particles along x, 4 % of the length apart) lies on a
/// nearly flat floor; sheet B, the same strands along z, starts above A and falls onto it under 1 g. Both are pinned at
/// their roots and rest on the floor with friction. After 3 natural seconds the heights of A and B are compared where
/// each strand of B crosses each strand of A (400 crossings): without hair–hair interaction B falls into A's layer
/// and ends below it at about half the crossings; a volume that keeps layers apart leaves B above A at every one.
/// Everything scales with <c>scale</c> (1 = 25 cm strands), times with √scale (Froude), so the case is the same at any size.
/// </summary>
public static class CrossingSheets
{
    public const int Strands = 20, Particles = 16;

    public static HairScene Scene(VolumeSettings? volume, SolverPath path, float drop = 0.12f, float scale = 1f)
    {
        float length = 0.25f * scale, spacing = 0.04f * length;
        var w = new HairWorld(2, Strands, Particles);
        var points = new Vector3[Particles];
        for (int i = 0; i < Strands; i++)
        {
            float z = (i - (Strands - 1) / 2f) * spacing;
            for (int k = 0; k < Particles; k++) points[k] = new Vector3(length * k / (Particles - 1), 0.008f * length, z);
            w.SetStrand(i, points, pinned: 1);
            float x = 0.1f * length + i * spacing;
            for (int k = 0; k < Particles; k++) points[k] = new Vector3(x, drop * length, -0.48f * length + length * k / (Particles - 1));
            w.SetStrand(Strands + i, points, pinned: 1);
        }
        var settings = new SimulationSettings { Bend = BendModel.Limp, Path = path, StaticFriction = 1f, KineticFriction = 1f };
        var scene = new HairScene(w, settings);
        // A floor: the top of a wide, flat ellipsoid.
        scene.AddCollider(Collider.Ellipsoid(new Vector3(0.5f * length, -2f * length, 0f), new Vector3(20f * length, 2f * length, 20f * length)));
        if (volume != null) scene.SetComponent(volume);
        return scene;
    }

    /// <summary>Drops sheet B from <paramref name="drop"/> strand lengths above A and runs 3 s × √scale at <paramref name="hz"/>.</summary>
    public static CrossingResult Run(VolumeSettings? volume, SolverPath path, int hz, float drop = 0.12f, float scale = 1f, IThreadDispatcher? dispatcher = null)
    {
        var scene = Scene(volume, path, drop, scale);
        var sim = new HairSimulation(scene, dispatcher: dispatcher);
        int frames = (int)Math.Ceiling(3.0 * Math.Sqrt(scale) * hz);
        for (int f = 0; f < frames; f++) sim.Step(1f / hz);
        return Measure(scene.World, 0.25f * scale);
    }

    /// <summary>Heights of A and B at every crossing of a strand of B over a strand of A.</summary>
    public static CrossingResult Measure(HairWorld w, float length)
    {
        int crossings = 0, sunk = 0; double gaps = 0;
        for (int i = 0; i < Strands; i++)
            for (int j = 0; j < Strands; j++)
            {
                var a = w.GetStrandPositions(i); var b = w.GetStrandPositions(Strands + j);
                double ya = HeightAt(a, b[b.Length / 2].X, 0), yb = HeightAt(b, a[a.Length / 2].Z, 2);
                if (double.IsNaN(ya) || double.IsNaN(yb)) continue;
                crossings++; gaps += yb - ya;
                if (yb <= ya) sunk++;
            }
        return new CrossingResult(crossings, sunk, crossings > 0 ? gaps / crossings / length : double.NaN, w.CountNonFinite());
    }

    // The strand's height where its coordinate (0 = x, 2 = z) passes through `at`; NaN where it does not.
    private static double HeightAt(Vector3[] s, float at, int axis)
    {
        for (int k = 1; k < s.Length; k++)
        {
            float k0 = axis == 0 ? s[k - 1].X : s[k - 1].Z, k1 = axis == 0 ? s[k].X : s[k].Z;
            if ((k0 - at) * (k1 - at) <= 0 && k0 != k1)
            {
                float t = (at - k0) / (k1 - k0);
                return s[k - 1].Y + t * (s[k].Y - s[k - 1].Y);
            }
        }
        return double.NaN;
    }
}
