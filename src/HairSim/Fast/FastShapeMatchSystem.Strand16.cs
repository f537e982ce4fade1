using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.Intrinsics;
using System.Runtime.Intrinsics.X86;

namespace HairSim.Fast;

/// <summary>
/// The 8-lane (AVX2) path's 16-particle strand in registers, the counterpart of the AVX-512 <see cref="Strand16"/>:
/// triples 0 … 7 and 8 … 15 in two vectors (0 and 15 do not exist and give zero goals; the loads of particles −1 and
/// 16 read the neighbouring strands and are masked out), each particle's "prev" and "next" goals taken from the
/// neighbouring lanes by cross-lane permutes, so no goal goes through memory (the goal-scratch path reloads goals
/// shifted by one slot, which the store buffer cannot forward). Same arithmetic and order as the goal-scratch path.
/// </summary>
public sealed partial class FastShapeMatchSystem
{
    /// <summary>A straight strand; returns false (nothing written) if a triple's ends coincide: the caller takes the general path.</summary>
    [MethodImpl(MethodImplOptions.NoInlining)]
    private static bool Strand16Narrow(HairWorld w, int first, in Params p)
    {
        var third = new Vector<float>(1f / 3f);
        var eps2 = new Vector<float>(1e-24f);
        // Triples 1 … 14 exist: lanes 1 … 7 of the first half, 0 … 6 of the second.
        var validA = Vector.GreaterThan(Simd.Lane, Vector<int>.Zero);
        var validB = Vector.LessThan(Simd.Lane, new Vector<int>(7));
        Half(w, first, 0, validA, third, eps2, out var okA, out var pxA, out var pyA, out var pzA, out var mxA, out var myA, out var mzA, out var nxA, out var nyA, out var nzA);
        Half(w, first, 8, validB, third, eps2, out var okB, out var pxB, out var pyB, out var pzB, out var mxB, out var myB, out var mzB, out var nxB, out var nyB, out var nzB);
        if (!Vector.EqualsAll((validA & ~okA) | (validB & ~okB), Vector<int>.Zero)) return false;
        var zero = Vector<float>.Zero;
        Apply(w, first, 0, p.FirstF, Down(pxA, pxB) + mxA + Up(zero, nxA), Down(pyA, pyB) + myA + Up(zero, nyA), Down(pzA, pzB) + mzA + Up(zero, nzA));
        Apply(w, first, 8, p.LastF, Down(pxB, zero) + mxB + Up(nxA, nxB), Down(pyB, zero) + myB + Up(nyA, nyB), Down(pzB, zero) + mzB + Up(nzA, nzB));
        return true;
    }

    /// <summary>The goals (relative to the particle each pulls) of triples k0 … k0 + 7; invalid lanes give zero.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Half(HairWorld w, int first, int k0, Vector<int> valid, Vector<float> third, Vector<float> eps2, out Vector<int> ok,
        out Vector<float> gpx, out Vector<float> gpy, out Vector<float> gpz, out Vector<float> gmx, out Vector<float> gmy, out Vector<float> gmz,
        out Vector<float> gnx, out Vector<float> gny, out Vector<float> gnz)
    {
        int k = first + k0;
        ref float px = ref Simd.At(w.PosX, 0); ref float py = ref Simd.At(w.PosY, 0); ref float pz = ref Simd.At(w.PosZ, 0);
        var bx = Simd.Ld(ref px, k); var by = Simd.Ld(ref py, k); var bz = Simd.Ld(ref pz, k);
        var ax = Simd.Ld(ref px, k - 1) - bx; var ay = Simd.Ld(ref py, k - 1) - by; var az = Simd.Ld(ref pz, k - 1) - bz;
        var cx = Simd.Ld(ref px, k + 1) - bx; var cy = Simd.Ld(ref py, k + 1) - by; var cz = Simd.Ld(ref pz, k + 1) - bz;
        var ox = (ax + cx) * third; var oy = (ay + cy) * third; var oz = (az + cz) * third;
        var ex = cx - ax; var ey = cy - ay; var ez = cz - az;
        var len2 = ex * ex + ey * ey + ez * ez;
        ok = Vector.GreaterThan(len2, eps2);
        var inv = Simd.InvSqrt14(Simd.Sel(ok, len2, Vector<float>.One));
        ex *= inv; ey *= inv; ez *= inv;
        var pa = Simd.Ld(ref Simd.At(w.ShapePrev, 0), k); var pm = Simd.Ld(ref Simd.At(w.ShapeMid, 0), k); var pn = Simd.Ld(ref Simd.At(w.ShapeNext, 0), k);
        gpx = Simd.Sel(valid, (ox - ax) + pa * ex, default); gpy = Simd.Sel(valid, (oy - ay) + pa * ey, default); gpz = Simd.Sel(valid, (oz - az) + pa * ez, default);
        gmx = Simd.Sel(valid, ox + pm * ex, default); gmy = Simd.Sel(valid, oy + pm * ey, default); gmz = Simd.Sel(valid, oz + pm * ez, default);
        gnx = Simd.Sel(valid, (ox - cx) + pn * ex, default); gny = Simd.Sel(valid, (oy - cy) + pn * ey, default); gnz = Simd.Sel(valid, (oz - cz) + pn * ez, default);
    }

    /// <summary>v += f · sum on the free particles j0 … j0 + 7.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Apply(HairWorld w, int first, int j0, Vector<float> f, Vector<float> sx, Vector<float> sy, Vector<float> sz)
    {
        int j = first + j0;
        var apply = ~Vector.Equals(Simd.Ld(ref Simd.At(w.InvMass, 0), j), Vector<float>.Zero);
        ref float vx = ref Simd.At(w.VelX, 0); ref float vy = ref Simd.At(w.VelY, 0); ref float vz = ref Simd.At(w.VelZ, 0);
        var dvx = f * sx; var dvy = f * sy; var dvz = f * sz;
        var x = Simd.Ld(ref vx, j); var y = Simd.Ld(ref vy, j); var z = Simd.Ld(ref vz, j);
        Simd.St(ref vx, j, Simd.Sel(apply, x + dvx, x));
        Simd.St(ref vy, j, Simd.Sel(apply, y + dvy, y));
        Simd.St(ref vz, j, Simd.Sel(apply, z + dvz, z));
    }

    /// <summary>Lane l ← lane l + 1 of (x, next): x1 … x7, next0.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static Vector<float> Down(Vector<float> x, Vector<float> next)
    {
        var idx = Vector256.Create(1, 2, 3, 4, 5, 6, 7, 0);
        return Avx.Blend(Avx2.PermuteVar8x32(x.AsVector256(), idx), Avx2.PermuteVar8x32(next.AsVector256(), idx), 0x80).AsVector();
    }

    /// <summary>Lane l ← lane l − 1 of (prev, x): prev7, x0 … x6.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static Vector<float> Up(Vector<float> prev, Vector<float> x)
    {
        var idx = Vector256.Create(7, 0, 1, 2, 3, 4, 5, 6);
        return Avx.Blend(Avx2.PermuteVar8x32(x.AsVector256(), idx), Avx2.PermuteVar8x32(prev.AsVector256(), idx), 0x01).AsVector();
    }
}
