using System.Numerics;

namespace HairSim;

/// <summary>
/// Grows hair sheets on an ellipsoid head. Sheet centres follow a Fibonacci lattice over the scalp region
/// (even coverage without rows); each sheet is a row of strands across the scalp (along the horizontal
/// tangent), with jittered roots so no streaks show. Strands leave the scalp along its normal and, with
/// <see cref="GroomSettings.Drape"/>, are combed down over the head (kept outside it) and fall: the rest pose is a
/// hairstyle at rest. With Drape 0 they stand straight out along the normal, the source's groom.
/// </summary>
public static class GroomBuilder
{
    /// <summary>Builds the world only (head at identity).</summary>
    public static HairWorld Build(GroomSettings g)
    {
        ArgumentNullException.ThrowIfNull(g);
        g.Validate();
        var world = new HairWorld(g.SheetCount, g.StrandsPerSheet, g.ParticlesPerStrand);
        var centres = SheetCentres(g);
        var rng = new SplitMix64(g.Seed);
        float spacing = MathF.Sqrt(ScalpArea(g) / g.SheetCount);
        float sheetWidth = spacing * g.SheetWidth;
        float strandSpacing = sheetWidth / g.StrandsPerSheet;
        float segment = g.StrandLength / (g.ParticlesPerStrand - 1);
        var pts = new Vector3[g.ParticlesPerStrand];
        float headScale = g.HeadRadii.Length() / GroomSettings.Reference().HeadRadii.Length();

        for (int q = 0; q < g.SheetCount; q++)
        {
            var dir = centres[q];
            var tangent = Vector3.Cross(Vector3.UnitY, dir);
            tangent = tangent.LengthSquared() < 1e-8f ? Vector3.UnitX : Vector3.Normalize(tangent);
            var bitangent = Vector3.Cross(dir, tangent);
            for (int j = 0; j < g.StrandsPerSheet; j++)
            {
                float across = (j - (g.StrandsPerSheet - 1) * 0.5f) * strandSpacing;
                float jx = (rng.NextFloat() - 0.5f) * g.RootJitter * strandSpacing;
                float jy = (rng.NextFloat() - 0.5f) * g.RootJitter * spacing * 0.5f;
                // Offsets across the sheet against the head's size (0.1 m on the reference head), so a scaled groom is the same groom.
                var onSphere = dir * (0.1f * headScale) + tangent * (across + jx) + bitangent * jy;
                var (root, normal) = SurfacePoint(g, onSphere);
                root += normal * g.RootLift;
                Comb(g, root, normal, segment, pts);
                world.SetStrand(world.SheetFirstStrand[q] + j, pts, g.PinnedPerStrand, straightRestShape: true);
            }
        }
        return world;
    }

    /// <summary>
    /// One strand's rest points: out of the scalp along the normal for the pinned particles, then turning towards
    /// straight down at up to Drape / (mean head radius) radians per metre, pushed back outside the head (plus the root
    /// lift) wherever a step would enter it, every segment exactly <paramref name="segment"/> long.
    /// </summary>
    private static void Comb(GroomSettings g, Vector3 root, Vector3 normal, float segment, Vector3[] pts)
    {
        pts[0] = root;
        var dir = normal;
        var down = -Vector3.UnitY;
        var a = g.HeadRadii;
        float turn = g.Drape * segment * 12f / (a.X + a.Y + a.Z); // a bend radius of a quarter of the head's
        var shell = a + new Vector3(g.RootLift);
        for (int k = 1; k < pts.Length; k++)
        {
            if (k >= g.PinnedPerStrand && turn > 0f) dir = GroomBuilder.TurnTowards(dir, down, turn);
            var next = pts[k - 1] + dir * segment;
            for (int it = 0; it < 3 && turn > 0f; it++)
            {
                var local = (next - g.HeadCenter) / shell;
                float r2 = local.LengthSquared();
                if (r2 >= 1f) break;
                // Radially out onto the shell, then back to the segment length from the previous point.
                next = g.HeadCenter + (next - g.HeadCenter) / MathF.Sqrt(r2);
                dir = Vector3.Normalize(next - pts[k - 1]);
                next = pts[k - 1] + dir * segment;
            }
            pts[k] = next;
        }
    }

    /// <summary>Unit direction turned towards <paramref name="target"/> by at most <paramref name="maxAngle"/> radians (combing).</summary>
    internal static Vector3 TurnTowards(Vector3 dir, Vector3 target, float maxAngle)
    {
        float angle = MathF.Acos(Math.Clamp(Vector3.Dot(dir, target), -1f, 1f));
        if (!(angle > 1e-6f)) return dir;
        var axis = Vector3.Cross(dir, target);
        axis = axis.LengthSquared() > 1e-12f ? Vector3.Normalize(axis) : Vector3.UnitX;
        return Vector3.Normalize(Vector3.Transform(dir, Quaternion.CreateFromAxisAngle(axis, MathF.Min(maxAngle, angle))));
    }

    /// <summary>A ready scene: the groomed world, its head ellipsoid as collider, and the given settings.</summary>
    public static HairScene BuildScene(GroomSettings g, SimulationSettings? settings = null)
    {
        var world = Build(g);
        var scene = new HairScene(world, settings);
        scene.AddCollider(Collider.Ellipsoid(g.HeadCenter, g.HeadRadii));
        return scene;
    }

    /// <summary>Is a unit direction (head space) on the scalp? The allowed angle from the top shrinks towards the face (+Z).</summary>
    public static bool OnScalp(GroomSettings g, Vector3 dir)
    {
        float polar = MathF.Acos(Math.Clamp(dir.Y, -1f, 1f));
        float horiz = MathF.Sqrt(dir.X * dir.X + dir.Z * dir.Z);
        float cosAz = horiz < 1e-6f ? 1f : dir.Z / horiz; // 1 at the face, −1 at the back
        float limit = g.ScalpAngleBack + (g.ScalpAngleFront - g.ScalpAngleBack) * (cosAz + 1f) * 0.5f;
        return polar <= limit;
    }

    /// <summary>The first SheetCount Fibonacci-lattice directions that fall on the scalp.</summary>
    private static Vector3[] SheetCentres(GroomSettings g)
    {
        var result = new Vector3[g.SheetCount];
        float golden = MathF.PI * (3f - MathF.Sqrt(5f));
        for (int total = g.SheetCount; ; total = (int)Math.Min(int.MaxValue / 2, total * 1.25 + 8))
        {
            int found = 0;
            for (int i = 0; i < total && found < g.SheetCount; i++)
            {
                float y = 1f - (i + 0.5f) * 2f / total;
                float r = MathF.Sqrt(MathF.Max(0f, 1f - y * y));
                var d = new Vector3(MathF.Cos(golden * i) * r, y, MathF.Sin(golden * i) * r);
                if (OnScalp(g, d)) result[found++] = d;
            }
            if (found == g.SheetCount) return result;
        }
    }

    /// <summary>Approximate scalp area on the ellipsoid (solid-angle share of the ellipsoid area).</summary>
    private static float ScalpArea(GroomSettings g)
    {
        const int n = 2000;
        int inside = 0;
        float golden = MathF.PI * (3f - MathF.Sqrt(5f));
        for (int i = 0; i < n; i++)
        {
            float y = 1f - (i + 0.5f) * 2f / n;
            float r = MathF.Sqrt(MathF.Max(0f, 1f - y * y));
            if (OnScalp(g, new Vector3(MathF.Cos(golden * i) * r, y, MathF.Sin(golden * i) * r))) inside++;
        }
        var a = g.HeadRadii;
        // Knud Thomsen's approximation of the ellipsoid surface area.
        const double p = 1.6075;
        double area = 4 * Math.PI * Math.Pow((Math.Pow(a.X * a.Y, p) + Math.Pow(a.X * a.Z, p) + Math.Pow(a.Y * a.Z, p)) / 3, 1 / p);
        return (float)(area * inside / n);
    }

    /// <summary>Radial projection of a direction onto the head ellipsoid, with the outward surface normal.</summary>
    private static (Vector3 point, Vector3 normal) SurfacePoint(GroomSettings g, Vector3 direction)
    {
        var d = Vector3.Normalize(direction);
        var a = g.HeadRadii;
        float s = 1f / MathF.Sqrt(d.X * d.X / (a.X * a.X) + d.Y * d.Y / (a.Y * a.Y) + d.Z * d.Z / (a.Z * a.Z));
        var local = d * s;
        var normal = Vector3.Normalize(new Vector3(local.X / (a.X * a.X), local.Y / (a.Y * a.Y), local.Z / (a.Z * a.Z)));
        return (g.HeadCenter + local, normal);
    }
}

/// <summary>A small deterministic random generator (SplitMix64): same seed, same groom, on every runtime.</summary>
public struct SplitMix64
{
    private ulong _state;
    public SplitMix64(ulong seed) => _state = seed;

    public ulong Next()
    {
        ulong z = _state += 0x9E3779B97F4A7C15UL;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9UL;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBUL;
        return z ^ (z >> 31);
    }

    /// <summary>Uniform in [0, 1).</summary>
    public float NextFloat() => (Next() >> 40) * (1f / (1 << 24));
}
