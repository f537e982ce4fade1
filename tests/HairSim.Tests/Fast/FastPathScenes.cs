using System.Numerics;
using HairSim;

namespace HairSim.Tests.Fast;

/// <summary>Scenes for fast-vs-reference comparisons: one builder per case, each the same for both paths.</summary>
internal static class FastPathScenes
{
    public static readonly string[] Names =
    [
        "straight", "cut", "bent", "short8", "odd-lengths", "sphere", "capsule", "rotated-ellipsoid", "all-colliders",
        "literal", "length-none", "pbd", "global-shape", "speed-limit", "one-pin", "no-colliders",
        "cut-mixed",
        // The default bend model (BendModel.RestShape), on the draped groom, cut, styled, odd lengths and other length modes.
        "rest", "rest-cut", "rest-cut-mixed", "rest-short8", "rest-p12", "rest-p3", "rest-p17", "rest-p40", "rest-p64", "rest-bent", "rest-odd-lengths", "rest-soft", "rest-speed-limit", "rest-all-colliders", "rest-planes", "limp",
    ];

    /// <summary>
    /// Not in <see cref="Names"/>: "planes", the source's scheme with its strand tips sliding on a tilted plane, where
    /// float and double part by a contact response within a frame (tips land on the plane every substep); it is
    /// compared by long-run statistics instead. "rest-planes" (the default model) is in the frame-by-frame lists.
    /// </summary>
    public static readonly string[] Others = ["planes"];

    /// <summary>Scenes of the default bend model (the others run the source's triple shape matching).</summary>
    public static bool IsRestShape(string name) => name.StartsWith("rest", StringComparison.Ordinal);

    /// <summary>
    /// A small groom on the reference head, changed per case. The original cases run the source's scheme
    /// (BendModel.SourceTriples, whose systems have strand-chunk and 16-lane kernels); "rest…" cases the default
    /// bend model with default settings, and "limp" no bending at all.
    /// </summary>
    public static HairScene Build(string name, SolverPath path)
    {
        var g = new GroomSettings { SheetCount = 24, StrandsPerSheet = 6, ParticlesPerStrand = 16 };
        var st = new SimulationSettings { Path = path, Bend = IsRestShape(name) ? BendModel.RestShape : BendModel.SourceTriples };
        if (IsRestShape(name) && name != "rest") name = name.Substring("rest-".Length);
        switch (name)
        {
            case "soft": st.Sag = 0.3f; st.BendDamping = 0.1f; break;
            case "limp": st.Bend = BendModel.Limp; break;
            case "short8": g.ParticlesPerStrand = 8; break;
            case "p12": g.ParticlesPerStrand = 12; break;
            case "p3": g.ParticlesPerStrand = 3; break;
            case "p17": g.ParticlesPerStrand = 17; break;
            case "p40": g.ParticlesPerStrand = 40; break;
            case "p64": g.ParticlesPerStrand = 64; break;
            case "literal": st.Mode = ShapeMatchMode.LiteralForce; st.Alpha = 400f; break;
            case "length-none": st.Length = LengthMode.None; break;
            case "pbd": st.Length = LengthMode.Pbd; st.LengthIterations = 3; break;
            case "global-shape": st.GlobalShapeStiffness = 0.05f; break;
            case "speed-limit": st.MaxSpeed = 0.3f; break;
            case "one-pin": g.PinnedPerStrand = 1; break;
        }
        HairScene scene;
        if (name == "odd-lengths") scene = OddLengths(st);
        else scene = GroomBuilder.BuildScene(g, st);
        var w = scene.World;
        switch (name)
        {
            case "cut":
                // Cuts leave 2 … 15 live particles per strand (a deterministic spread).
                for (int s = 0; s < w.StrandCount; s++) w.StrandParticleCount[s] = 2 + (s * 7) % 14;
                w.MarkEdited();
                break;
            case "cut-mixed":
                // Runs of long strands of equal live length broken by short ones (padded path), and a second length:
                // the fast shape match reuses zeroed goal slots between equal lengths and must reset after a short strand.
                for (int s = 0; s < w.StrandCount; s++) w.StrandParticleCount[s] = s % 8 == 7 ? 5 : s % 24 < 12 ? 16 : 12;
                w.MarkEdited();
                break;
            case "bent":
                Bend(w);
                break;
            case "sphere":
                scene.ClearColliders();
                scene.AddCollider(Collider.Sphere(new Vector3(0, 0.02f, 0), 0.1f));
                break;
            case "capsule":
                scene.ClearColliders();
                scene.AddCollider(Collider.Capsule(new Vector3(-0.06f, 0, 0), new Vector3(0.06f, 0.01f, 0.02f), 0.09f));
                break;
            case "rotated-ellipsoid":
                scene.ClearColliders();
                scene.AddCollider(Collider.Ellipsoid(new Vector3(0, 0.005f, 0), new Vector3(0.08f, 0.102f, 0.096f),
                    Quaternion.CreateFromYawPitchRoll(0.3f, 0.2f, -0.1f)));
                break;
            case "all-colliders":
                scene.AddCollider(Collider.Sphere(new Vector3(0, -0.12f, 0.05f), 0.06f));
                scene.AddCollider(Collider.Capsule(new Vector3(0, -0.15f, -0.02f), new Vector3(0, -0.3f, -0.03f), 0.05f));
                scene.AddCollider(Collider.Capsule(new Vector3(0.1f, -0.1f, 0), new Vector3(0.1f, -0.1f, 0), 0.04f));
                break;
            case "no-colliders":
                scene.ClearColliders();
                break;
            case "planes":
                // A tilted plane on the head that cuts through the hanging hair, and a floor fixed in the world under it.
                scene.AddCollider(Collider.Plane(new Vector3(0.02f, -0.2f, 0f), new Vector3(0.3f, 1f, 0.2f)));
                scene.AddCollider(Collider.Plane(new Vector3(0f, -0.23f, 0f), Vector3.UnitY).InWorldSpace());
                break;
        }
        return scene;
    }

    /// <summary>Strands of many capacities (2 … 33) and live counts, so every chunk and tail shape is hit.</summary>
    private static HairScene OddLengths(SimulationSettings st)
    {
        int[] caps = [2, 3, 4, 5, 7, 8, 9, 10, 11, 12, 15, 16, 17, 23, 24, 25, 33];
        int perSheet = 6;
        var strands = new int[caps.Length * perSheet];
        for (int i = 0; i < strands.Length; i++) strands[i] = caps[i % caps.Length];
        var sheets = new int[caps.Length];
        Array.Fill(sheets, perSheet);
        var w = new HairWorld(sheets, strands);
        for (int s = 0; s < w.StrandCount; s++)
        {
            int n = w.StrandCapacity[s];
            var dir = Vector3.Normalize(new Vector3(MathF.Sin(s * 0.7f), 1.2f, MathF.Cos(s * 0.7f)));
            var root = new Vector3(0.08f * dir.X, 0.1f * dir.Y, 0.095f * dir.Z) * 1.02f;
            var pts = new Vector3[n];
            for (int k = 0; k < n; k++) pts[k] = root + dir * (0.012f * k) + new Vector3(0, 0, 0.002f * MathF.Sin(k));
            w.SetStrand(s, pts, pinned: Math.Min(2, n - 1), straightRestShape: s % 2 == 0);
            if (n > 4 && s % 3 == 0) w.StrandParticleCount[s] = n - 2;
        }
        var scene = new HairScene(w, st);
        scene.AddCollider(Collider.Ellipsoid(Vector3.Zero, new Vector3(0.078f, 0.1f, 0.095f)));
        return scene;
    }

    /// <summary>Curls every strand's rest pose (a styled groom): rest shapes get ShapeBend ≠ 0.</summary>
    private static void Bend(HairWorld w)
    {
        for (int s = 0; s < w.StrandCount; s++)
        {
            int n = w.StrandParticleCount[s], first = w.StrandFirst[s];
            var root = w.GetRest(first);
            var dir = Vector3.Normalize(w.GetRest(first + 1) - root);
            var side = Vector3.Normalize(Vector3.Cross(dir, Vector3.UnitY + new Vector3(0.1f, 0, 0.2f)));
            var pts = new Vector3[n];
            float step = 0.016f;
            for (int k = 0; k < n; k++)
            {
                float a = 0.5f * k;
                pts[k] = root + dir * (step * k) + side * (0.01f * (1 - MathF.Cos(a)));
            }
            w.SetStrand(s, pts, pinned: 2);
        }
    }

    public const int TeleportFrame = 6;

    /// <summary>A head shaking and bobbing; at <see cref="TeleportFrame"/> it jumps far enough to count as a teleport.</summary>
    public static RigidTransform HeadAt(int frame, bool teleport = true)
    {
        float t = frame / 60f;
        var shift = teleport && frame >= TeleportFrame ? new Vector3(1.6f, 0, 0) : Vector3.Zero; // over twice any scene's reach
        var shake = HairSim.Measurement.HeadMotion.Shake(t);
        return new RigidTransform(shift + shake.Position, shake.Rotation);
    }

    public static float MaxPositionDifference(HairWorld a, HairWorld b) => MaxDifference(a, b, static (w, i) => w.GetPosition(i));

    public static float MaxVelocityDifference(HairWorld a, HairWorld b) => MaxDifference(a, b, static (w, i) => w.GetVelocity(i));

    /// <summary>Largest distance between a's and b's value of one per-particle vector over a's live particles.</summary>
    private static float MaxDifference(HairWorld a, HairWorld b, Func<HairWorld, int, Vector3> value)
    {
        float max = 0f;
        for (int s = 0; s < a.StrandCount; s++)
        {
            int first = a.StrandFirst[s];
            for (int i = first; i < first + a.StrandParticleCount[s]; i++)
                max = MathF.Max(max, Vector3.Distance(value(a, i), value(b, i)));
        }
        return max;
    }

    /// <summary>Root-mean-square position difference over live particles.</summary>
    public static double RmsPositionDifference(HairWorld a, HairWorld b)
    {
        double sum = 0;
        int count = 0;
        for (int s = 0; s < a.StrandCount; s++)
        {
            int first = a.StrandFirst[s];
            for (int i = first; i < first + a.StrandParticleCount[s]; i++, count++)
                sum += Vector3.DistanceSquared(a.GetPosition(i), b.GetPosition(i));
        }
        return Math.Sqrt(sum / Math.Max(1, count));
    }

    /// <summary>Mean position of the live particles (where the hair mass is).</summary>
    public static Vector3 Centroid(HairWorld w)
    {
        var sum = Vector3.Zero;
        int count = 0;
        for (int s = 0; s < w.StrandCount; s++)
        {
            int first = w.StrandFirst[s];
            for (int i = first; i < first + w.StrandParticleCount[s]; i++, count++) sum += w.GetPosition(i);
        }
        return sum / Math.Max(1, count);
    }

}
