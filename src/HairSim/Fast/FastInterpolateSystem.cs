using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;

namespace HairSim.Fast;

/// <summary>
/// Fast <see cref="InterpolateSystem"/>: the same render strands, float SIMD across the particles of a strand
/// (lane k = particle k of the four strands the Catmull-Rom curve passes through).
/// <para>
/// Barry–Goldman's three levels of lerps are folded into four weights per point, computed once for x, y and z:
/// P = p1 + c0·(p0 − p1) + c2·(p2 − p1) + c3·(p3 − p1). The weights are the same algebra as the reference's knots
/// (t0 = 0, t1 = d01, t2 = t1 + d12, t3 = t2 + d23, u = t1 + t·d12), and working on offsets from p1 keeps rounding at
/// the scale of the gap between strands, where the reference's float form cancels when neighbours nearly coincide.
/// Lanes past a strand's live tip (a cut) take the scalar path with the reference's clamping.
/// </para>
/// </summary>
public sealed class FastInterpolateSystem : IHairSystem
{
    private const float Eps = 1e-6f; // the reference's fallback threshold on √distance
    private readonly RenderStrands _out;

    public FastInterpolateSystem(HairScene scene)
    {
        _out = new RenderStrands(scene.World, scene.Render!);
        scene.RenderOutput = _out;
    }

    public RenderStrands Output => _out;
    public string Name => InterpolateSystem.SystemName;
    public SystemPhase Phase => SystemPhase.FrameEnd;

    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var w = scene.World;
        int g = _out.StrandsPerGap, stride = _out.Stride;
        for (int q = begin; q < end; q++)
        {
            int s0 = w.SheetFirstStrand[q], ns = w.SheetStrandCount[q];
            int r = _out.SheetFirst[q];
            for (int j = 0; j < ns; j++)
            {
                int sj = s0 + j, nj = w.StrandParticleCount[sj];
                CopyStrand(w, sj, nj, _out.Points, r * stride);
                _out.Counts[r++] = nj;
                if (j == ns - 1) break;
                int nn = w.StrandParticleCount[sj + 1];
                for (int m = 1; m <= g; m++)
                {
                    float t = m / (float)(g + 1);
                    int count = (int)MathF.Round(nj + (nn - nj) * t, MidpointRounding.AwayFromZero);
                    Gap(w, sj, j > 0, j + 2 < ns, t, count, _out.Points, r * stride);
                    _out.Counts[r++] = count;
                }
            }
        }
    }

    private static void CopyStrand(HairWorld w, int s, int n, Vector3[] pts, int at)
    {
        int first = w.StrandFirst[s];
        ref Vector3 dst = ref MemoryMarshal.GetArrayDataReference(pts);
        for (int k = 0; k < n; k++)
            Unsafe.Add(ref dst, at + k) = new Vector3(w.PosX[first + k], w.PosY[first + k], w.PosZ[first + k]);
    }

    /// <summary>
    /// One render strand of <paramref name="count"/> points at <paramref name="t"/> between strand s and s + 1, with
    /// s − 1 and s + 2 as neighbours where the sheet has them (else mirrored, as the reference does).
    /// </summary>
    private static void Gap(HairWorld w, int s, bool hasPrev, bool hasNext, float t, int count, Vector3[] pts, int at)
    {
        int f1 = w.StrandFirst[s], f2 = w.StrandFirst[s + 1];
        int f0 = hasPrev ? w.StrandFirst[s - 1] : f1, f3 = hasNext ? w.StrandFirst[s + 2] : f2;
        // Particles every strand involved has live: no clamping there.
        int unclamped = Math.Min(count, Math.Min(w.StrandParticleCount[s], w.StrandParticleCount[s + 1]));
        if (hasPrev) unclamped = Math.Min(unclamped, w.StrandParticleCount[s - 1]);
        if (hasNext) unclamped = Math.Min(unclamped, w.StrandParticleCount[s + 2]);

        int width = Vector<float>.Count, k = 0;
        if (unclamped >= width)
        {
            Span<float> xs = stackalloc float[3 * Vector<float>.Count];
            ref float px = ref MemoryMarshal.GetArrayDataReference(w.PosX);
            ref float py = ref MemoryMarshal.GetArrayDataReference(w.PosY);
            ref float pz = ref MemoryMarshal.GetArrayDataReference(w.PosZ);
            var vt = new Vector<float>(t);
            var vs = new Vector<float>(1f - t);
            for (; k + width <= unclamped; k += width)
            {
                var x1 = Simd.Ld(ref px, f1 + k); var y1 = Simd.Ld(ref py, f1 + k); var z1 = Simd.Ld(ref pz, f1 + k);
                var e2x = Simd.Ld(ref px, f2 + k) - x1; var e2y = Simd.Ld(ref py, f2 + k) - y1; var e2z = Simd.Ld(ref pz, f2 + k) - z1;
                Vector<float> e0x, e0y, e0z, e3x, e3y, e3z, f3x, f3y, f3z;
                if (hasPrev) { e0x = Simd.Ld(ref px, f0 + k) - x1; e0y = Simd.Ld(ref py, f0 + k) - y1; e0z = Simd.Ld(ref pz, f0 + k) - z1; }
                else { e0x = -e2x; e0y = -e2y; e0z = -e2z; }
                if (hasNext)
                {
                    var x3 = Simd.Ld(ref px, f3 + k); var y3 = Simd.Ld(ref py, f3 + k); var z3 = Simd.Ld(ref pz, f3 + k);
                    e3x = x3 - x1; e3y = y3 - y1; e3z = z3 - z1;
                    f3x = e3x - e2x; f3y = e3y - e2y; f3z = e3z - e2z;
                }
                else { e3x = e2x + e2x; e3y = e2y + e2y; e3z = e2z + e2z; f3x = e2x; f3y = e2y; f3z = e2z; }

                Weights(vt, vs, e0x, e0y, e0z, e2x, e2y, e2z, f3x, f3y, f3z, out var c0, out var c2, out var c3);
                var x = x1 + c0 * e0x + c2 * e2x + c3 * e3x;
                var y = y1 + c0 * e0y + c2 * e2y + c3 * e3y;
                var z = z1 + c0 * e0z + c2 * e2z + c3 * e3z;
                StoreInterleaved(x, y, z, xs, pts, at + k);
            }
        }
        for (; k < count; k++) pts[at + k] = Point(w, s, hasPrev, hasNext, k, t);
    }

    /// <summary>√|e| (centripetal knot spacing).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static Vector<float> Knot(Vector<float> x, Vector<float> y, Vector<float> z) =>
        Vector.SquareRoot(Vector.SquareRoot(x * x + y * y + z * z));

    /// <summary>
    /// The weights of p0, p2 and p3 (p1's is 1 minus their sum) at t (s = 1 − t), from the offsets p0 − p1, p2 − p1
    /// and p3 − p2: knot spacings √|offset| with the reference's fallbacks for coincident points, then Barry–Goldman's
    /// lerps A1, A2 = s·p1 + t·p2, A3, then B1, B2, then s·B1 + t·B2, multiplied out.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Weights(Vector<float> t, Vector<float> s,
        Vector<float> e0x, Vector<float> e0y, Vector<float> e0z, Vector<float> e2x, Vector<float> e2y, Vector<float> e2z,
        Vector<float> f3x, Vector<float> f3y, Vector<float> f3z,
        out Vector<float> c0, out Vector<float> c2, out Vector<float> c3)
    {
        var d01 = Knot(e0x, e0y, e0z);
        var d12 = Knot(e2x, e2y, e2z);
        var d23 = Knot(f3x, f3y, f3z);
        var eps = new Vector<float>(Eps);
        d12 = Vector.ConditionalSelect(Vector.LessThan(d12, eps), Vector<float>.One, d12);
        d01 = Vector.ConditionalSelect(Vector.LessThan(d01, eps), d12, d01);
        d23 = Vector.ConditionalSelect(Vector.LessThan(d23, eps), d12, d23);
        var td = t * d12;
        var sd = s * d12;
        var a10 = -td / d01;              // A1's weight of p0: (t1 − u) / (t1 − t0)
        var g1 = sd / (d01 + d12);        // B1's weight of A1: (t2 − u) / (t2 − t0)
        var d2 = td / (d12 + d23);        // B2's weight of A3: (u − t1) / (t3 − t1)
        var a33 = -sd / d23;              // A3's weight of p3: (u − t2) / (t3 − t2)
        var one = Vector<float>.One;
        c0 = s * g1 * a10;
        c3 = t * d2 * a33;
        c2 = t * (s * (one - g1) + t * (one - d2)) + t * d2 * (one - a33);
    }

    /// <summary>Writes 8 (or 16) points given as x, y, z lanes into consecutive Vector3s.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void StoreInterleaved(Vector<float> x, Vector<float> y, Vector<float> z, Span<float> tmp, Vector3[] pts, int at)
    {
        int n = Vector<float>.Count;
        ref float b = ref MemoryMarshal.GetReference(tmp);
        Simd.St(ref b, 0, x); Simd.St(ref b, n, y); Simd.St(ref b, 2 * n, z);
        ref Vector3 dst = ref Unsafe.Add(ref MemoryMarshal.GetArrayDataReference(pts), at);
        for (int i = 0; i < n; i++)
            Unsafe.Add(ref dst, i) = new Vector3(Unsafe.Add(ref b, i), Unsafe.Add(ref b, n + i), Unsafe.Add(ref b, 2 * n + i));
    }

    /// <summary>One point with the reference's clamping to each strand's live tip; the same weights as the SIMD lanes.</summary>
    private static Vector3 Point(HairWorld w, int s, bool hasPrev, bool hasNext, int k, float t)
    {
        var p1 = InterpolateSystem.At(w, s, k);
        var e2 = InterpolateSystem.At(w, s + 1, k) - p1;
        var e0 = hasPrev ? InterpolateSystem.At(w, s - 1, k) - p1 : -e2;
        var e3 = hasNext ? InterpolateSystem.At(w, s + 2, k) - p1 : e2 + e2;
        var f3 = hasNext ? e3 - e2 : e2;
        // The lanes' arithmetic on broadcast vectors: the same knots, fallbacks and weights as the SIMD loop.
        Weights(new Vector<float>(t), new Vector<float>(1f - t), new(e0.X), new(e0.Y), new(e0.Z), new(e2.X), new(e2.Y), new(e2.Z),
            new(f3.X), new(f3.Y), new(f3.Z), out var c0, out var c2, out var c3);
        return p1 + c0[0] * e0 + c2[0] * e2 + c3[0] * e3;
    }
}
