using System.Runtime.CompilerServices;
using System.Runtime.Intrinsics;
using System.Runtime.Intrinsics.X86;

namespace HairSim.Fast;

/// <summary>
/// 8 × 8 float transposes with AVX shuffles: how the fast length pass turns 8 consecutive strands (particles
/// contiguous per strand) into a tile where row k holds particle k of each strand, and back. About 24 shuffles per
/// 64 floats instead of 64 scalar loads and stores.
/// </summary>
internal static class Transpose
{
    /// <summary>True when the 8 × 8 transpose is available and Vector&lt;float&gt; is 8 wide (the tile's lane count).</summary>
    public static bool Available => Avx.IsSupported && System.Numerics.Vector<float>.Count == 8;

    /// <summary>
    /// 16 strands of 16 particles (256 consecutive floats) into 16 columns of a tile with <paramref name="lanes"/> floats per row (row k = particle k of each strand).
    /// A separate, non-inlined method with constant strides: the JIT folds every row address into the load or
    /// store, and the four transposes are inlined against this method's own inlining budget, not the caller's.
    /// </summary>
    [MethodImpl(MethodImplOptions.NoInlining)]
    public static void In16(ref float strands, ref float tile, int lanes)
    {
        Block8(ref strands, 16, ref tile, lanes);
        Block8(ref Unsafe.Add(ref strands, 8), 16, ref Unsafe.Add(ref tile, 8 * lanes), lanes);
        Block8(ref Unsafe.Add(ref strands, 8 * 16), 16, ref Unsafe.Add(ref tile, 8), lanes);
        Block8(ref Unsafe.Add(ref strands, 8 * 16 + 8), 16, ref Unsafe.Add(ref tile, 8 * lanes + 8), lanes);
    }

    /// <summary>The inverse of <see cref="In16"/>; with <paramref name="add"/> the tile is added to the strands.</summary>
    [MethodImpl(MethodImplOptions.NoInlining)]
    public static void Out16(ref float tile, int lanes, ref float strands, bool add)
    {
        Block8(ref tile, lanes, ref strands, 16, add);
        Block8(ref Unsafe.Add(ref tile, 8 * lanes), lanes, ref Unsafe.Add(ref strands, 8), 16, add);
        Block8(ref Unsafe.Add(ref tile, 8), lanes, ref Unsafe.Add(ref strands, 8 * 16), 16, add);
        Block8(ref Unsafe.Add(ref tile, 8 * lanes + 8), lanes, ref Unsafe.Add(ref strands, 8 * 16 + 8), 16, add);
    }

    /// <summary>
    /// dst[j·dstStride + i] = src[i·srcStride + j] for i, j in 0 … 7, or += when <paramref name="add"/> (the length
    /// pass adds velocity changes on the way out). Callers pass a constant, so the JIT drops the unused branch.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void Block8(ref float src, int srcStride, ref float dst, int dstStride, bool add = false)
    {
        var r0 = Ld(ref src, 0); var r1 = Ld(ref src, srcStride); var r2 = Ld(ref src, 2 * srcStride); var r3 = Ld(ref src, 3 * srcStride);
        var r4 = Ld(ref src, 4 * srcStride); var r5 = Ld(ref src, 5 * srcStride); var r6 = Ld(ref src, 6 * srcStride); var r7 = Ld(ref src, 7 * srcStride);
        var t0 = Avx.UnpackLow(r0, r1); var t1 = Avx.UnpackHigh(r0, r1);
        var t2 = Avx.UnpackLow(r2, r3); var t3 = Avx.UnpackHigh(r2, r3);
        var t4 = Avx.UnpackLow(r4, r5); var t5 = Avx.UnpackHigh(r4, r5);
        var t6 = Avx.UnpackLow(r6, r7); var t7 = Avx.UnpackHigh(r6, r7);
        var u0 = Avx.Shuffle(t0, t2, 0x44); var u1 = Avx.Shuffle(t0, t2, 0xEE);
        var u2 = Avx.Shuffle(t1, t3, 0x44); var u3 = Avx.Shuffle(t1, t3, 0xEE);
        var u4 = Avx.Shuffle(t4, t6, 0x44); var u5 = Avx.Shuffle(t4, t6, 0xEE);
        var u6 = Avx.Shuffle(t5, t7, 0x44); var u7 = Avx.Shuffle(t5, t7, 0xEE);
        Put(ref dst, 0, Avx.Permute2x128(u0, u4, 0x20), add);
        Put(ref dst, dstStride, Avx.Permute2x128(u1, u5, 0x20), add);
        Put(ref dst, 2 * dstStride, Avx.Permute2x128(u2, u6, 0x20), add);
        Put(ref dst, 3 * dstStride, Avx.Permute2x128(u3, u7, 0x20), add);
        Put(ref dst, 4 * dstStride, Avx.Permute2x128(u0, u4, 0x31), add);
        Put(ref dst, 5 * dstStride, Avx.Permute2x128(u1, u5, 0x31), add);
        Put(ref dst, 6 * dstStride, Avx.Permute2x128(u2, u6, 0x31), add);
        Put(ref dst, 7 * dstStride, Avx.Permute2x128(u3, u7, 0x31), add);
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Put(ref float r, int i, Vector256<float> v, bool add) => St(ref r, i, add ? Avx.Add(Ld(ref r, i), v) : v);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static Vector256<float> Ld(ref float r, int i) =>
        Unsafe.ReadUnaligned<Vector256<float>>(ref Unsafe.As<float, byte>(ref Unsafe.Add(ref r, i)));

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void St(ref float r, int i, Vector256<float> v) =>
        Unsafe.WriteUnaligned(ref Unsafe.As<float, byte>(ref Unsafe.Add(ref r, i)), v);
}
