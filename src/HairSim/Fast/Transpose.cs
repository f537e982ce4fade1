using System.Runtime.CompilerServices;
using System.Runtime.Intrinsics;
using System.Runtime.Intrinsics.X86;

namespace HairSim.Fast;

/// <summary>
/// 8 × 8 float transposes with AVX shuffles: how the fast length pass turns 8 consecutive strands (particles
/// contiguous per strand) into a tile where row k holds particle k of each strand, and back. About 24 shuffles per
/// 64 floats instead of 64 scalar loads and stores. With AVX-512, 16 strands of 16 particles are transposed as one
/// 16 × 16 block in registers (<see cref="In16Wide"/>, <see cref="Out16Wide"/>).
/// The chunk transposes (and head follow's pinned rows on chunks) are compiled optimised from their first call
/// (<c>AggressiveOptimization</c>): under tiered compilation they ran as unoptimised code through a scene's first
/// second, whose frames then missed a 60 Hz budget. The systems' RunChunk methods are left tiered: marked as well, the
/// steady frames read a few per cent slower, their profile-guided optimisation lost.
/// </summary>
internal static partial class Transpose
{
    /// <summary>True when the 8 × 8 transpose is available and Vector&lt;float&gt; is 8 wide (the tile's lane count).</summary>
    public static bool Available => Avx.IsSupported && System.Numerics.Vector<float>.Count == 8;

    /// <summary>
    /// 16 strands of 16 particles (256 consecutive floats) into 16 columns of a tile with <paramref name="lanes"/> floats per row (row k = particle k of each strand).
    /// A separate, non-inlined method with constant strides: the JIT folds every row address into the load or
    /// store, and the four transposes are inlined against this method's own inlining budget, not the caller's.
    /// </summary>
    [MethodImpl(MethodImplOptions.NoInlining | MethodImplOptions.AggressiveOptimization)]
    public static void In16(ref float strands, ref float tile, int lanes)
    {
        Block8(ref strands, 16, ref tile, lanes);
        Block8(ref Unsafe.Add(ref strands, 8), 16, ref Unsafe.Add(ref tile, 8 * lanes), lanes);
        Block8(ref Unsafe.Add(ref strands, 8 * 16), 16, ref Unsafe.Add(ref tile, 8), lanes);
        Block8(ref Unsafe.Add(ref strands, 8 * 16 + 8), 16, ref Unsafe.Add(ref tile, 8 * lanes + 8), lanes);
    }

    /// <summary>
    /// <see cref="In16"/> with AVX-512: one 16 × 16 transpose in registers (64 shuffles per 256 floats instead of
    /// 96 for four 8 × 8 blocks, and 16 loads and stores of 64 bytes instead of 32 of 32 bytes).
    /// </summary>
    public static void In16Wide(ref float strands, ref float tile, int lanes) => In16Strided(ref strands, 16, ref tile, lanes);

    /// <summary>The inverse of <see cref="In16Wide"/>; with <paramref name="add"/> the tile is added to the strands.</summary>
    [MethodImpl(MethodImplOptions.NoInlining | MethodImplOptions.AggressiveOptimization)]
    public static void Out16Wide(ref float tile, int lanes, ref float strands, bool add)
    {
        Block16(ref tile, lanes, out var o0, out var o1, out var o2, out var o3, out var o4, out var o5, out var o6, out var o7,
            out var o8, out var o9, out var o10, out var o11, out var o12, out var o13, out var o14, out var o15);
        Put16(ref strands, 0, o0, add); Put16(ref strands, 16, o1, add); Put16(ref strands, 32, o2, add); Put16(ref strands, 48, o3, add);
        Put16(ref strands, 64, o4, add); Put16(ref strands, 80, o5, add); Put16(ref strands, 96, o6, add); Put16(ref strands, 112, o7, add);
        Put16(ref strands, 128, o8, add); Put16(ref strands, 144, o9, add); Put16(ref strands, 160, o10, add); Put16(ref strands, 176, o11, add);
        Put16(ref strands, 192, o12, add); Put16(ref strands, 208, o13, add); Put16(ref strands, 224, o14, add); Put16(ref strands, 240, o15, add);
    }

    /// <summary>
    /// <see cref="Out16Wide"/> without add, returning the unsigned maximum of the stored floats' <see cref="Simd.FiniteProbe"/>s:
    /// the chunk's check for NaN and ±∞ on values already in registers, instead of a pass that loads them again.
    /// </summary>
    [MethodImpl(MethodImplOptions.NoInlining | MethodImplOptions.AggressiveOptimization)]
    public static Vector512<uint> Out16WideProbed(ref float tile, int lanes, ref float strands)
    {
        Block16(ref tile, lanes, out var o0, out var o1, out var o2, out var o3, out var o4, out var o5, out var o6, out var o7,
            out var o8, out var o9, out var o10, out var o11, out var o12, out var o13, out var o14, out var o15);
        St16(ref strands, 0, o0); St16(ref strands, 16, o1); St16(ref strands, 32, o2); St16(ref strands, 48, o3);
        St16(ref strands, 64, o4); St16(ref strands, 80, o5); St16(ref strands, 96, o6); St16(ref strands, 112, o7);
        St16(ref strands, 128, o8); St16(ref strands, 144, o9); St16(ref strands, 160, o10); St16(ref strands, 176, o11);
        St16(ref strands, 192, o12); St16(ref strands, 208, o13); St16(ref strands, 224, o14); St16(ref strands, 240, o15);
        var a = Vector512.Max(Vector512.Max(Probe(o0, o1), Probe(o2, o3)), Vector512.Max(Probe(o4, o5), Probe(o6, o7)));
        var b = Vector512.Max(Vector512.Max(Probe(o8, o9), Probe(o10, o11)), Vector512.Max(Probe(o12, o13), Probe(o14, o15)));
        return Vector512.Max(a, b);
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static Vector512<uint> Probe(Vector512<float> a, Vector512<float> b) => Vector512.Max(Simd.FiniteProbe(a), Simd.FiniteProbe(b));

    /// <summary>
    /// 16 strands of capacity <paramref name="stride"/> ≤ 16, back to back, into rows (row k = particle k of each):
    /// 16 floats are read from each strand's start, so rows past the capacity hold the next strand's particles (the
    /// caller masks them) and the caller must leave 16 − stride floats readable past the last strand.
    /// </summary>
    [MethodImpl(MethodImplOptions.NoInlining | MethodImplOptions.AggressiveOptimization)]
    public static void In16Strided(ref float strands, int stride, ref float tile, int lanes)
    {
        Block16(ref strands, stride, out var o0, out var o1, out var o2, out var o3, out var o4, out var o5, out var o6, out var o7,
            out var o8, out var o9, out var o10, out var o11, out var o12, out var o13, out var o14, out var o15);
        St16(ref tile, 0, o0); St16(ref tile, lanes, o1); St16(ref tile, 2 * lanes, o2); St16(ref tile, 3 * lanes, o3);
        St16(ref tile, 4 * lanes, o4); St16(ref tile, 5 * lanes, o5); St16(ref tile, 6 * lanes, o6); St16(ref tile, 7 * lanes, o7);
        St16(ref tile, 8 * lanes, o8); St16(ref tile, 9 * lanes, o9); St16(ref tile, 10 * lanes, o10); St16(ref tile, 11 * lanes, o11);
        St16(ref tile, 12 * lanes, o12); St16(ref tile, 13 * lanes, o13); St16(ref tile, 14 * lanes, o14); St16(ref tile, 15 * lanes, o15);
    }

    /// <summary>
    /// The inverse of <see cref="In16Strided"/>: strands 0 … <paramref name="whole"/> − 1 are stored as 16 floats, in
    /// order, so what spills into strand i + 1 is overwritten by strand i + 1's own store; the rest only their first
    /// <paramref name="width"/> floats (the caller sets <paramref name="whole"/> so that no store reaches past its strands).
    /// </summary>
    [MethodImpl(MethodImplOptions.NoInlining | MethodImplOptions.AggressiveOptimization)]
    public static void Out16Strided(ref float tile, int lanes, ref float strands, int stride, int whole, int width)
    {
        Block16(ref tile, lanes, out var o0, out var o1, out var o2, out var o3, out var o4, out var o5, out var o6, out var o7,
            out var o8, out var o9, out var o10, out var o11, out var o12, out var o13, out var o14, out var o15);
        PutStrand(ref strands, 0, stride, whole, width, o0); PutStrand(ref strands, 1, stride, whole, width, o1); PutStrand(ref strands, 2, stride, whole, width, o2);
        PutStrand(ref strands, 3, stride, whole, width, o3); PutStrand(ref strands, 4, stride, whole, width, o4); PutStrand(ref strands, 5, stride, whole, width, o5);
        PutStrand(ref strands, 6, stride, whole, width, o6); PutStrand(ref strands, 7, stride, whole, width, o7); PutStrand(ref strands, 8, stride, whole, width, o8);
        PutStrand(ref strands, 9, stride, whole, width, o9); PutStrand(ref strands, 10, stride, whole, width, o10); PutStrand(ref strands, 11, stride, whole, width, o11);
        PutStrand(ref strands, 12, stride, whole, width, o12); PutStrand(ref strands, 13, stride, whole, width, o13); PutStrand(ref strands, 14, stride, whole, width, o14);
        PutStrand(ref strands, 15, stride, whole, width, o15);
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void PutStrand(ref float strands, int i, int stride, int whole, int width, Vector512<float> v)
    {
        if (i < whole) { St16(ref strands, i * stride, v); return; }
        for (int k = 0; k < width; k++) Unsafe.Add(ref strands, i * stride + k) = v.GetElement(k);
    }

    /// <summary>
    /// Rows src[i·stride … +15] (i = 0 … 15) transposed: o_j[i] = src[i·stride + j]. Unpack and shufps build 4 × 4
    /// blocks inside each 128-bit lane; two rounds of 128-bit lane shuffles put the blocks in place.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Block16(ref float src, int stride,
        out Vector512<float> o0, out Vector512<float> o1, out Vector512<float> o2, out Vector512<float> o3,
        out Vector512<float> o4, out Vector512<float> o5, out Vector512<float> o6, out Vector512<float> o7,
        out Vector512<float> o8, out Vector512<float> o9, out Vector512<float> o10, out Vector512<float> o11,
        out Vector512<float> o12, out Vector512<float> o13, out Vector512<float> o14, out Vector512<float> o15)
    {
        // Rows 4a … 4a+3 → u[4a + b], whose 128-bit lane k holds column 4k + b of those rows.
        Quad(ref src, stride, 0, out var u0, out var u1, out var u2, out var u3);
        Quad(ref src, stride, 4, out var u4, out var u5, out var u6, out var u7);
        Quad(ref src, stride, 8, out var u8, out var u9, out var u10, out var u11);
        Quad(ref src, stride, 12, out var u12, out var u13, out var u14, out var u15);
        Lanes(u0, u4, u8, u12, out o0, out o4, out o8, out o12);
        Lanes(u1, u5, u9, u13, out o1, out o5, out o9, out o13);
        Lanes(u2, u6, u10, u14, out o2, out o6, out o10, out o14);
        Lanes(u3, u7, u11, u15, out o3, out o7, out o11, out o15);
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Quad(ref float src, int stride, int row, out Vector512<float> u0, out Vector512<float> u1, out Vector512<float> u2, out Vector512<float> u3)
    {
        var r0 = Ld16(ref src, row * stride); var r1 = Ld16(ref src, (row + 1) * stride);
        var r2 = Ld16(ref src, (row + 2) * stride); var r3 = Ld16(ref src, (row + 3) * stride);
        var t0 = Avx512F.UnpackLow(r0, r1); var t1 = Avx512F.UnpackHigh(r0, r1);
        var t2 = Avx512F.UnpackLow(r2, r3); var t3 = Avx512F.UnpackHigh(r2, r3);
        u0 = Avx512F.Shuffle(t0, t2, 0x44); u1 = Avx512F.Shuffle(t0, t2, 0xEE);
        u2 = Avx512F.Shuffle(t1, t3, 0x44); u3 = Avx512F.Shuffle(t1, t3, 0xEE);
    }

    /// <summary>From u[b], u[4+b], u[8+b], u[12+b]: columns b, 4+b, 8+b, 12+b, all 16 rows.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Lanes(Vector512<float> a, Vector512<float> b, Vector512<float> c, Vector512<float> d,
        out Vector512<float> col0, out Vector512<float> col4, out Vector512<float> col8, out Vector512<float> col12)
    {
        var p0 = Avx512F.Shuffle4x128(a, b, 0x88); var p1 = Avx512F.Shuffle4x128(a, b, 0xDD);
        var q0 = Avx512F.Shuffle4x128(c, d, 0x88); var q1 = Avx512F.Shuffle4x128(c, d, 0xDD);
        col0 = Avx512F.Shuffle4x128(p0, q0, 0x88); col8 = Avx512F.Shuffle4x128(p0, q0, 0xDD);
        col4 = Avx512F.Shuffle4x128(p1, q1, 0x88); col12 = Avx512F.Shuffle4x128(p1, q1, 0xDD);
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Put16(ref float r, int i, Vector512<float> v, bool add) => St16(ref r, i, add ? Avx512F.Add(Ld16(ref r, i), v) : v);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static Vector512<float> Ld16(ref float r, int i) => Vector512.LoadUnsafe(ref r, (nuint)i);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void St16(ref float r, int i, Vector512<float> v) => v.StoreUnsafe(ref r, (nuint)i);

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

    // ---- strands ⇄ tiles (FastLengthSystem, FastBendSystem) ----

    /// <summary>Strand l's particles (rows of length <paramref name="rows"/> from <paramref name="first"/>) into tile column l, 8 strands at a time.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    internal static void StrandsIn(float[] src, int first, int rows, scoped StrandScratch t, int field, int lanes)
    {
        ref float d = ref t.Data[t.Offset(field)];
        if (rows == 16)
        {
            // The common strand length: constant strides let the JIT fold every row address into the instruction.
            // A 32-lane tile exists only with AVX-512, which transposes 16 × 16 in registers.
            if (lanes == 32) for (int g = 0; g < lanes; g += 16) In16Wide(ref Simd.At(src, first + g * 16), ref Unsafe.Add(ref d, g), lanes);
            else for (int g = 0; g < lanes; g += 16) In16(ref Simd.At(src, first + g * 16), ref Unsafe.Add(ref d, g), lanes);
            return;
        }
        for (int g = 0; g < lanes; g += 8)
        {
            ref float s = ref Simd.At(src, first + g * rows);
            for (int c = 0; c < rows; c += 8) Block8(ref Unsafe.Add(ref s, c), rows, ref Unsafe.Add(ref d, c * lanes + g), lanes);
        }
    }

    /// <summary>Tile column l back to strand l's particles, 8 strands at a time; with add, added to them (velocity changes).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    internal static void StrandsOut(scoped StrandScratch t, int field, float[] dst, int first, int rows, int lanes, bool add = false)
    {
        ref float s = ref t.Data[t.Offset(field)];
        if (rows == 16)
        {
            for (int g = 0; g < lanes; g += 16)
            {
                if (lanes == 32)
                {
                    if (add) Out16Wide(ref Unsafe.Add(ref s, g), lanes, ref Simd.At(dst, first + g * 16), add: true);
                    else Out16Wide(ref Unsafe.Add(ref s, g), lanes, ref Simd.At(dst, first + g * 16), add: false);
                }
                else if (add) Out16(ref Unsafe.Add(ref s, g), lanes, ref Simd.At(dst, first + g * 16), add: true);
                else Out16(ref Unsafe.Add(ref s, g), lanes, ref Simd.At(dst, first + g * 16), add: false);
            }
            return;
        }
        for (int g = 0; g < lanes; g += 8)
        {
            ref float d = ref Simd.At(dst, first + g * rows);
            for (int c = 0; c < rows; c += 8) Block8(ref Unsafe.Add(ref s, c * lanes + g), lanes, ref Unsafe.Add(ref d, c), rows, add);
        }
    }
}
