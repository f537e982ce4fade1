using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.Intrinsics;

namespace HairSim.Fast;

/// <summary>
/// Coulomb friction of <see cref="FastCollideSystem"/> in position-based form (Macklin et al. 2014, §6.1), as
/// <see cref="CollideSystem"/> does it in double: per contact, the tangential part Δx_t of the displacement from
/// x_start (the position at the start of the substep, see <see cref="FrictionStarts"/>) to the surface point is taken back whole if |Δx_t| &lt; μs·d (static), else by
/// μk·d of its length (kinetic), from the position and (as Δx_t/h) from the velocity; then the frictionless response.
/// World-space displacement: a head moving under resting hair drags it along. The 8- and 16-lane helpers do the same
/// arithmetic in the same order (same bits). Strand chunks decline friction frames (a chunk has no rows for the start
/// positions), so those frames step system by system through <see cref="ResolveWithFriction"/>.
/// </summary>
public sealed partial class FastCollideSystem
{
    /// <summary>A frame's friction constants, in both widths. <see cref="On"/> false: the frictionless kernels, unchanged.</summary>
    private readonly struct FrictionLanes
    {
        public readonly bool On;
        public readonly Vector<float> H, MuS, MuK;
        public readonly Vector512<float> H16, MuS16, MuK16;

        public FrictionLanes(FrameContext ctx)
        {
            float muS = ctx.Settings.StaticFriction, muK = ctx.Settings.KineticFriction, h = ctx.H;
            On = muS > 0f || muK > 0f;
            H = new(h); MuS = new(muS); MuK = new(muK);
            H16 = Vector512.Create(h); MuS16 = Vector512.Create(muS); MuK16 = Vector512.Create(muK);
        }
    }

    /// <summary>|Δx_t| below this counts as no slide (avoids 0/0; Δx_t is then zero whatever is taken of it).</summary>
    private const float TinySlide = 1e-30f;

    private readonly FrictionStarts _starts = new();

    /// <summary>
    /// Every collider of the substep with friction, over strands [begin, end). The kernels take the start-of-substep
    /// positions (<see cref="FrictionStarts"/>, per particle like the world's arrays) in place of the rest positions
    /// they do not use, through the same runs of live particles as the frictionless pass (ParticleRuns).
    /// </summary>
    private void ResolveWithFriction(FrameContext ctx, int substep, HairWorld w, int begin, int end)
    {
        var colliders = ctx.CollidersAt(substep);
        float slide = ctx.Settings.ContactSlide, h = ctx.H;
        var friction = new FrictionLanes(ctx);
        var starts = _starts.Ensure(w);
        float[] sx = starts.X, sy = starts.Y, sz = starts.Z;
        // Where nothing is stored, the start is estimated from this substep's velocity: x − h·v.
        for (int s = begin; s < end; s++)
        {
            if (starts.Holds(w, ctx, substep, s)) continue;
            for (int i = w.StrandFirst[s], last = i + w.StrandParticleCount[s]; i < last; i++)
            {
                sx[i] = w.PosX[i] - h * w.VelX[i]; sy[i] = w.PosY[i] - h * w.VelY[i]; sz[i] = w.PosZ[i] - h * w.VelZ[i];
            }
        }
        for (int c = 0; c < colliders.Length; c++)
        {
            var col = colliders[c];
            if (col.Kind == ColliderKind.Ellipsoid)
            {
                var k = new EllipsoidKernel(col, slide, friction);
                ParticleRuns.ForEachLiveWide(w, begin, end, ref k, _wide, sx, sy, sz);
            }
            else if (col.Kind == ColliderKind.Plane)
            {
                var k = new PlaneKernel(col, slide, friction);
                ParticleRuns.ForEachLiveWide(w, begin, end, ref k, _wide, sx, sy, sz);
            }
            else
            {
                var k = new CapsuleKernel(col, slide, friction);
                ParticleRuns.ForEachLiveWide(w, begin, end, ref k, _wide, sx, sy, sz);
            }
        }
        // This substep's end is the next one's start.
        for (int s = begin; s < end; s++)
        {
            int first = w.StrandFirst[s], n = w.StrandParticleCount[s];
            w.PosX.AsSpan(first, n).CopyTo(sx.AsSpan(first, n));
            w.PosY.AsSpan(first, n).CopyTo(sy.AsSpan(first, n));
            w.PosZ.AsSpan(first, n).CopyTo(sz.AsSpan(first, n));
            starts.Wrote(w, ctx, substep, s);
        }
    }

    /// <summary>
    /// Stores the pushed-out positions (surface point minus the friction correction) of the hit lanes, and their
    /// velocities minus correction/h. (x, y, z) are the positions before the push-out, (wx, wy, wz) the surface points,
    /// (sx, sy, sz) the positions at the start of the substep.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void PushOutWithFriction(Vector<int> hit, Vector<float> x, Vector<float> y, Vector<float> z,
        Vector<float> wx, Vector<float> wy, Vector<float> wz, Vector<float> nx, Vector<float> ny, Vector<float> nz,
        Vector<float> depth, in FrictionLanes f, ref float px, ref float py, ref float pz, ref float vx, ref float vy, ref float vz,
        ref float sx, ref float sy, ref float sz)
    {
        var ux = Simd.Ld(ref vx, 0); var uy = Simd.Ld(ref vy, 0); var uz = Simd.Ld(ref vz, 0);
        var dx = wx - Simd.Ld(ref sx, 0); var dy = wy - Simd.Ld(ref sy, 0); var dz = wz - Simd.Ld(ref sz, 0);
        var dn = dx * nx + dy * ny + dz * nz;
        var tx = dx - dn * nx; var ty = dy - dn * ny; var tz = dz - dn * nz;
        var len = Vector.SquareRoot(tx * tx + ty * ty + tz * tz);
        var kinetic = Vector.Min(f.MuK * depth / Vector.Max(len, new Vector<float>(TinySlide)), Vector<float>.One);
        var take = Simd.Sel(Vector.LessThan(len, f.MuS * depth), Vector<float>.One, kinetic);
        tx *= take; ty *= take; tz *= take;
        Simd.St(ref px, 0, Simd.Sel(hit, wx - tx, x));
        Simd.St(ref py, 0, Simd.Sel(hit, wy - ty, y));
        Simd.St(ref pz, 0, Simd.Sel(hit, wz - tz, z));
        Simd.St(ref vx, 0, Simd.Sel(hit, ux - tx / f.H, ux));
        Simd.St(ref vy, 0, Simd.Sel(hit, uy - ty / f.H, uy));
        Simd.St(ref vz, 0, Simd.Sel(hit, uz - tz / f.H, uz));
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void PushOutWithFriction16(Vector512<float> hit, Vector512<float> x, Vector512<float> y, Vector512<float> z,
        Vector512<float> wx, Vector512<float> wy, Vector512<float> wz, Vector512<float> nx, Vector512<float> ny, Vector512<float> nz,
        Vector512<float> depth, in FrictionLanes f, ref float px, ref float py, ref float pz, ref float vx, ref float vy, ref float vz,
        ref float sx, ref float sy, ref float sz)
    {
        var ux = Vector512.LoadUnsafe(ref vx); var uy = Vector512.LoadUnsafe(ref vy); var uz = Vector512.LoadUnsafe(ref vz);
        var dx = wx - Vector512.LoadUnsafe(ref sx); var dy = wy - Vector512.LoadUnsafe(ref sy); var dz = wz - Vector512.LoadUnsafe(ref sz);
        var dn = dx * nx + dy * ny + dz * nz;
        var tx = dx - dn * nx; var ty = dy - dn * ny; var tz = dz - dn * nz;
        var len = Vector512.Sqrt(tx * tx + ty * ty + tz * tz);
        var kinetic = Vector512.Min(f.MuK16 * depth / Vector512.Max(len, Vector512.Create(TinySlide)), Vector512<float>.One);
        var take = Vector512.ConditionalSelect(Vector512.LessThan(len, f.MuS16 * depth), Vector512<float>.One, kinetic);
        tx *= take; ty *= take; tz *= take;
        Vector512.ConditionalSelect(hit, wx - tx, x).StoreUnsafe(ref px);
        Vector512.ConditionalSelect(hit, wy - ty, y).StoreUnsafe(ref py);
        Vector512.ConditionalSelect(hit, wz - tz, z).StoreUnsafe(ref pz);
        Vector512.ConditionalSelect(hit, ux - tx / f.H16, ux).StoreUnsafe(ref vx);
        Vector512.ConditionalSelect(hit, uy - ty / f.H16, uy).StoreUnsafe(ref vy);
        Vector512.ConditionalSelect(hit, uz - tz / f.H16, uz).StoreUnsafe(ref vz);
    }
}
