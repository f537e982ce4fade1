using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using System.Runtime.Intrinsics;
using System.Runtime.Intrinsics.X86;

namespace HairSim.Fast;

/// <summary>
/// Small helpers for the fast path: unaligned Vector&lt;float&gt; loads and stores on array data without
/// bounds checks (every caller proves its range first), and lane masks.
/// </summary>
internal static class Simd
{
    public static int Width => Vector<float>.Count;

    /// <summary>0, 1, …, Width − 1 as ints: lane indices for range masks.</summary>
    public static readonly Vector<int> Lane = MakeLane();

    private static Vector<int> MakeLane()
    {
        Span<int> l = stackalloc int[Vector<int>.Count];
        for (int i = 0; i < l.Length; i++) l[i] = i;
        return new Vector<int>(l);
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static ref float At(float[] a, int i) => ref Unsafe.Add(ref MemoryMarshal.GetArrayDataReference(a), i);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector<float> Ld(ref float r, int i) =>
        Unsafe.ReadUnaligned<Vector<float>>(ref Unsafe.As<float, byte>(ref Unsafe.Add(ref r, i)));

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void St(ref float r, int i, Vector<float> v) =>
        Unsafe.WriteUnaligned(ref Unsafe.As<float, byte>(ref Unsafe.Add(ref r, i)), v);

    /// <summary>As <see cref="Ld(ref float, int)"/> with a native-sized index (no sign extension in a hot loop's addressing).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector<float> Ld(ref float r, nuint i) =>
        Unsafe.ReadUnaligned<Vector<float>>(ref Unsafe.As<float, byte>(ref Unsafe.Add(ref r, i)));

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void St(ref float r, nuint i, Vector<float> v) =>
        Unsafe.WriteUnaligned(ref Unsafe.As<float, byte>(ref Unsafe.Add(ref r, i)), v);

    /// <summary>
    /// A float's bits shifted left by one (the sign dropped): as an unsigned integer, at least 0xFF000000 exactly when
    /// the float is NaN or ±∞ (all exponent bits set). The unsigned maximum of these over many values says whether all
    /// were finite (<see cref="AllFinite"/>): two integer operations per vector and no long dependency chain.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector512<uint> FiniteProbe(Vector512<float> v) => v.AsUInt32() << 1;

    /// <summary><see cref="FiniteProbe(Vector512{float})"/> on 8-lane vectors.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector<uint> FiniteProbe(Vector<float> v) => Vector.AsVectorUInt32(v) << 1;

    /// <summary>
    /// Whether |x|, |y| and |z| are at most the bound whose <see cref="FiniteProbe"/> is <paramref name="boundProbe"/>, in
    /// every lane (false for NaN): the probes order magnitudes as the floats do, so an integer maximum and one compare
    /// decide what three squares and their sum would (see <see cref="SpeedBound"/>).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static bool AllWithin(Vector512<float> x, Vector512<float> y, Vector512<float> z, Vector512<uint> boundProbe) =>
        Vector512.LessThanOrEqualAll(Vector512.Max(Vector512.Max(FiniteProbe(x), FiniteProbe(y)), FiniteProbe(z)), boundProbe);

    /// <summary><see cref="AllWithin(Vector512{float}, Vector512{float}, Vector512{float}, Vector512{uint})"/> on 8-lane vectors.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static bool AllWithin(Vector<float> x, Vector<float> y, Vector<float> z, Vector<uint> boundProbe) =>
        Vector.LessThanOrEqualAll(Vector.Max(Vector.Max(FiniteProbe(x), FiniteProbe(y)), FiniteProbe(z)), boundProbe);

    /// <summary>
    /// The <see cref="FiniteProbe"/> of a per-component bound under which no velocity can be over the speed limit
    /// <paramref name="maxSpeed"/> (+∞ when off): 0.57 · limit, so three squares and their sum stay below the limit's square
    /// (3 · 0.57² ≈ 0.975, with room for the roundings). A speed check that passes it skips its squares; one that does not
    /// takes the exact test, so the bits are those of the exact test alone.
    /// </summary>
    public static uint SpeedBound(float maxSpeed) => BitConverter.SingleToUInt32Bits(0.57f * maxSpeed) << 1;

    /// <summary>Whether every value whose <see cref="FiniteProbe"/> went into the maximum <paramref name="probes"/> was finite.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static bool AllFinite(Vector512<uint> probes) => Vector512.LessThanAll(probes, Vector512.Create(0xFF000000u));

    /// <summary>
    /// 1/√x for x &gt; 0: the hardware estimate (12 bits) refined by one Newton step (≈ 23 bits, an ulp or two,
    /// about the rounding of a sqrt and a divide together), much cheaper than both; exact sqrt + divide elsewhere.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector<float> InvSqrt(Vector<float> x)
    {
        if (Avx.IsSupported && Vector<float>.Count == 8)
        {
            return NewtonStep(x, Avx.ReciprocalSqrt(x.AsVector256()).AsVector());
        }
        return Vector<float>.One / Vector.SquareRoot(x);
    }

    /// <summary>
    /// <see cref="InvSqrt"/> on 16 lanes (AVX-512 with AVX): the AVX estimate of each 8-lane half and the same Newton
    /// step, so every lane gets the bits the 8-lane code gives it (AVX-512's own estimate differs).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector512<float> InvSqrt16(Vector512<float> x)
    {
        return NewtonStep(x, Vector512.Create(Avx.ReciprocalSqrt(x.GetLower()), Avx.ReciprocalSqrt(x.GetUpper())));
    }

    /// <summary>
    /// <see cref="InvSqrt"/> from AVX-512's 14-bit estimate where the CPU has it (≈ 1 ulp after the Newton step; one
    /// instruction for 16 lanes, where AVX's estimate of two 8-lane halves takes five), else AVX's. The 8-lane form takes
    /// the 256-bit AVX-512 estimate on those CPUs, so the two forms give the same bits. Shape matching's triples use it;
    /// the length pass keeps <see cref="InvSqrt"/> (its bits, and so the scenes tested on them, unchanged).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector<float> InvSqrt14(Vector<float> x)
    {
        if (!Avx512F.VL.IsSupported || Vector<float>.Count != 8) return InvSqrt(x);
        return NewtonStep(x, Avx512F.VL.ReciprocalSqrt14(x.AsVector256()).AsVector());
    }

    /// <summary><see cref="InvSqrt14"/> on 16 lanes (AVX-512): the same estimate and Newton step, so the same bits in every lane.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector512<float> InvSqrt14x16(Vector512<float> x) => NewtonStep(x, Avx512F.ReciprocalSqrt14(x));

    /// <summary>One Newton step from an estimate y of 1/√x: y·(1.5 − 0.5·x·y²), the same order in every form above.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static Vector<float> NewtonStep(Vector<float> x, Vector<float> y) =>
        y * (new Vector<float>(1.5f) - new Vector<float>(0.5f) * x * y * y);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static Vector512<float> NewtonStep(Vector512<float> x, Vector512<float> y) =>
        y * (Vector512.Create(1.5f) - Vector512.Create(0.5f) * x * y * y);

    /// <summary>One bit per lane of a mask, lane 0 in bit 0.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static uint MaskBits(Vector<int> mask)
    {
        if (Vector<int>.Count == 8) return mask.AsVector256().ExtractMostSignificantBits();
        if (Vector<int>.Count == 4) return mask.AsVector128().ExtractMostSignificantBits();
        uint bits = 0;
        for (int l = 0; l < Vector<int>.Count && l < 32; l++) if (mask[l] != 0) bits |= 1u << l;
        return bits;
    }

    // Fused multiply-adds: one rounding instead of two and one instruction instead of two, in kernels bound by their
    // operation count. The 8- and 16-lane forms round alike, so the two paths keep giving the same bits; a CPU without
    // FMA (none that has AVX2 in practice) falls back to the two roundings.
    /// <summary>a·b + c.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector<float> MulAdd(Vector<float> a, Vector<float> b, Vector<float> c) =>
        Fma.IsSupported && Vector<float>.Count == 8 ? Fma.MultiplyAdd(a.AsVector256(), b.AsVector256(), c.AsVector256()).AsVector() : a * b + c;

    /// <summary>c − a·b.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector<float> NegMulAdd(Vector<float> a, Vector<float> b, Vector<float> c) =>
        Fma.IsSupported && Vector<float>.Count == 8 ? Fma.MultiplyAddNegated(a.AsVector256(), b.AsVector256(), c.AsVector256()).AsVector() : c - a * b;

    /// <summary>a·b − c.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector<float> MulSub(Vector<float> a, Vector<float> b, Vector<float> c) =>
        Fma.IsSupported && Vector<float>.Count == 8 ? Fma.MultiplySubtract(a.AsVector256(), b.AsVector256(), c.AsVector256()).AsVector() : a * b - c;

    /// <summary>a·b + c on 16 lanes (AVX-512).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector512<float> MulAdd(Vector512<float> a, Vector512<float> b, Vector512<float> c) => Avx512F.FusedMultiplyAdd(a, b, c);

    /// <summary>c − a·b on 16 lanes.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector512<float> NegMulAdd(Vector512<float> a, Vector512<float> b, Vector512<float> c) => Avx512F.FusedMultiplyAddNegated(a, b, c);

    /// <summary>a·b − c on 16 lanes.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector512<float> MulSub(Vector512<float> a, Vector512<float> b, Vector512<float> c) => Avx512F.FusedMultiplySubtract(a, b, c);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Vector<float> Sel(Vector<int> mask, Vector<float> ifTrue, Vector<float> ifFalse) =>
        Vector.ConditionalSelect(mask, ifTrue, ifFalse);
}

/// <summary>A head pose as a 3×3 rotation matrix plus translation, broadcast to SIMD lanes (built once per substep).</summary>
internal readonly struct PoseLanes
{
    public readonly Vector<float> M00, M01, M02, M10, M11, M12, M20, M21, M22, Tx, Ty, Tz;
    public readonly float S00, S01, S02, S10, S11, S12, S20, S21, S22, STx, STy, STz;

    public PoseLanes(in RigidTransform t) : this(t.Rotation, t.Position) { }

    public PoseLanes(Quaternion q, Vector3 p)
    {
        float xx = q.X * q.X, yy = q.Y * q.Y, zz = q.Z * q.Z;
        float xy = q.X * q.Y, xz = q.X * q.Z, yz = q.Y * q.Z, wx = q.W * q.X, wy = q.W * q.Y, wz = q.W * q.Z;
        S00 = 1f - 2f * (yy + zz); S01 = 2f * (xy - wz); S02 = 2f * (xz + wy);
        S10 = 2f * (xy + wz); S11 = 1f - 2f * (xx + zz); S12 = 2f * (yz - wx);
        S20 = 2f * (xz - wy); S21 = 2f * (yz + wx); S22 = 1f - 2f * (xx + yy);
        STx = p.X; STy = p.Y; STz = p.Z;
        M00 = new(S00); M01 = new(S01); M02 = new(S02);
        M10 = new(S10); M11 = new(S11); M12 = new(S12);
        M20 = new(S20); M21 = new(S21); M22 = new(S22);
        Tx = new(STx); Ty = new(STy); Tz = new(STz);
    }

    /// <summary>The inverse rotation (transpose) with no translation: world directions into local ones.</summary>
    public static PoseLanes InverseRotation(Quaternion q) => new(Quaternion.Conjugate(q), Vector3.Zero);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public void Point(Vector<float> x, Vector<float> y, Vector<float> z, out Vector<float> ox, out Vector<float> oy, out Vector<float> oz)
    {
        ox = M00 * x + M01 * y + M02 * z + Tx;
        oy = M10 * x + M11 * y + M12 * z + Ty;
        oz = M20 * x + M21 * y + M22 * z + Tz;
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public void Direction(Vector<float> x, Vector<float> y, Vector<float> z, out Vector<float> ox, out Vector<float> oy, out Vector<float> oz)
    {
        ox = M00 * x + M01 * y + M02 * z;
        oy = M10 * x + M11 * y + M12 * z;
        oz = M20 * x + M21 * y + M22 * z;
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public Vector3 Point(Vector3 v) => new(
        S00 * v.X + S01 * v.Y + S02 * v.Z + STx, S10 * v.X + S11 * v.Y + S12 * v.Z + STy, S20 * v.X + S21 * v.Y + S22 * v.Z + STz);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public Vector3 Direction(Vector3 v) => new(
        S00 * v.X + S01 * v.Y + S02 * v.Z, S10 * v.X + S11 * v.Y + S12 * v.Z, S20 * v.X + S21 * v.Y + S22 * v.Z);
}

/// <summary><see cref="PoseLanes"/> broadcast to 16 lanes, for the AVX-512 kernels (same arithmetic, same order).</summary>
internal readonly struct PoseLanes16
{
    public readonly Vector512<float> M00, M01, M02, M10, M11, M12, M20, M21, M22, Tx, Ty, Tz;

    public PoseLanes16(in PoseLanes p)
    {
        M00 = Vector512.Create(p.S00); M01 = Vector512.Create(p.S01); M02 = Vector512.Create(p.S02);
        M10 = Vector512.Create(p.S10); M11 = Vector512.Create(p.S11); M12 = Vector512.Create(p.S12);
        M20 = Vector512.Create(p.S20); M21 = Vector512.Create(p.S21); M22 = Vector512.Create(p.S22);
        Tx = Vector512.Create(p.STx); Ty = Vector512.Create(p.STy); Tz = Vector512.Create(p.STz);
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public void Point(Vector512<float> x, Vector512<float> y, Vector512<float> z, out Vector512<float> ox, out Vector512<float> oy, out Vector512<float> oz)
    {
        ox = M00 * x + M01 * y + M02 * z + Tx;
        oy = M10 * x + M11 * y + M12 * z + Ty;
        oz = M20 * x + M21 * y + M22 * z + Tz;
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public void Direction(Vector512<float> x, Vector512<float> y, Vector512<float> z, out Vector512<float> ox, out Vector512<float> oy, out Vector512<float> oz)
    {
        ox = M00 * x + M01 * y + M02 * z;
        oy = M10 * x + M11 * y + M12 * z;
        oz = M20 * x + M21 * y + M22 * z;
    }
}
