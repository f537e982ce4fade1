namespace HairSim;

/// <summary>
/// Segments against spheres and capsules, reference implementation in double precision. The particle test of
/// <see cref="CollideSystem"/> misses a collider thinner than a segment (a 1 cm bar under 1.7 cm segments): both ends
/// are outside while the segment between them cuts through it. For every live segment, root to tip, and every sphere
/// and capsule: the closest points of the segment and the collider's axis; if they are nearer than the radius, the
/// segment's point is pushed out along the axis-to-segment direction, the push shared by the two ends as a point on a
/// segment is (by its barycentric weight and the ends' inverse masses: a pinned end does not move), and the ends lose
/// their velocity into the collider; the segments are swept root to tip and back. Only colliders thinner than twice
/// the segment (radius below its rest length) are tested: a thicker one cannot pass between two particles, and
/// the particle test holds it (ellipsoids are heads, far thicker than a segment).
/// </summary>
public sealed class SegmentCollideSystem : IHairSystem
{
    public const string SystemName = "SegmentCollide";
    public string Name => SystemName;
    public SystemPhase Phase => SystemPhase.Substep;

    /// <summary>Whether a scene needs it: a sphere or capsule thinner than twice its longest segment.</summary>
    public static bool Needed(HairScene scene)
    {
        float longest = 0f;
        foreach (float l in scene.World.RestLength) longest = MathF.Max(longest, l);
        foreach (var c in scene.Colliders) if (c.Kind is ColliderKind.Sphere or ColliderKind.Capsule && c.Radius < longest) return true;
        return false;
    }

    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var w = scene.World;
        var colliders = ctx.CollidersAt(substep);
        for (int s = begin; s < end; s++)
        {
            int first = w.StrandFirst[s], n = w.StrandParticleCount[s];
            // Root to tip, then back: a push on one segment moves an end its neighbour shares (hair wrapped over a bar
            // touches it with two or three segments), and the way back settles those.
            for (int j = 1; j < 2 * n - 2; j++)
            {
                int k = j < n ? j : 2 * n - 1 - j;
                int i0 = first + k - 1, i1 = first + k;
                double w0 = w.InvMass[i0] != 0f ? 1 : 0, w1 = w.InvMass[i1] != 0f ? 1 : 0;
                if (w0 + w1 == 0) continue;
                double rest = w.RestLength[i1];
                foreach (var c in colliders)
                {
                    if (c.Kind is not (ColliderKind.Sphere or ColliderKind.Capsule) || !(c.Radius < rest)) continue; // planes and heads: the particle test
                    if (!Contact(w.PosX[i0], w.PosY[i0], w.PosZ[i0], w.PosX[i1], w.PosY[i1], w.PosZ[i1], c, w0, w1,
                            out double nx, out double ny, out double nz, out double push0, out double push1)) continue;
                    Push(w, i0, nx, ny, nz, push0);
                    Push(w, i1, nx, ny, nz, push1);
                }
            }
        }
    }

    private static void Push(HairWorld w, int i, double nx, double ny, double nz, double push)
    {
        if (push == 0) return;
        w.PosX[i] = (float)(w.PosX[i] + nx * push); w.PosY[i] = (float)(w.PosY[i] + ny * push); w.PosZ[i] = (float)(w.PosZ[i] + nz * push);
        double vn = w.VelX[i] * nx + w.VelY[i] * ny + w.VelZ[i] * nz;
        if (vn < 0) { w.VelX[i] = (float)(w.VelX[i] - vn * nx); w.VelY[i] = (float)(w.VelY[i] - vn * ny); w.VelZ[i] = (float)(w.VelZ[i] - vn * nz); }
    }

    /// <summary>
    /// Segment p0 → p1 against a sphere or capsule (world space): false if they do not overlap; else the outward
    /// normal and how far each end moves along it so that the segment's nearest point reaches the surface.
    /// </summary>
    public static bool Contact(double p0x, double p0y, double p0z, double p1x, double p1y, double p1z, in Collider c, double w0, double w1,
        out double nx, out double ny, out double nz, out double push0, out double push1)
    {
        nx = ny = nz = push0 = push1 = 0;
        double ax = c.Center.X, ay = c.Center.Y, az = c.Center.Z;
        double ux = p1x - p0x, uy = p1y - p0y, uz = p1z - p0z;
        double vx = c.End.X - ax, vy = c.End.Y - ay, vz = c.End.Z - az;
        if (c.Kind == ColliderKind.Sphere) vx = vy = vz = 0;
        double rx = p0x - ax, ry = p0y - ay, rz = p0z - az;
        double uu = ux * ux + uy * uy + uz * uz, vv = vx * vx + vy * vy + vz * vz;
        double uv = ux * vx + uy * vy + uz * vz, ur = ux * rx + uy * ry + uz * rz, vr = vx * rx + vy * ry + vz * rz;
        if (!(uu > 0)) return false;
        double s, t;
        if (!(vv > 1e-30))
        {
            t = 0; s = Math.Clamp(-ur / uu, 0, 1);
        }
        else
        {
            double denom = uu * vv - uv * uv;
            s = denom > 1e-30 * uu * vv ? Math.Clamp((uv * vr - ur * vv) / denom, 0, 1) : 0;
            t = (uv * s + vr) / vv;
            if (t < 0) { t = 0; s = Math.Clamp(-ur / uu, 0, 1); }
            else if (t > 1) { t = 1; s = Math.Clamp((uv - ur) / uu, 0, 1); }
        }
        double dx = rx + ux * s - vx * t, dy = ry + uy * s - vy * t, dz = rz + uz * s - vz * t;
        double dist = Math.Sqrt(dx * dx + dy * dy + dz * dz), radius = c.Radius;
        if (!(dist < radius) || !(dist > 1e-12 * radius)) return false; // on the axis: no direction to push (the particle test's fallback covers ends)
        double weight = (1 - s) * (1 - s) * w0 + s * s * w1;
        if (!(weight > 0)) return false;
        double lambda = (radius - dist) / weight;
        nx = dx / dist; ny = dy / dist; nz = dz / dist;
        push0 = lambda * (1 - s) * w0; push1 = lambda * s * w1;
        return true;
    }
}
