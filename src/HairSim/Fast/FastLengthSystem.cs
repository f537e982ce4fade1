using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.Intrinsics;
using System.Runtime.Intrinsics.X86;

namespace HairSim.Fast;

/// <summary>
/// Fast <see cref="LengthSystem"/> in float. Follow-the-leader is a chain along each strand (particle k needs
/// particle k−1 already corrected), so it cannot be vectorised along the strand; it is vectorised across
/// strands instead: 16 strands (32 with AVX-512, see FastLengthSystem.Wide.cs) are transposed into a small
/// per-thread tile (row k = particle k of each strand, as two SIMD vectors), swept root to tip together, and written
/// back. Two independent vectors per row let the CPU overlap two dependency chains (square root latency). PBD runs
/// the same way with its Gauss–Seidel sweeps (8 lanes at a time, whatever the tile width). Lanes past a strand's live count, and padding lanes of the last group, are masked out
/// (InvMass 0).
/// </summary>
public sealed partial class FastLengthSystem : IHairSystem
{
    public string Name => LengthSystem.SystemName;
    public SystemPhase Phase => SystemPhase.Substep;

    // Tile fields, each maxCapacity rows × Lanes.
    internal const int TX = 0, TY = 1, TZ = 2, TVx = 3, TVy = 4, TVz = 5, TM = 6, TL = 7, TOx = 8, TOy = 9, TOz = 10, FieldCount = 11;

    /// <summary>SIMD vectors per tile row (two chains whose latencies overlap).</summary>
    private const int Halves = 2;

    private readonly int _maxCapacity;
    /// <summary>Strands per tile: Halves × 8 (AVX) or Halves × 16 (AVX-512, <see cref="FollowTheLeader16"/>).</summary>
    private readonly int _lanes;

    /// <param name="maxStrandCapacity">The longest strand's capacity (sizes the tile).</param>
    /// <param name="allowWide">Sweep 16-lane vectors where the CPU has AVX-512 (same bits either way).</param>
    public FastLengthSystem(int maxStrandCapacity, bool allowWide = true)
    {
        _maxCapacity = maxStrandCapacity;
        _lanes = Halves * (allowWide && WideAvailable ? 16 : Vector<float>.Count);
    }

    private static bool WideAvailable => FastPathInfo.Avx512;

    /// <summary>Whether this instance sweeps 16-lane vectors.</summary>
    internal bool UsesWide => _lanes == Halves * 16;

    // The stack scratch is fully written before it is read, or only read in lanes that are masked out.
    [SkipLocalsInit]
    private void RunTiles(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var st = ctx.Settings;
        if (st.Length == LengthMode.None || LengthSystem.FusedIntoBend(st)) return;
        var w = scene.World;
        int lanes = _lanes, width = Vector<float>.Count;
        // The tile is a StrandScratch whose "capacity" is rows × lanes.
        int size = StrandScratch.Size(_maxCapacity * lanes, FieldCount);
        var scratch = new StrandScratch(size <= StrandScratch.StackFloats ? stackalloc float[size] : StrandScratch.Heap(size), _maxCapacity * lanes);
        var head = new PoseLanes(ctx.HeadAt(substep));
        Span<int> firsts = stackalloc int[lanes];
        Span<int> counts = stackalloc int[lanes];
        for (int s0 = begin; s0 < end; s0 += lanes)
        {
            int used = Math.Min(lanes, end - s0);
            int rows = 0;
            bool uniform = used == lanes && Transpose.Available;
            for (int l = 0; l < lanes; l++)
            {
                firsts[l] = l < used ? w.StrandFirst[s0 + l] : 0;
                counts[l] = l < used ? w.StrandParticleCount[s0 + l] : 0;
                rows = Math.Max(rows, counts[l]);
                if (l < used) uniform &= counts[l] == w.StrandCapacity[s0 + l];
            }
            // Uniform: whole strands of one capacity (a multiple of 8), back to back.
            uniform &= rows % 8 == 0 && counts[0] == rows;
            for (int l = 1; uniform && l < lanes; l++) uniform = counts[l] == rows && firsts[l] == firsts[0] + l * rows;
            Gather(w, scratch, firsts, counts, rows, uniform);
            if (st.Length == LengthMode.FollowTheLeader)
            {
                if (UsesWide) FollowTheLeader16(w, scratch, firsts, rows, ctx.H, st.LengthDamping, in head);
                else FollowTheLeader(w, scratch, firsts, rows, ctx.H, st.LengthDamping, in head);
            }
            else Pbd(scratch, rows, lanes, ctx.H, st.LengthIterations);
            Scatter(w, scratch, firsts, counts, rows, uniform);
        }
    }

    /// <summary>
    /// Fills the tile from the world. Uniform groups (Width whole strands of equal capacity, a multiple of 8,
    /// laid out back to back, as every uncut groom is) use 8 × 8 SIMD transposes; anything else is copied
    /// element by element.
    /// </summary>
    private static void Gather(HairWorld w, scoped StrandScratch t, ReadOnlySpan<int> firsts, ReadOnlySpan<int> counts, int rows, bool uniform)
    {
        int width = firsts.Length;
        Span<float> d = t.Data;
        if (uniform)
        {
            int first = firsts[0];
            Transpose.StrandsIn(w.PosX, first, rows, t, TX, width); Transpose.StrandsIn(w.PosY, first, rows, t, TY, width); Transpose.StrandsIn(w.PosZ, first, rows, t, TZ, width);
            Transpose.StrandsIn(w.InvMass, first, rows, t, TM, width); Transpose.StrandsIn(w.RestLength, first, rows, t, TL, width);
            ClearRootKick(t, width);
            return;
        }
        int ox = t.Offset(TX), oy = t.Offset(TY), oz = t.Offset(TZ), om = t.Offset(TM), ol = t.Offset(TL);
        ClearRootKick(t, width);
        // Masked lanes: InvMass 0 (never moved) at a finite position; their results are never written back.
        d.Slice(om, rows * width).Clear();
        d.Slice(ox, rows * width).Clear(); d.Slice(oy, rows * width).Clear(); d.Slice(oz, rows * width).Clear();
        d.Slice(ol, rows * width).Clear();
        ref float dd = ref d[0];
        ref float px = ref Simd.At(w.PosX, 0), py = ref Simd.At(w.PosY, 0), pz = ref Simd.At(w.PosZ, 0);
        ref float m = ref Simd.At(w.InvMass, 0), l0 = ref Simd.At(w.RestLength, 0);
        for (int l = 0; l < width; l++)
        {
            int first = firsts[l], n = counts[l];
            for (int k = 0; k < n; k++)
            {
                int i = first + k, r = k * width + l;
                Unsafe.Add(ref dd, ox + r) = Unsafe.Add(ref px, i); Unsafe.Add(ref dd, oy + r) = Unsafe.Add(ref py, i); Unsafe.Add(ref dd, oz + r) = Unsafe.Add(ref pz, i);
                Unsafe.Add(ref dd, om + r) = Unsafe.Add(ref m, i); Unsafe.Add(ref dd, ol + r) = Unsafe.Add(ref l0, i);
            }
        }
    }

    private static void Scatter(HairWorld w, scoped StrandScratch t, ReadOnlySpan<int> firsts, ReadOnlySpan<int> counts, int rows, bool uniform)
    {
        int width = firsts.Length;
        if (uniform)
        {
            int first = firsts[0];
            Transpose.StrandsOut(t, TX, w.PosX, first, rows, width); Transpose.StrandsOut(t, TY, w.PosY, first, rows, width); Transpose.StrandsOut(t, TZ, w.PosZ, first, rows, width);
            Transpose.StrandsOut(t, TVx, w.VelX, first, rows, width, add: true); Transpose.StrandsOut(t, TVy, w.VelY, first, rows, width, add: true);
            Transpose.StrandsOut(t, TVz, w.VelZ, first, rows, width, add: true);
            return;
        }
        ref float dd = ref t.Data[0];
        int ox = t.Offset(TX), oy = t.Offset(TY), oz = t.Offset(TZ), ovx = t.Offset(TVx), ovy = t.Offset(TVy), ovz = t.Offset(TVz);
        ref float px = ref Simd.At(w.PosX, 0), py = ref Simd.At(w.PosY, 0), pz = ref Simd.At(w.PosZ, 0);
        ref float vx = ref Simd.At(w.VelX, 0), vy = ref Simd.At(w.VelY, 0), vz = ref Simd.At(w.VelZ, 0);
        for (int l = 0; l < width; l++)
        {
            int first = firsts[l], n = counts[l];
            for (int k = 0; k < n; k++)
            {
                int i = first + k, r = k * width + l;
                Unsafe.Add(ref px, i) = Unsafe.Add(ref dd, ox + r); Unsafe.Add(ref py, i) = Unsafe.Add(ref dd, oy + r); Unsafe.Add(ref pz, i) = Unsafe.Add(ref dd, oz + r);
                Unsafe.Add(ref vx, i) += Unsafe.Add(ref dd, ovx + r); Unsafe.Add(ref vy, i) += Unsafe.Add(ref dd, ovy + r); Unsafe.Add(ref vz, i) += Unsafe.Add(ref dd, ovz + r);
            }
        }
    }

    /// <summary>
    /// The velocity fields of the tile hold velocity changes, not velocities (so velocities are never transposed
    /// in): every sweep writes the change of rows 1 … rows−1, and the root row never changes.
    /// </summary>
    private static void ClearRootKick(scoped StrandScratch t, int lanes)
    {
        t.Data.Slice(t.Offset(TVx), lanes).Clear(); t.Data.Slice(t.Offset(TVy), lanes).Clear(); t.Data.Slice(t.Offset(TVz), lanes).Clear();
    }

    /// <summary>Per-sweep constants and tile offsets.</summary>
    private readonly struct FtlParams
    {
        public readonly Vector<float> InvH, Damp, Eps2;
        public readonly int Ox, Oy, Oz, Ovx, Ovy, Ovz, Om, Ol, Lanes;

        public FtlParams(scoped StrandScratch t, float h, float damping, int lanes)
        {
            InvH = new(1f / h); Damp = new(damping); Eps2 = new(1e-24f); // |e| < 1e-12, squared
            Ox = t.Offset(TX); Oy = t.Offset(TY); Oz = t.Offset(TZ); Ovx = t.Offset(TVx); Ovy = t.Offset(TVy); Ovz = t.Offset(TVz);
            Om = t.Offset(TM); Ol = t.Offset(TL); Lanes = lanes;
        }
    }

    /// <summary>
    /// The sweep, root to tip (written for Halves = 2: two vectors of strands, each carrying a chain — the
    /// corrected previous particle, its correction, whether it is free — from row to row). The sweep is
    /// latency-bound, so the chains are plain locals that stay in registers: nothing in this loop takes their
    /// address or calls out (a call would make the JIT spill them around it on every row). A row where some lane's
    /// neighbours coincide (rare) hands the rest of the sweep to <see cref="SweepWithFallback"/>.
    /// </summary>
    private static void FollowTheLeader(HairWorld w, scoped StrandScratch t, ReadOnlySpan<int> firsts, int rows, float h, float damping, in PoseLanes head)
    {
        int width = Vector<float>.Count;
        ref float d = ref t.Data[0];
        var p = new FtlParams(t, h, damping, firsts.Length);
        var ax = Simd.Ld(ref d, p.Ox); var ay = Simd.Ld(ref d, p.Oy); var az = Simd.Ld(ref d, p.Oz);
        var bx = Simd.Ld(ref d, p.Ox + width); var by = Simd.Ld(ref d, p.Oy + width); var bz = Simd.Ld(ref d, p.Oz + width);
        Vector<float> adx = default, ady = default, adz = default, bdx = default, bdy = default, bdz = default;
        Vector<int> aFree = default, bFree = default;
        int k = 1;
        for (; k < rows; k++)
        {
            int ra = k * p.Lanes, rb = ra + width;
            var xa = Simd.Ld(ref d, p.Ox + ra); var ya = Simd.Ld(ref d, p.Oy + ra); var za = Simd.Ld(ref d, p.Oz + ra);
            var xb = Simd.Ld(ref d, p.Ox + rb); var yb = Simd.Ld(ref d, p.Oy + rb); var zb = Simd.Ld(ref d, p.Oz + rb);
            var freeA = ~Vector.Equals(Simd.Ld(ref d, p.Om + ra), Vector<float>.Zero);
            var freeB = ~Vector.Equals(Simd.Ld(ref d, p.Om + rb), Vector<float>.Zero);
            var exa = xa - ax; var eya = ya - ay; var eza = za - az;
            var exb = xb - bx; var eyb = yb - by; var ezb = zb - bz;
            var len2a = exa * exa + eya * eya + eza * eza;
            var len2b = exb * exb + eyb * eyb + ezb * ezb;
            var degenerate = (freeA & Vector.LessThan(len2a, p.Eps2)) | (freeB & Vector.LessThan(len2b, p.Eps2));
            if (!Vector.EqualsAll(degenerate, Vector<int>.Zero)) break;
            // The two chains' sqrt latencies overlap.
            Advance(ref d, in p, k, ra, xa, ya, za, exa, eya, eza, len2a, freeA, ref ax, ref ay, ref az, ref adx, ref ady, ref adz, ref aFree);
            Advance(ref d, in p, k, rb, xb, yb, zb, exb, eyb, ezb, len2b, freeB, ref bx, ref by, ref bz, ref bdx, ref bdy, ref bdz, ref bFree);
        }
        if (k < rows)
        {
            SweepWithFallback(w, t, firsts, rows, k, h, damping, in head,
                new Chain { Px = ax, Py = ay, Pz = az, Dx = adx, Dy = ady, Dz = adz, Free = aFree },
                new Chain { Px = bx, Py = by, Pz = bz, Dx = bdx, Dy = bdy, Dz = bdz, Free = bFree }, default, default);
            return;
        }
        if (rows >= 2)
        {
            int r = (rows - 1) * p.Lanes;
            Kick(ref d, r, p.Ovx, p.Ovy, p.Ovz, aFree, adx, ady, adz, p.InvH);
            Kick(ref d, r + width, p.Ovx, p.Ovy, p.Ovz, bFree, bdx, bdy, bdz, p.InvH);
        }
    }

    /// <summary>
    /// Row k of one vector of strands whose neighbours do not coincide: put particle k at its rest distance from
    /// k−1, then kick k−1's velocity. (cx, cy, cz) is the corrected particle k−1 on entry and particle k on return;
    /// (cdx, cdy, cdz) and cFree its correction and free mask.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Advance(ref float d, in FtlParams p, int k, int r, Vector<float> x, Vector<float> y, Vector<float> z,
        Vector<float> ex, Vector<float> ey, Vector<float> ez, Vector<float> len2, Vector<int> free,
        ref Vector<float> cx, ref Vector<float> cy, ref Vector<float> cz, ref Vector<float> cdx, ref Vector<float> cdy, ref Vector<float> cdz,
        ref Vector<int> cFree)
    {
        // Correction d = leader + e·ratio − x. With e = x − leader that is e·(ratio − 1), which keeps float
        // rounding at segment scale (the reference computes it in double).
        var corr = Simd.Ld(ref d, p.Ol + r) * Simd.InvSqrt(Simd.Sel(free, len2, Vector<float>.One)) - Vector<float>.One;
        corr = Simd.Sel(free, corr, Vector<float>.Zero);
        var dx = ex * corr; var dy = ey * corr; var dz = ez * corr;
        var tx = x + dx; var ty = y + dy; var tz = z + dz;
        Simd.St(ref d, p.Ox + r, tx); Simd.St(ref d, p.Oy + r, ty); Simd.St(ref d, p.Oz + r, tz);
        // Velocity of particle k−1 now that its successor's correction is known: v += (d[k−1] − s·d[k]) / h.
        if (k >= 2) Kick(ref d, r - p.Lanes, p.Ovx, p.Ovy, p.Ovz, cFree, cdx - p.Damp * dx, cdy - p.Damp * dy, cdz - p.Damp * dz, p.InvH);
        cx = tx; cy = ty; cz = tz;
        cdx = dx; cdy = dy; cdz = dz; cFree = free;
    }

    /// <summary>Sweep state of one SIMD vector of strands: the corrected previous particle and its correction.</summary>
    private struct Chain
    {
        public Vector<float> Px, Py, Pz, Dx, Dy, Dz;
        public Vector<int> Free;
    }

    /// <summary>The rest of a sweep from row <paramref name="k0"/>, when some neighbours coincide: the general row step with the reference's fallback axis.</summary>
    /// <remarks>Chains c0 … c3 are the tile's 8-lane vectors in order (c2, c3 unused in a 16-lane tile).</remarks>
    [MethodImpl(MethodImplOptions.NoInlining)]
    [SkipLocalsInit]
    private static void SweepWithFallback(HairWorld w, scoped StrandScratch t, ReadOnlySpan<int> firsts, int rows, int k0, float h, float damping,
        in PoseLanes head, Chain c0, Chain c1, Chain c2, Chain c3)
    {
        int width = Vector<float>.Count;
        ref float d = ref t.Data[0];
        var p = new FtlParams(t, h, damping, firsts.Length);
        Span<Chain> chains = stackalloc Chain[4];
        chains[0] = c0; chains[1] = c1; chains[2] = c2; chains[3] = c3;
        int count = p.Lanes / width;
        for (int k = k0; k < rows; k++)
            for (int c = 0; c < count; c++) Step(w, ref d, in p, ref chains[c], firsts, k, c * width, in head);
        int r = (rows - 1) * p.Lanes;
        for (int c = 0; c < count; c++)
            Kick(ref d, r + c * width, p.Ovx, p.Ovy, p.Ovz, chains[c].Free, chains[c].Dx, chains[c].Dy, chains[c].Dz, p.InvH);
    }

    /// <summary>Row k of one vector of strands, any lanes possibly degenerate (see <see cref="Advance"/> for the common case).</summary>
    private static void Step(HairWorld w, ref float d, in FtlParams p, ref Chain c, ReadOnlySpan<int> firsts, int k, int half, in PoseLanes head)
    {
        int r = k * p.Lanes + half;
        var x = Simd.Ld(ref d, p.Ox + r); var y = Simd.Ld(ref d, p.Oy + r); var z = Simd.Ld(ref d, p.Oz + r);
        var free = ~Vector.Equals(Simd.Ld(ref d, p.Om + r), Vector<float>.Zero);
        var ex = x - c.Px; var ey = y - c.Py; var ez = z - c.Pz;
        var len2 = ex * ex + ey * ey + ez * ez;
        var degenerate = free & Vector.LessThan(len2, p.Eps2);
        if (Vector.EqualsAll(degenerate, Vector<int>.Zero))
        {
            Advance(ref d, in p, k, r, x, y, z, ex, ey, ez, len2, free, ref c.Px, ref c.Py, ref c.Pz, ref c.Dx, ref c.Dy, ref c.Dz, ref c.Free);
            return;
        }
        // Coincident neighbours: the edge takes the reference's fallback axis; d = leader + axis·ratio − x.
        var len = Vector.SquareRoot(len2);
        var ox = ex; var oy = ey; var oz = ez;
        RestAxis(w, firsts.Slice(half), k, degenerate, in head, ref ex, ref ey, ref ez, ref len);
        var ratio = Simd.Ld(ref d, p.Ol + r) / Simd.Sel(free, len, Vector<float>.One);
        var corr = ratio - Vector<float>.One;
        var dx = Simd.Sel(free, Simd.Sel(degenerate, (c.Px - x) + ex * ratio, ox * corr), Vector<float>.Zero);
        var dy = Simd.Sel(free, Simd.Sel(degenerate, (c.Py - y) + ey * ratio, oy * corr), Vector<float>.Zero);
        var dz = Simd.Sel(free, Simd.Sel(degenerate, (c.Pz - z) + ez * ratio, oz * corr), Vector<float>.Zero);
        var tx = x + dx; var ty = y + dy; var tz = z + dz;
        Simd.St(ref d, p.Ox + r, tx); Simd.St(ref d, p.Oy + r, ty); Simd.St(ref d, p.Oz + r, tz);
        if (k >= 2) Kick(ref d, r - p.Lanes, p.Ovx, p.Ovy, p.Ovz, c.Free, c.Dx - p.Damp * dx, c.Dy - p.Damp * dy, c.Dz - p.Damp * dz, p.InvH);
        c.Px = tx; c.Py = ty; c.Pz = tz;
        c.Dx = dx; c.Dy = dy; c.Dz = dz; c.Free = free;
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Kick(ref float d, int r, int ovx, int ovy, int ovz, Vector<int> free,
                             Vector<float> cx, Vector<float> cy, Vector<float> cz, Vector<float> invH)
    {
        // The tile holds velocity changes (added to the world's velocities on scatter); pinned lanes change by 0.
        Simd.St(ref d, ovx + r, Simd.Sel(free, cx * invH, Vector<float>.Zero));
        Simd.St(ref d, ovy + r, Simd.Sel(free, cy * invH, Vector<float>.Zero));
        Simd.St(ref d, ovz + r, Simd.Sel(free, cz * invH, Vector<float>.Zero));
    }

    /// <summary>Coincident neighbours (the reference's fallback): the edge takes the rest direction carried by the head, else −Y.</summary>
    private static void RestAxis(HairWorld w, ReadOnlySpan<int> firsts, int k, Vector<int> degenerate, in PoseLanes head,
                                 ref Vector<float> ex, ref Vector<float> ey, ref Vector<float> ez, ref Vector<float> len)
    {
        int width = Vector<float>.Count;
        Span<float> buf = stackalloc float[4 * width];
        ex.CopyTo(buf); ey.CopyTo(buf.Slice(width)); ez.CopyTo(buf.Slice(2 * width)); len.CopyTo(buf.Slice(3 * width));
        for (int l = 0; l < width; l++)
        {
            if (degenerate[l] == 0) continue;
            int i = firsts[l] + k;
            var axis = head.Direction(w.GetRest(i) - w.GetRest(i - 1));
            float al = axis.Length();
            if (al < 1e-12f) { axis = -Vector3.UnitY; al = 1f; }
            buf[l] = axis.X; buf[width + l] = axis.Y; buf[2 * width + l] = axis.Z; buf[3 * width + l] = al;
        }
        ex = new Vector<float>(buf); ey = new Vector<float>(buf.Slice(width)); ez = new Vector<float>(buf.Slice(2 * width)); len = new Vector<float>(buf.Slice(3 * width));
    }

    private static void Pbd(scoped StrandScratch t, int rows, int lanes, float h, int iterations)
    {
        int width = Vector<float>.Count;
        ref float d = ref t.Data[0];
        int ox = t.Offset(TX), oy = t.Offset(TY), oz = t.Offset(TZ), ovx = t.Offset(TVx), ovy = t.Offset(TVy), ovz = t.Offset(TVz),
            om = t.Offset(TM), ol = t.Offset(TL), oox = t.Offset(TOx), ooy = t.Offset(TOy), ooz = t.Offset(TOz);
        int cells = rows * lanes;
        t.Data.Slice(ox, cells).CopyTo(t.Data.Slice(oox, cells));
        t.Data.Slice(oy, cells).CopyTo(t.Data.Slice(ooy, cells));
        t.Data.Slice(oz, cells).CopyTo(t.Data.Slice(ooz, cells));
        var eps = new Vector<float>(1e-12f);
        for (int it = 0; it < iterations; it++)
        {
            for (int k = 1; k < rows; k++)
            {
                for (int half = 0; half < lanes; half += width)
                {
                    int a = (k - 1) * lanes + half, b = k * lanes + half;
                    var wa = Simd.Ld(ref d, om + a); var wb = Simd.Ld(ref d, om + b);
                    var wsum = wa + wb;
                    var ax = Simd.Ld(ref d, ox + a); var ay = Simd.Ld(ref d, oy + a); var az = Simd.Ld(ref d, oz + a);
                    var bx = Simd.Ld(ref d, ox + b); var by = Simd.Ld(ref d, oy + b); var bz = Simd.Ld(ref d, oz + b);
                    var ex = bx - ax; var ey = by - ay; var ez = bz - az;
                    var len = Vector.SquareRoot(ex * ex + ey * ey + ez * ez);
                    var act = ~Vector.Equals(wsum, Vector<float>.Zero) & Vector.GreaterThanOrEqual(len, eps);
                    if (Vector.EqualsAll(act, Vector<int>.Zero)) continue;
                    var c = Simd.Sel(act, (len - Simd.Ld(ref d, ol + b)) / Simd.Sel(act, len * wsum, Vector<float>.One), Vector<float>.Zero);
                    var ca = wa * c; var cb = wb * c;
                    Simd.St(ref d, ox + a, ax + ca * ex); Simd.St(ref d, oy + a, ay + ca * ey); Simd.St(ref d, oz + a, az + ca * ez);
                    Simd.St(ref d, ox + b, bx - cb * ex); Simd.St(ref d, oy + b, by - cb * ey); Simd.St(ref d, oz + b, bz - cb * ez);
                }
            }
        }
        var invH = new Vector<float>(1f / h);
        for (int r = 0; r < cells; r += width)
        {
            var free = ~Vector.Equals(Simd.Ld(ref d, om + r), Vector<float>.Zero);
            Kick(ref d, r, ovx, ovy, ovz, free,
                Simd.Ld(ref d, ox + r) - Simd.Ld(ref d, oox + r), Simd.Ld(ref d, oy + r) - Simd.Ld(ref d, ooy + r),
                Simd.Ld(ref d, oz + r) - Simd.Ld(ref d, ooz + r), invH);
        }
    }
}
