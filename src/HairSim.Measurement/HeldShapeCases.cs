using System.Numerics;

namespace HairSim.Measurement;

/// <summary>The rest shapes a style must keep (issue: styles that hold).</summary>
public enum HeldShape
{
    /// <summary>Straight and horizontal from the root: the hardest case for gravity.</summary>
    Cantilever,
    /// <summary>A quarter circle rising from horizontal at the root to vertical at the tip.</summary>
    UpwardArc,
    /// <summary>A hanging helix of two turns (a curl).</summary>
    Curl,
}

/// <summary>How far a held shape ended from its rest shape, as shares of the strand length (worst of the last frames).</summary>
public readonly record struct HeldShapeResult(double TipError, double WorstError, double MaxSpeedAtRest, double LengthError, int NonFinite)
{
    public bool Finite => NonFinite == 0 && double.IsFinite(WorstError);
}

/// <summary>
/// One strand grown in a rest shape (straight horizontal, upward arc, hanging curl), released under gravity with
/// the head still, at any scale and frame rate: does it keep its shape? Times scale with √(length / 0.25 m) (Froude
/// scaling), so the same case at 1 cm and at 10 m is the same motion if the model is scale-free.
/// </summary>
public static class HeldShapeCases
{
    /// <summary>Head-space rest points of a shape of the given length (root at the origin, +x outward, +y up).</summary>
    public static Vector3[] Points(HeldShape shape, float length, int particles)
    {
        if (particles < 2) throw new ArgumentOutOfRangeException(nameof(particles), particles, "A strand needs at least 2 particles.");
        if (!(length > 0f) || !float.IsFinite(length)) throw new ArgumentOutOfRangeException(nameof(length), length, "Length must be positive and finite.");
        var pts = new Vector3[particles];
        for (int k = 0; k < particles; k++)
        {
            double u = (double)k / (particles - 1); // arc-length share
            pts[k] = shape switch
            {
                HeldShape.Cantilever => new Vector3((float)(u * length), 0f, 0f),
                HeldShape.UpwardArc => Arc(u, length),
                _ => Helix(u, length),
            };
        }
        return pts;
    }

    private static Vector3 Arc(double u, double length)
    {
        double r = 2 * length / Math.PI, phi = u * Math.PI / 2;
        return new Vector3((float)(r * Math.Sin(phi)), (float)(r * (1 - Math.Cos(phi))), 0f);
    }

    /// <summary>Two turns, radius 6 % of the length, hanging (−y); the root sits on the helix's rim.</summary>
    private static Vector3 Helix(double u, double length)
    {
        const double turns = 2, radiusShare = 0.06;
        double r = radiusShare * length;
        double perTurn = length / turns;
        double pitch = Math.Sqrt(perTurn * perTurn - (2 * Math.PI * r) * (2 * Math.PI * r));
        double a = u * turns * 2 * Math.PI;
        return new Vector3((float)(r * Math.Sin(a)), (float)(-pitch * turns * u), (float)(r * (1 - Math.Cos(a))));
    }

    /// <summary>The three shapes at one scale and rate: the worst of each figure (what the report ranks).</summary>
    public static HeldShapeResult Worst(SimulationSettings settings, int hz, float length = 0.25f, int particles = 16)
    {
        double tip = 0, worst = 0, speed = 0, stretch = 0;
        int bad = 0;
        foreach (var shape in Enum.GetValues<HeldShape>())
        {
            var r = Run(shape, length, particles, hz, settings);
            tip = Max(tip, r.TipError); worst = Max(worst, r.WorstError); speed = Max(speed, r.MaxSpeedAtRest);
            stretch = Max(stretch, r.LengthError); bad += r.NonFinite;
        }
        return new HeldShapeResult(tip, worst, speed, stretch, bad);
    }

    /// <summary>Max that keeps NaN.</summary>
    private static double Max(double a, double b) => double.IsNaN(a) || double.IsNaN(b) ? double.NaN : Math.Max(a, b);

    /// <summary>A scene with one strand of the shape, root pinned, no collider.</summary>
    public static HairScene Scene(HeldShape shape, float length, int particles, SimulationSettings settings)
    {
        var w = new HairWorld(1, 1, particles);
        w.SetStrand(0, Points(shape, length, particles), pinned: 1);
        return new HairScene(w, settings);
    }

    /// <summary>
    /// Runs the shape for <paramref name="seconds25cm"/> × √(length / 0.25 m) seconds at <paramref name="hz"/> and
    /// measures the last 10 % of frames: worst distance of the tip and of any particle from its rest place, the largest
    /// speed in the velocity buffers (as a share of √(g·length), the scale's natural speed) and the worst length drift.
    /// </summary>
    public static HeldShapeResult Run(HeldShape shape, float length, int particles, int hz, SimulationSettings settings, float seconds25cm = 3f)
    {
        var scene = Scene(shape, length, particles, settings);
        var sim = new HairSimulation(scene);
        var w = scene.World;
        float dt = 1f / hz;
        int frames = Math.Max(10, (int)Math.Ceiling(seconds25cm * Math.Sqrt(length / 0.25) * hz));
        int measureFrom = frames - Math.Max(1, frames / 10);
        double tip = 0, worst = 0, speed = 0, stretch = 0;
        int n = w.StrandParticleCount[0];
        for (int f = 0; f < frames; f++)
        {
            sim.Step(dt);
            if (f < measureFrom) continue;
            for (int k = 0; k < n; k++)
            {
                double d = Vector3.Distance(w.GetPosition(k), w.GetRest(k));
                worst = Max(worst, d);
                if (k == n - 1) tip = Max(tip, d);
                speed = Max(speed, w.GetVelocity(k).Length());
                if (k > 0) stretch = Max(stretch, Math.Abs(Vector3.Distance(w.GetPosition(k), w.GetPosition(k - 1)) / w.RestLength[k] - 1));
            }
        }
        double natural = Math.Sqrt(BendProfile.StandardGravity * length);
        int bad = w.CountNonFinite();
        return new HeldShapeResult(tip / length, worst / length, speed / natural, stretch, bad);
    }

    /// <summary>
    /// The same head shake at another size: the canonical small groom (25 cm strands on the reference head) and the
    /// head motion scaled by <paramref name="scale"/> in length and √scale in time (Froude scaling), run for 2 s × √scale
    /// at <paramref name="hz"/> frames per second; returns every live particle's position divided by the scale. A scale-free model gives
    /// the same shape at every size (the positions agree up to the frame times, which are not scaled).
    /// </summary>
    public static Vector3[] ScaledShake(float scale, double hz, SimulationSettings settings, float seconds = 2f)
    {
        if (!(scale > 0f) || !float.IsFinite(scale)) throw new ArgumentOutOfRangeException(nameof(scale), scale, "Scale must be positive and finite.");
        var g = CanonicalCases.SmallGroom();
        g.StrandLength *= scale; g.HeadRadii *= scale; g.HeadCenter *= scale; g.RootLift *= scale;
        var scene = GroomBuilder.BuildScene(g, settings);
        var sim = new HairSimulation(scene);
        var w = scene.World;
        float time = MathF.Sqrt(scale), dt = (float)(1 / hz);
        int frames = (int)Math.Round(seconds * time * hz);
        for (int f = 0; f < frames; f++)
        {
            var shake = HeadMotion.Shake((f + 1) * dt / time);
            sim.Step(dt, new RigidTransform(shake.Position * scale, shake.Rotation));
        }
        var result = new List<Vector3>();
        for (int s = 0; s < w.StrandCount; s++)
            for (int k = 0; k < w.StrandParticleCount[s]; k++) result.Add(w.GetPosition(w.StrandFirst[s] + k) / scale);
        return result.ToArray();
    }

    /// <summary>Largest distance between corresponding points of two <see cref="ScaledShake"/> runs, as a share of the 25 cm strand.</summary>
    public static double ShapeDifference(Vector3[] a, Vector3[] b)
    {
        if (a.Length != b.Length) throw new ArgumentException("The runs hold different particle counts.", nameof(b));
        double d = 0;
        for (int i = 0; i < a.Length; i++) d = Max(d, Vector3.Distance(a[i], b[i]));
        return d / CanonicalCases.StrandLength;
    }
}
