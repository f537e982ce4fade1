using System.Numerics;
using System.Runtime.CompilerServices;

namespace HairSim.Fast;

/// <summary>
/// Fast <see cref="BendSystem"/> in float. The sweep is a chain along each strand (segment k's target needs the
/// frame carried through k−1), so it is vectorised across strands: a group of strands is put into a stack tile
/// (row k = particle k of each strand), swept root to tip together, and written back. Each tile row is two SIMD
/// vectors of strands, two independent chains whose latencies (square roots, divisions) overlap: 16 strands per
/// tile with 8-lane vectors, 32 with 16-lane AVX-512 vectors (FastBendSystem.Wide.cs, same arithmetic, same bits).
/// Groups of whole strands of one capacity laid back to back (every uncut groom) are moved in and out with SIMD
/// transposes; any other group element by element. Per strand the rest directions and joint time constants are
/// cached until the world is edited or Sag changes. Same arithmetic as the reference, in float; lanes past a
/// strand's live count, and padding lanes, are masked out (InvMass 0).
/// </summary>
public sealed partial class FastBendSystem : IHairSystem
{
    public string Name => BendSystem.SystemName;
    public SystemPhase Phase => SystemPhase.Substep;

    // Tile fields, each maxCapacity rows × lanes. Velocities are updated in place and written back whole.
    private const int TX = 0, TY = 1, TZ = 2, TVx = 3, TVy = 4, TVz = 5, TM = 6, TL = 7, TRx = 8, TRy = 9, TRz = 10, TA = 11, TB = 12,
        FieldCount = 13;

    /// <summary>SIMD vectors per tile row (two chains whose latencies overlap).</summary>
    private const int Halves = 2;

    private readonly int _maxCapacity;
    /// <summary>Strands per tile: Halves × 8 (AVX) or Halves × 16 (AVX-512, <see cref="Sweep16"/>).</summary>
    private readonly int _lanes;
    // Per particle k of a strand: the rest unit direction of segment k (k−1 → k, head space; 0 if degenerate) and the
    // T² of the joint that holds it (joint k−1), cached per strand until the world's next edit or a new Sag; and that
    // joint's spring and dashpot shares a, b for the substep h and damping ζ they were computed for.
    private readonly float[] _restX, _restY, _restZ, _jointT2, _jointA, _jointB, _profile;
    private readonly long[] _profileAt;
    private readonly float[] _profileSag, _sharesH, _sharesZeta;

    public FastBendSystem(HairWorld world) : this(world, allowWide: true) { }

    /// <param name="world">The world (sizes the tile and the per-strand cache).</param>
    /// <param name="allowWide">Sweep 16-lane vectors where the CPU has AVX-512 (same bits either way).</param>
    public FastBendSystem(HairWorld world, bool allowWide)
    {
        _maxCapacity = world.MaxStrandCapacity;
        _lanes = Halves * (allowWide && FastPathInfo.Avx512 ? 16 : Vector<float>.Count);
        int n = world.ParticleCount;
        _restX = new float[n]; _restY = new float[n]; _restZ = new float[n]; _jointT2 = new float[n]; _profile = new float[n];
        _jointA = new float[n]; _jointB = new float[n];
        _profileAt = new long[world.StrandCount];
        _profileSag = new float[world.StrandCount];
        _sharesH = new float[world.StrandCount]; _sharesZeta = new float[world.StrandCount];
        _chunkBend = new float[ChunkBendFields * n];
        _chunkBlock = new int[world.StrandCount];
        Array.Fill(_chunkBlock, -1);
        int strands = world.StrandCount;
        _checkedGeneration = new long[strands]; _checkedStamp = new long[strands];
        _checkedSag = new float[strands]; _checkedH = new float[strands]; _checkedZeta = new float[strands];
    }

    /// <summary>Whether this instance sweeps 16-lane vectors.</summary>
    internal bool UsesWide => _lanes == Halves * 16;

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private void EnsureCache(HairWorld w, int s, float sag, float h, float zeta)
    {
        if (_profileAt[s] != w.EditStamp + 1L || _profileSag[s] != sag) { FillCache(w, s, sag); CacheShares(w, s, h, zeta); }
        else if (_sharesH[s] != h || _sharesZeta[s] != zeta) CacheShares(w, s, h, zeta);
    }

    /// <summary>
    /// The implicit spring-dashpot's shares of each joint of strand s, a = T²/den and b = 2ζhT/den with
    /// den = T² + 2ζhT + h² (see BendSystem): they depend on the strand and h only, so they are worked out once per
    /// strand and substep length instead of in every row of every sweep (a square root and two divisions).
    /// </summary>
    private void CacheShares(HairWorld w, int s, float h, float zeta)
    {
        float zeta2h = 2f * zeta * h, hh = h * h;
        int first = w.StrandFirst[s], cap = w.StrandCapacity[s];
        for (int i = first; i < first + cap; i++)
        {
            float t2 = _jointT2[i], tt = MathF.Sqrt(t2);
            float den = t2 + zeta2h * tt + hh;
            _jointA[i] = t2 / den; _jointB[i] = zeta2h * tt / den;
        }
        _sharesH[s] = h; _sharesZeta[s] = zeta;
        _chunkBlock[s] = -1;
        Interlocked.Increment(ref _cacheGeneration);
    }

    private void FillCache(HairWorld w, int s, float sag)
    {
        BendProfile.Compute(w, s, sag, _profile);
        int first = w.StrandFirst[s], cap = w.StrandCapacity[s];
        for (int k = 0; k < cap; k++)
        {
            int i = first + k;
            _jointT2[i] = k == 0 ? 0f : _profile[i - 1];
            if (k == 0) { _restX[i] = _restY[i] = _restZ[i] = 0f; continue; }
            double rx = w.RestX[i] - w.RestX[i - 1], ry = w.RestY[i] - w.RestY[i - 1], rz = w.RestZ[i] - w.RestZ[i - 1];
            double rl = Math.Sqrt(rx * rx + ry * ry + rz * rz);
            if (rl > 0) { _restX[i] = (float)(rx / rl); _restY[i] = (float)(ry / rl); _restZ[i] = (float)(rz / rl); }
            else _restX[i] = _restY[i] = _restZ[i] = 0f;
        }
        _profileAt[s] = w.EditStamp + 1L; _profileSag[s] = sag;
        _chunkBlock[s] = -1;
        Interlocked.Increment(ref _cacheGeneration);
    }

    // The stack tile is fully written before it is read (uniform groups by the transposes, others cleared first).
    [SkipLocalsInit]
    private void RunTiles(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var w = scene.World;
        var st = ctx.Settings;
        if (st.Bend != BendModel.RestShape) return;
        for (int s = begin; s < end; s++) EnsureCache(w, s, st.Sag, ctx.H, st.BendDamping);
        int lanes = _lanes;
        int size = StrandScratch.Size(_maxCapacity * lanes, FieldCount);
        var t = new StrandScratch(size <= StrandScratch.StackFloats ? stackalloc float[size] : StrandScratch.Heap(size), _maxCapacity * lanes);
        var p = new SweepParams(ctx, substep, t, lanes);
        Span<int> firsts = stackalloc int[lanes];
        Span<int> counts = stackalloc int[lanes];
        for (int s0 = begin; s0 < end; s0 += lanes)
        {
            int used = Math.Min(lanes, end - s0), rows = 0;
            // Transposed in and out: a full group of strands of one capacity (a multiple of 8) laid back to back, as a
            // groom is, cut or not. Particles past a cut are masked (InvMass 0 in the tile): they are swept as pins,
            // never moved, and written back as they were, so cut hair stays on the transposed path.
            int cap = w.StrandCapacity[s0];
            bool layout = used == lanes && Transpose.Available && cap % 8 == 0;
            bool cut = false;
            for (int l = 0; l < lanes; l++)
            {
                firsts[l] = l < used ? w.StrandFirst[s0 + l] : 0;
                counts[l] = l < used ? w.StrandParticleCount[s0 + l] : 0;
                rows = Math.Max(rows, counts[l]);
                if (l < used) { layout &= w.StrandCapacity[s0 + l] == cap && firsts[l] == firsts[0] + l * cap; cut |= counts[l] != cap; }
            }
            if (layout)
            {
                rows = cap;
                GatherUniform(w, t, firsts[0], rows, lanes);
                if (cut) MaskPastCuts(t, counts, rows, lanes);
            }
            else Gather(w, t, firsts, counts, rows);
            ref float d = ref t.Data[0];
            if (UsesWide) Sweep16(ref d, ref d, rows, in p);
            else Sweep(ref d, ref d, rows, in p);
            if (layout) ScatterUniform(w, t, firsts[0], rows, lanes);
            else Scatter(w, t, firsts, counts);
        }
    }

    /// <summary>Rows past each lane's live count become pins (InvMass 0): swept but never moved or kicked.</summary>
    private static void MaskPastCuts(scoped StrandScratch t, ReadOnlySpan<int> counts, int rows, int lanes)
    {
        ref float m = ref t.Data[t.Offset(TM)];
        for (int l = 0; l < lanes; l++)
            for (int k = counts[l]; k < rows; k++) Unsafe.Add(ref m, k * lanes + l) = 0f;
    }

    /// <summary>Any group: masked cells are zeroed (InvMass 0, never moved, finite), then live cells copied one by one.</summary>
    private void Gather(HairWorld w, scoped StrandScratch t, ReadOnlySpan<int> firsts, ReadOnlySpan<int> counts, int rows)
    {
        int lanes = firsts.Length;
        Span<float> d = t.Data;
        for (int f = 0; f < FieldCount; f++) d.Slice(t.Offset(f), rows * lanes).Clear();
        ReadOnlySpan<float[]> src = [w.PosX, w.PosY, w.PosZ, w.VelX, w.VelY, w.VelZ, w.InvMass, w.RestLength, _restX, _restY, _restZ, _jointA, _jointB];
        ref float dd = ref d[0];
        for (int f = 0; f < src.Length; f++)
        {
            ref float a = ref Simd.At(src[f], 0);
            int o = t.Offset(f);
            for (int l = 0; l < lanes; l++)
            {
                int first = firsts[l], n = counts[l];
                for (int k = 0; k < n; k++) Unsafe.Add(ref dd, o + k * lanes + l) = Unsafe.Add(ref a, first + k);
            }
        }
    }

    private static void Scatter(HairWorld w, scoped StrandScratch t, ReadOnlySpan<int> firsts, ReadOnlySpan<int> counts)
    {
        int lanes = firsts.Length;
        ReadOnlySpan<float[]> dst = [w.PosX, w.PosY, w.PosZ, w.VelX, w.VelY, w.VelZ];
        ref float dd = ref t.Data[0];
        for (int f = 0; f < dst.Length; f++)
        {
            ref float a = ref Simd.At(dst[f], 0);
            int o = t.Offset(TX + f);
            for (int l = 0; l < lanes; l++)
            {
                // The root row never changes.
                int first = firsts[l], n = counts[l];
                for (int k = 1; k < n; k++) Unsafe.Add(ref a, first + k) = Unsafe.Add(ref dd, o + k * lanes + l);
            }
        }
    }

    /// <summary>Whole strands of one capacity (a multiple of 8), back to back: every field by SIMD transposes.</summary>
    private void GatherUniform(HairWorld w, scoped StrandScratch t, int first, int rows, int lanes)
    {
        Transpose.StrandsIn(w.PosX, first, rows, t, TX, lanes); Transpose.StrandsIn(w.PosY, first, rows, t, TY, lanes); Transpose.StrandsIn(w.PosZ, first, rows, t, TZ, lanes);
        Transpose.StrandsIn(w.VelX, first, rows, t, TVx, lanes); Transpose.StrandsIn(w.VelY, first, rows, t, TVy, lanes); Transpose.StrandsIn(w.VelZ, first, rows, t, TVz, lanes);
        Transpose.StrandsIn(w.InvMass, first, rows, t, TM, lanes); Transpose.StrandsIn(w.RestLength, first, rows, t, TL, lanes);
        Transpose.StrandsIn(_restX, first, rows, t, TRx, lanes); Transpose.StrandsIn(_restY, first, rows, t, TRy, lanes); Transpose.StrandsIn(_restZ, first, rows, t, TRz, lanes);
        Transpose.StrandsIn(_jointA, first, rows, t, TA, lanes); Transpose.StrandsIn(_jointB, first, rows, t, TB, lanes);
    }

    private static void ScatterUniform(HairWorld w, scoped StrandScratch t, int first, int rows, int lanes)
    {
        Transpose.StrandsOut(t, TX, w.PosX, first, rows, lanes); Transpose.StrandsOut(t, TY, w.PosY, first, rows, lanes); Transpose.StrandsOut(t, TZ, w.PosZ, first, rows, lanes);
        Transpose.StrandsOut(t, TVx, w.VelX, first, rows, lanes); Transpose.StrandsOut(t, TVy, w.VelY, first, rows, lanes); Transpose.StrandsOut(t, TVz, w.VelZ, first, rows, lanes);
    }

    /// <summary><see cref="Sweep16{TIntegrate}"/>: the sweep alone.</summary>
    private struct Apart { }
    /// <summary><see cref="Sweep16{TIntegrate}"/>: each row integrated first (FastIntegrateSystem fused in).</summary>
    private struct Fused { }

    /// <summary>
    /// Per-sweep constants and where each field's row 0 is: particle fields from one base, the cached rest fields
    /// (rest directions, joint shares) from another (the same tile here; a chunk keeps them apart). Rows are Lanes floats apart.
    /// </summary>
    private readonly struct SweepParams
    {
        public readonly float H, InvH, Reaction, FallX, FallY, FallZ;
        /// <summary>The speed limit (m/s) the kick clamps velocities to; +∞ when off.</summary>
        public readonly float MaxSpeed, MaxSpeedSq;
        /// <summary>Velocities within this in every component are under the limit (<see cref="Simd.SpeedBound"/>).</summary>
        public readonly uint SpeedBound;
        /// <summary>Integration's velocity keep per substep and gravity × h (for the sweep that integrates each row first, <see cref="Fused"/>).</summary>
        public readonly float Keep, GravityStepX, GravityStepY, GravityStepZ;
        public readonly float Qx, Qy, Qz, Qw;
        public readonly int Ox, Oy, Oz, Ovx, Ovy, Ovz, Om, Ol, Orx, Ory, Orz, Oa, Ob, Lanes;
        /// <summary>The chunk runner's prefetch of the next chunk, advanced once per row (0: none).</summary>
        public readonly nint Prefetch;
        /// <summary>Where the 16-lane sweep writes its far-row mask (<see cref="StrandChunk.FarRows"/>; 0: no test), and the far sphere it tests against.</summary>
        public readonly nint FarRows;
        public readonly float FarX, FarY, FarZ, FarOuter2;

        public SweepParams(FrameContext ctx, int substep, scoped StrandScratch t, int lanes)
            : this(ctx, substep, lanes, t.Offset(TX), t.Offset(TY), t.Offset(TZ), t.Offset(TVx), t.Offset(TVy), t.Offset(TVz), t.Offset(TM), t.Offset(TL),
                t.Offset(TRx), t.Offset(TRy), t.Offset(TRz), t.Offset(TA), t.Offset(TB)) { }

        public SweepParams(FrameContext ctx, int substep, int lanes, int ox, int oy, int oz, int ovx, int ovy, int ovz, int om, int ol,
            int orx, int ory, int orz, int oa, int ob, nint prefetch = 0, nint farRows = 0)
        {
            Prefetch = prefetch;
            FarRows = farRows;
            if (farRows != 0)
            {
                FastCollideSystem.FarSphere(ctx.CollidersAt(substep)[0], out var centre, out FarOuter2);
                FarX = centre.X; FarY = centre.Y; FarZ = centre.Z;
            }
            var st = ctx.Settings;
            float h = ctx.H;
            H = h; InvH = 1f / h;
            Reaction = (float)BendSystem.ReactionShare;
            float kappa = MathF.Max(0f, 1f - st.Damping * h);
            Keep = kappa;
            var gravityStep = st.Gravity * h; // as FastIntegrateSystem builds it
            GravityStepX = gravityStep.X; GravityStepY = gravityStep.Y; GravityStepZ = gravityStep.Z;
            FallX = st.Gravity.X * h * h * kappa; FallY = st.Gravity.Y * h * h * kappa; FallZ = st.Gravity.Z * h * h * kappa;
            MaxSpeed = st.MaxSpeed > 0f ? st.MaxSpeed : float.PositiveInfinity;
            MaxSpeedSq = MaxSpeed * MaxSpeed;
            SpeedBound = Simd.SpeedBound(MaxSpeed);
            var q = ctx.HeadAt(substep).Rotation;
            Qx = q.X; Qy = q.Y; Qz = q.Z; Qw = q.W;
            Ox = ox; Oy = oy; Oz = oz; Ovx = ovx; Ovy = ovy; Ovz = ovz; Om = om; Ol = ol;
            Orx = orx; Ory = ory; Orz = orz; Oa = oa; Ob = ob; Lanes = lanes;
        }
    }
}
