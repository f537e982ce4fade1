using System.Runtime.CompilerServices;

namespace HairSim.Fast;

/// <summary>
/// Fast <see cref="SegmentCollideSystem"/>: the same closest-point test in float, strand by strand (contacts with thin
/// colliders are few, and the sweep is short). It runs on strand chunks too, reading the chunk's rows: one
/// <see cref="Segment"/> routine for both, so chunks give the bits of the world pass.
/// </summary>
public sealed class FastSegmentCollideSystem : IHairSystem, IStrandChunkSystem
{
    public string Name => SegmentCollideSystem.SystemName;
    public SystemPhase Phase => SystemPhase.Substep;

    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var w = scene.World;
        var colliders = ctx.CollidersAt(substep);
        for (int s = begin; s < end; s++)
        {
            int first = w.StrandFirst[s], n = w.StrandParticleCount[s];
            for (int j = 1; j < 2 * n - 2; j++) // root to tip and back, as the reference
            {
                int k = j < n ? j : 2 * n - 1 - j;
                int i0 = first + k - 1, i1 = first + k;
                Segment(colliders, ref w.PosX[i0], ref w.PosY[i0], ref w.PosZ[i0], ref w.VelX[i0], ref w.VelY[i0], ref w.VelZ[i0], w.InvMass[i0],
                    ref w.PosX[i1], ref w.PosY[i1], ref w.PosZ[i1], ref w.VelX[i1], ref w.VelY[i1], ref w.VelZ[i1], w.InvMass[i1], w.RestLength[i1]);
            }
        }
    }

    bool IStrandChunkSystem.SupportsChunks => FastPathInfo.Avx512;
    ChunkFields IStrandChunkSystem.ChunkNeeds => ChunkFields.RestLength;

    bool IStrandChunkSystem.RunChunk(HairScene scene, FrameContext ctx, int substep, scoped in StrandChunk chunk)
    {
        var colliders = ctx.CollidersAt(substep);
        const int L = StrandChunk.Lanes;
        ref float px = ref chunk.Row(StrandChunk.X, 0), py = ref chunk.Row(StrandChunk.Y, 0), pz = ref chunk.Row(StrandChunk.Z, 0);
        ref float vx = ref chunk.Row(StrandChunk.VelX, 0), vy = ref chunk.Row(StrandChunk.VelY, 0), vz = ref chunk.Row(StrandChunk.VelZ, 0);
        ref float m = ref chunk.Row(StrandChunk.InvMass, 0), rest = ref chunk.Row(StrandChunk.RestLength, 0);
        // Strand by strand (lane), root to tip, as the world pass does.
        for (int l = 0; l < L; l++)
            for (int j = 1; j < 2 * StrandChunk.Rows - 2; j++)
            {
                int k = j < StrandChunk.Rows ? j : 2 * StrandChunk.Rows - 1 - j;
                int r0 = (k - 1) * L + l, r1 = k * L + l;
                Segment(colliders,
                    ref Unsafe.Add(ref px, r0), ref Unsafe.Add(ref py, r0), ref Unsafe.Add(ref pz, r0),
                    ref Unsafe.Add(ref vx, r0), ref Unsafe.Add(ref vy, r0), ref Unsafe.Add(ref vz, r0), Unsafe.Add(ref m, r0),
                    ref Unsafe.Add(ref px, r1), ref Unsafe.Add(ref py, r1), ref Unsafe.Add(ref pz, r1),
                    ref Unsafe.Add(ref vx, r1), ref Unsafe.Add(ref vy, r1), ref Unsafe.Add(ref vz, r1), Unsafe.Add(ref m, r1), Unsafe.Add(ref rest, r1));
            }
        return true;
    }

    /// <summary>One segment against every sphere and capsule (see <see cref="SegmentCollideSystem.Contact"/>), in float.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Segment(ReadOnlySpan<Collider> colliders,
        ref float p0x, ref float p0y, ref float p0z, ref float v0x, ref float v0y, ref float v0z, float m0,
        ref float p1x, ref float p1y, ref float p1z, ref float v1x, ref float v1y, ref float v1z, float m1, float restLength)
    {
        float w0 = m0 != 0f ? 1f : 0f, w1 = m1 != 0f ? 1f : 0f;
        if (w0 + w1 == 0f) return;
        foreach (ref readonly var c in colliders)
        {
            if (c.Kind is not (ColliderKind.Sphere or ColliderKind.Capsule) || !(c.Radius < restLength)) continue;
            float ax = c.Center.X, ay = c.Center.Y, az = c.Center.Z;
            float ux = p1x - p0x, uy = p1y - p0y, uz = p1z - p0z;
            float vx = c.End.X - ax, vy = c.End.Y - ay, vz = c.End.Z - az;
            if (c.Kind == ColliderKind.Sphere) vx = vy = vz = 0f;
            float rx = p0x - ax, ry = p0y - ay, rz = p0z - az;
            float uu = ux * ux + uy * uy + uz * uz, vv = vx * vx + vy * vy + vz * vz;
            float uv = ux * vx + uy * vy + uz * vz, ur = ux * rx + uy * ry + uz * rz, vr = vx * rx + vy * ry + vz * rz;
            if (!(uu > 0f)) continue;
            float s, t;
            if (!(vv > 1e-30f))
            {
                t = 0f; s = Math.Clamp(-ur / uu, 0f, 1f);
            }
            else
            {
                float denom = uu * vv - uv * uv;
                s = denom > 1e-30f * uu * vv ? Math.Clamp((uv * vr - ur * vv) / denom, 0f, 1f) : 0f;
                t = (uv * s + vr) / vv;
                if (t < 0f) { t = 0f; s = Math.Clamp(-ur / uu, 0f, 1f); }
                else if (t > 1f) { t = 1f; s = Math.Clamp((uv - ur) / uu, 0f, 1f); }
            }
            float dx = rx + ux * s - vx * t, dy = ry + uy * s - vy * t, dz = rz + uz * s - vz * t;
            float dist = MathF.Sqrt(dx * dx + dy * dy + dz * dz), radius = c.Radius;
            if (!(dist < radius) || !(dist > 1e-12f * radius)) continue;
            float weight = (1f - s) * (1f - s) * w0 + s * s * w1;
            if (!(weight > 0f)) continue;
            float lambda = (radius - dist) / weight;
            float nx = dx / dist, ny = dy / dist, nz = dz / dist;
            Push(ref p0x, ref p0y, ref p0z, ref v0x, ref v0y, ref v0z, nx, ny, nz, lambda * (1f - s) * w0);
            Push(ref p1x, ref p1y, ref p1z, ref v1x, ref v1y, ref v1z, nx, ny, nz, lambda * s * w1);
        }
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Push(ref float px, ref float py, ref float pz, ref float vx, ref float vy, ref float vz, float nx, float ny, float nz, float push)
    {
        if (push == 0f) return;
        px += nx * push; py += ny * push; pz += nz * push;
        float vn = vx * nx + vy * ny + vz * nz;
        if (vn < 0f) { vx -= vn * nx; vy -= vn * ny; vz -= vn * nz; }
    }
}
