using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.Intrinsics;
using System.Runtime.Intrinsics.X86;

namespace HairSim.Fast;

/// <summary>
/// The 16-lane (AVX-512) path of <see cref="FastShapeMatchSystem"/> for the common case: straight rest shape, no
/// global stiffness, at least 16 particles. A 16-particle strand is one chunk of triples, entirely in registers
/// (<see cref="Strand16"/>). Longer strands go through goal scratch: triple chunks start at 1, 17, … and may read up to
/// 16 particles past the strand (another strand's data, possibly being written by another thread); those lanes are
/// masked out and their goals stored as zero, so every goal slot a particle reads is either a real goal or zero and
/// the sums need no masks. Velocity stores never leave the strand (the last particle chunk overlaps the previous
/// one instead). Bent strands, short strands, the world's last strands (no room to read past) and α = 0 or β &gt; 0
/// take the 8-lane path.
/// </summary>
public sealed partial class FastShapeMatchSystem
{
    private const int Wide = 16;

    private static bool WideAvailable => FastPathInfo.Avx512;

    [SkipLocalsInit]
    [MethodImpl(MethodImplOptions.NoInlining)]
    private void RunWide(HairWorld w, int begin, int end, in Params p)
    {
        // Goal fields GPx … GNz in a StrandScratch whose stride leaves room for slots −1 … capacity + 15.
        int cap = _maxCapacity + Wide;
        int size = StrandScratch.Size(cap, 9);
        var scratch = new StrandScratch(size <= StrandScratch.StackFloats ? stackalloc float[size] : StrandScratch.Heap(size), cap);
        ref float g = ref scratch.Data[0];
        nint o = scratch.Offset(0), st = scratch.Stride;
        // Slots −1 and 0 are read (the root's missing goals) but never written by a triple chunk: zero them once.
        for (int f = 0; f < 9; f++) { Unsafe.Add(ref g, o + f * st - 1) = 0f; Unsafe.Add(ref g, o + f * st) = 0f; }

        var third = Vector512.Create(1f / 3f);
        var eps2 = Vector512.Create(1e-24f);
        var fOne = Vector512.Create(p.F.GetElement(0)); var fHalf = Vector512.Create(p.FHalf.GetElement(0)); var fThird = Vector512.Create(p.FThird.GetElement(0));
        var lane = Vector512.Create(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
        int length = w.PosX.Length;
        var consts = new Consts16(in p);

        for (int s = begin; s < end; s++)
        {
            int first = w.StrandFirst[s], n = w.StrandParticleCount[s];
            // Triple chunks start at k0 ≤ n and read particles up to k0 + 16: index first + n + 16 must exist.
            if (n < Wide || first + n + Wide >= length || Bent(w, s, first, n))
            {
                NarrowStrand(w, first, n, in p);
                continue;
            }
            if (n == Wide && first >= 1 && Strand16(w, first, in consts)) continue;
            ref float px = ref Simd.At(w.PosX, first); ref float py = ref Simd.At(w.PosY, first); ref float pz = ref Simd.At(w.PosZ, first);
            ref float sp = ref Simd.At(w.ShapePrev, first); ref float sm = ref Simd.At(w.ShapeMid, first); ref float sn = ref Simd.At(w.ShapeNext, first);
            var lastTriple = Vector512.Create(n - 2);
            for (int k0 = 1; k0 <= n; k0 += Wide)
            {
                nuint k = (nuint)k0;
                var bx = Vector512.LoadUnsafe(ref px, k); var by = Vector512.LoadUnsafe(ref py, k); var bz = Vector512.LoadUnsafe(ref pz, k);
                var ax = Vector512.LoadUnsafe(ref px, k - 1) - bx; var ay = Vector512.LoadUnsafe(ref py, k - 1) - by; var az = Vector512.LoadUnsafe(ref pz, k - 1) - bz;
                var cx = Vector512.LoadUnsafe(ref px, k + 1) - bx; var cy = Vector512.LoadUnsafe(ref py, k + 1) - by; var cz = Vector512.LoadUnsafe(ref pz, k + 1) - bz;
                var ox = (ax + cx) * third; var oy = (ay + cy) * third; var oz = (az + cz) * third;
                var ex = cx - ax; var ey = cy - ay; var ez = cz - az;
                var len2 = ex * ex + ey * ey + ez * ez;
                var ok = Vector512.GreaterThan(len2, eps2);
                var l2 = Vector512.ConditionalSelect(ok, len2, Vector512<float>.One);
                var inv = Simd.InvSqrt14x16(l2);
                ex *= inv; ey *= inv; ez *= inv;
                var kk = lane + Vector512.Create(k0);
                var valid = (Vector512.GreaterThanOrEqual(kk, Vector512<int>.One) & Vector512.LessThanOrEqual(kk, lastTriple)).AsSingle();
                var pa = Vector512.LoadUnsafe(ref sp, k); var pm = Vector512.LoadUnsafe(ref sm, k); var pn = Vector512.LoadUnsafe(ref sn, k);
                ref float gk = ref Unsafe.Add(ref g, o + k0);
                Vector512.ConditionalSelect(valid, (ox - ax) + pa * ex, default).StoreUnsafe(ref gk, (nuint)(GPx * st));
                Vector512.ConditionalSelect(valid, (oy - ay) + pa * ey, default).StoreUnsafe(ref gk, (nuint)(GPy * st));
                Vector512.ConditionalSelect(valid, (oz - az) + pa * ez, default).StoreUnsafe(ref gk, (nuint)(GPz * st));
                Vector512.ConditionalSelect(valid, ox + pm * ex, default).StoreUnsafe(ref gk, (nuint)(GMx * st));
                Vector512.ConditionalSelect(valid, oy + pm * ey, default).StoreUnsafe(ref gk, (nuint)(GMy * st));
                Vector512.ConditionalSelect(valid, oz + pm * ez, default).StoreUnsafe(ref gk, (nuint)(GMz * st));
                Vector512.ConditionalSelect(valid, (ox - cx) + pn * ex, default).StoreUnsafe(ref gk, (nuint)(GNx * st));
                Vector512.ConditionalSelect(valid, (oy - cy) + pn * ey, default).StoreUnsafe(ref gk, (nuint)(GNy * st));
                Vector512.ConditionalSelect(valid, (oz - cz) + pn * ez, default).StoreUnsafe(ref gk, (nuint)(GNz * st));
                var degenerate = Vector512.AndNot(valid, ok);
                if (degenerate != Vector512<float>.Zero) WideDegenerate(w, first, k0, degenerate, in p, scratch);
            }

            ref float vx = ref Simd.At(w.VelX, first); ref float vy = ref Simd.At(w.VelY, first); ref float vz = ref Simd.At(w.VelZ, first);
            ref float m = ref Simd.At(w.InvMass, first);
            var tip = Vector512.Create(n - 1); var beforeTip = Vector512.Create(n - 2);
            for (int j0 = 0; j0 < n; j0 += Wide)
            {
                // The last chunk overlaps the previous one; lanes below `fresh` were already updated.
                int fresh = j0;
                if (j0 + Wide > n) j0 = n - Wide;
                nuint j = (nuint)j0;
                ref float gj = ref Unsafe.Add(ref g, o + j0);
                var sx = Vector512.LoadUnsafe(ref gj, (nuint)(GPx * st + 1)) + Vector512.LoadUnsafe(ref gj, (nuint)(GMx * st)) + Vector512.LoadUnsafe(ref gj, (nuint)(GNx * st - 1));
                var sy = Vector512.LoadUnsafe(ref gj, (nuint)(GPy * st + 1)) + Vector512.LoadUnsafe(ref gj, (nuint)(GMy * st)) + Vector512.LoadUnsafe(ref gj, (nuint)(GNy * st - 1));
                var sz = Vector512.LoadUnsafe(ref gj, (nuint)(GPz * st + 1)) + Vector512.LoadUnsafe(ref gj, (nuint)(GMz * st)) + Vector512.LoadUnsafe(ref gj, (nuint)(GNz * st - 1));
                // α/h over the goal count: 1 at the root and the tip, 2 next to them, 3 elsewhere.
                var jj = lane + Vector512.Create(j0);
                var ends = (Vector512.Equals(jj, Vector512<int>.Zero) | Vector512.Equals(jj, tip)).AsSingle();
                var nextToEnds = (Vector512.Equals(jj, Vector512<int>.One) | Vector512.Equals(jj, beforeTip)).AsSingle();
                var f = Vector512.ConditionalSelect(ends, fOne, Vector512.ConditionalSelect(nextToEnds, fHalf, fThird));
                var apply = ~Vector512.Equals(Vector512.LoadUnsafe(ref m, j), Vector512<float>.Zero)
                            & Vector512.GreaterThanOrEqual(jj, Vector512.Create(fresh)).AsSingle();
                var x = Vector512.LoadUnsafe(ref vx, j); var y = Vector512.LoadUnsafe(ref vy, j); var z = Vector512.LoadUnsafe(ref vz, j);
                Vector512.ConditionalSelect(apply, x + f * sx, x).StoreUnsafe(ref vx, j);
                Vector512.ConditionalSelect(apply, y + f * sy, y).StoreUnsafe(ref vy, j);
                Vector512.ConditionalSelect(apply, z + f * sz, z).StoreUnsafe(ref vz, j);
                j0 = Math.Max(j0, fresh);
            }
        }
    }

    /// <summary>Per-run constants of <see cref="Strand16"/>.</summary>
    private readonly struct Consts16
    {
        public readonly Vector512<float> Third, Eps2, Valid, F;

        public Consts16(in Params p)
        {
            Third = Vector512.Create(1f / 3f); Eps2 = Vector512.Create(1e-24f);
            // Triples 1 … 14 exist; particle j has 1, 2, 3, …, 3, 2, 1 goals.
            Valid = Vector512.Create(0, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, 0).AsSingle();
            float f1 = p.F.GetElement(0), f2 = p.FHalf.GetElement(0), f3 = p.FThird.GetElement(0);
            F = Vector512.Create(f1, f2, f3, f3, f3, f3, f3, f3, f3, f3, f3, f3, f3, f3, f2, f1);
        }
    }

    /// <summary>
    /// A 16-particle strand entirely in registers: triples 0 … 15 in one chunk (0 and 15 do not exist and give
    /// zero goals; reading particle −1 and 16 touches the neighbouring strands, masked out), then each particle's
    /// "prev" and "next" goals are the neighbouring lanes (<c>valignd</c> shifts in zeros), so no goal goes through
    /// memory. Same arithmetic and order as the 8-lane path. Returns false (nothing written) if a triple's ends
    /// coincide: the caller then takes the general path with its scalar fallback.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static bool Strand16(HairWorld w, int first, in Consts16 c)
    {
        ref float px = ref Simd.At(w.PosX, first - 1); ref float py = ref Simd.At(w.PosY, first - 1); ref float pz = ref Simd.At(w.PosZ, first - 1);
        var bx = Vector512.LoadUnsafe(ref px, 1); var by = Vector512.LoadUnsafe(ref py, 1); var bz = Vector512.LoadUnsafe(ref pz, 1);
        var ax = Vector512.LoadUnsafe(ref px) - bx; var ay = Vector512.LoadUnsafe(ref py) - by; var az = Vector512.LoadUnsafe(ref pz) - bz;
        var cx = Vector512.LoadUnsafe(ref px, 2) - bx; var cy = Vector512.LoadUnsafe(ref py, 2) - by; var cz = Vector512.LoadUnsafe(ref pz, 2) - bz;
        var ox = (ax + cx) * c.Third; var oy = (ay + cy) * c.Third; var oz = (az + cz) * c.Third;
        var ex = cx - ax; var ey = cy - ay; var ez = cz - az;
        var len2 = ex * ex + ey * ey + ez * ez;
        var ok = Vector512.GreaterThan(len2, c.Eps2);
        if (Vector512.AndNot(c.Valid, ok) != Vector512<float>.Zero) return false;
        var l2 = Vector512.ConditionalSelect(ok, len2, Vector512<float>.One);
        var inv = Simd.InvSqrt14x16(l2);
        ex *= inv; ey *= inv; ez *= inv;
        var pa = Vector512.LoadUnsafe(ref Simd.At(w.ShapePrev, first)); var pm = Vector512.LoadUnsafe(ref Simd.At(w.ShapeMid, first));
        var pn = Vector512.LoadUnsafe(ref Simd.At(w.ShapeNext, first));
        var v = c.Valid;
        // Particle j: goal "prev" of triple j + 1, "mid" of triple j, "next" of triple j − 1.
        var sx = Down(Vector512.ConditionalSelect(v, (ox - ax) + pa * ex, default)) + Vector512.ConditionalSelect(v, ox + pm * ex, default)
                 + Up(Vector512.ConditionalSelect(v, (ox - cx) + pn * ex, default));
        var sy = Down(Vector512.ConditionalSelect(v, (oy - ay) + pa * ey, default)) + Vector512.ConditionalSelect(v, oy + pm * ey, default)
                 + Up(Vector512.ConditionalSelect(v, (oy - cy) + pn * ey, default));
        var sz = Down(Vector512.ConditionalSelect(v, (oz - az) + pa * ez, default)) + Vector512.ConditionalSelect(v, oz + pm * ez, default)
                 + Up(Vector512.ConditionalSelect(v, (oz - cz) + pn * ez, default));
        var apply = ~Vector512.Equals(Vector512.LoadUnsafe(ref Simd.At(w.InvMass, first)), Vector512<float>.Zero);
        ref float vx = ref Simd.At(w.VelX, first); ref float vy = ref Simd.At(w.VelY, first); ref float vz = ref Simd.At(w.VelZ, first);
        var x = Vector512.LoadUnsafe(ref vx); var y = Vector512.LoadUnsafe(ref vy); var z = Vector512.LoadUnsafe(ref vz);
        Vector512.ConditionalSelect(apply, x + c.F * sx, x).StoreUnsafe(ref vx);
        Vector512.ConditionalSelect(apply, y + c.F * sy, y).StoreUnsafe(ref vy);
        Vector512.ConditionalSelect(apply, z + c.F * sz, z).StoreUnsafe(ref vz);
        return true;
    }

    /// <summary>Lane j ← lane j + 1, lane 15 ← 0.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static Vector512<float> Down(Vector512<float> x) => Avx512F.AlignRight32(Vector512<uint>.Zero, x.AsUInt32(), 1).AsSingle();

    /// <summary>Lane j ← lane j − 1, lane 0 ← 0.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static Vector512<float> Up(Vector512<float> x) => Avx512F.AlignRight32(x.AsUInt32(), Vector512<uint>.Zero, 15).AsSingle();

    /// <summary>Triples of a wide chunk whose ends coincide: the reference's fallback axis, in scalar code.</summary>
    [MethodImpl(MethodImplOptions.NoInlining)]
    private static void WideDegenerate(HairWorld w, int first, int k0, Vector512<float> degenerate, in Params p, scoped StrandScratch scratch)
    {
        var v = View(w, first);
        for (int l = 0; l < Wide; l++)
            if (BitConverter.SingleToInt32Bits(degenerate.GetElement(l)) != 0)
                ScalarTriple(ref v, k0 + l, bent: false, in p, scratch, ref scratch.Data[0]);
    }

    /// <summary>One strand the wide path does not take, through the 8-lane path (with its own scratch).</summary>
    [SkipLocalsInit]
    [MethodImpl(MethodImplOptions.NoInlining)]
    private void NarrowStrand(HairWorld w, int first, int n, in Params p)
    {
        int size = StrandScratch.Size(_maxCapacity, FieldCount);
        var scratch = new StrandScratch(size <= StrandScratch.StackFloats ? stackalloc float[size] : StrandScratch.Heap(size), _maxCapacity);
        if (n >= Vector<float>.Count + 2)
        {
            var v = View(w, first);
            Strand(ref v, w, first, n, padded: false, zeroSlots: true, in p, scratch);
        }
        else ShortStrand(w, first, n, in p, scratch);
    }
}
