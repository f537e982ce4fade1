using System.Numerics;
using System.Diagnostics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using System.Runtime.Intrinsics;
using System.Runtime.Intrinsics.X86;
using HairSim.Meshes;

namespace HairSim.Fast;

/// <summary>
/// Fast <see cref="MeshCollideSystem"/>: on strand chunks, 8 strands at a time (AVX2 gathers of the distance field),
/// each lane walking its strand from root to tip exactly as the reference does (particle push, then the segment's
/// midpoint test with both ends pushed again), with every operation in the reference's order, so a chunk gives the
/// reference's bits (tested). Most samples are skipped without changing a decision:
/// <list type="bullet">
/// <item>a 4 × 4 × 4-cell brick's lower bound of the field (<see cref="SignedDistanceField.Bricks"/>, one gather from a
/// small table) settles particles farther than the margin plus half the chunk's longest segment (plus the trilinear
/// slack): neither pushed nor starting a midpoint test; a midpoint whose brick lies beyond the margin is not pushed;</item>
/// <item>each 8-lane row keeps a record of where it was last measured and what (carried from frame to frame): a row
/// whose lanes all stayed within their clearance of it (the distance beyond that far threshold, over √3) is settled
/// without a sample, and so is a row's midpoint test when every tested midpoint stayed within its clearance (each
/// substep first reads every row's record 16 lanes at a time, <see cref="Kernel.Classify"/>, and the walk then visits
/// only the rows where something happens);</item>
/// <item>a row nearer than that whose lanes all stay above the margin by √3 × their move is settled with bounds (record
/// ± √3 × move): not pushed, and measured only if a midpoint decision falls between its bounds.</item>
/// </list>
/// Strands outside chunks (and machines without AVX-512) go through the reference system.
/// </summary>
[SkipLocalsInit]
public sealed class FastMeshCollideSystem : IHairSystem, IStrandChunkSystem
{
    /// <summary>Debug builds count how rows were settled, so tests can see each path taken (no cost in release builds).</summary>
    internal static class Counts
    {
        internal static long BoundedRows, Measured;
        [Conditional("DEBUG")] internal static void Add(ref long count) => Interlocked.Increment(ref count);
    }

    private readonly MeshCollideSystem _reference = new();
    private readonly HairScene? _scene;
    // Per chunk (at its first strand): its longest segment this frame, from its first substep (ChunkMaxRest).
    private float[] _chunkMaxRest = [];
    // This frame's mesh colliders and each one's pose per substep ([substep × count + mesh]).
    private MeshCollideSystem.Pose[] _poses = [];
    private MeshCollider[] _colliders = [];

    /// <param name="scene">The scene this pipeline steps: its colliders are looked up once per frame instead of once per chunk.</param>
    public FastMeshCollideSystem(HairScene? scene = null) => _scene = scene;

    public string Name => MeshCollideSystem.SystemName;
    public SystemPhase Phase => SystemPhase.Substep;

    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end) => _reference.Run(scene, ctx, substep, begin, end);

    bool IStrandChunkSystem.SupportsChunks => FastPathInfo.Avx512 && Avx2.IsSupported;
    ChunkFields IStrandChunkSystem.ChunkNeeds => ChunkFields.RestLength;
    /// <summary>Particles past a cut arrive as pins (never pushed); midpoints are tested only between live particles, as the reference does.</summary>
    bool IStrandChunkSystem.TakesCutStrands => true;

    unsafe bool IStrandChunkSystem.BeginChunkFrame(FrameContext ctx)
    {
        _colliders = _scene?.MeshColliderArray ?? [];
        int strands = _scene?.World.StrandCount ?? 0;
        if (_chunkMaxRest.Length != strands) _chunkMaxRest = new float[strands];
        int n = _colliders.Length;
        if (_poses.Length < ctx.Substeps * n) _poses = new MeshCollideSystem.Pose[ctx.Substeps * n];
        for (int s = 0; s < ctx.Substeps; s++)
            for (int m = 0; m < n; m++) _poses[s * n + m] = new MeshCollideSystem.Pose(ctx.MeshPoseAt(s, m, _colliders));
        // The calling thread's memos are made here, in the first frame, not on the first chunk it happens to take:
        // which chunks a thread takes varies, and a step must allocate nothing once the scene runs.
        for (int m = 0; m < n; m++) CornerMemo.For(m, _colliders[m].Field);
        PrepareCarriedClearances(ctx.Teleported);
        return true;
    }

    // Clearances carried from frame to frame, per mesh collider: for each particle slot, its record (laid out as the
    // thread memo keeps them, RecordAt), in the chunk's row layout at 4 × its first particle. A record is a fact
    // about the field, true whichever particle reads it (the field is at least d at this head-space point, and exactly d
    // below the far distance stamped with it), so it holds across frames, edits, margins and other chunk boundaries, and
    // is dropped only when the field changes. With them a chunk's first substep settles rows as its later substeps do,
    // instead of sampling every row again. The midpoints' records stay in the thread memo, from the chunk's first
    // substep on: carried too (2026-11-27 again), the doubled block made frames slower.
    private const int CarryFloats = ClearFloats / 8; // per particle: its record's x, y, z and distance
    private float[]?[] _carry = [];
    // Per mesh: the first index of _carry[m] on a 64-byte line (the array is pinned), where its records start.
    private int[] _carryBase = [];
    // Per mesh, for each 8-lane row of records (at its first particle / 8): the far distance of the chunk that wrote
    // it, below which the record's distances are exact (above it, bounds). −∞: none exact.
    private float[]?[] _carryFar = [];
    private SignedDistanceField?[] _carryField = [];
    // The world's edit stamp the records were written under, and whether the last frame teleported: which strands make
    // a chunk changes only with an edit or a teleport, and a chunk starting elsewhere lays its rows over other rows'
    // records (with strand lengths that are not a multiple of 8, off by part of a row: one row's x beside another's distance).
    private int _carryEdit = -1;
    private bool _carryTeleported;

    private void PrepareCarriedClearances(bool teleported)
    {
        var w = _scene?.World;
        int n = _colliders.Length;
        if (w == null || n == 0) return;
        bool relaid = w.EditStamp != _carryEdit || teleported || _carryTeleported;
        _carryEdit = w.EditStamp; _carryTeleported = teleported;
        if (_carry.Length != n) { Array.Resize(ref _carry, n); Array.Resize(ref _carryFar, n); Array.Resize(ref _carryField, n); Array.Resize(ref _carryBase, n); }
        long size = (long)CarryFloats * w.ParticleCount + StrandScratch.LineFloats;
        for (int m = 0; m < n; m++)
        {
            var mc = _colliders[m];
            var carry = _carry[m];
            bool fresh = carry == null || carry.Length != size;
            if (fresh)
            {
                _carry[m] = carry = GC.AllocateUninitializedArray<float>((int)size, pinned: true);
                _carryBase[m] = StrandScratch.ToLine(ref MemoryMarshal.GetArrayDataReference(carry));
                _carryFar[m] = GC.AllocateUninitializedArray<float>(w.ParticleCount / 8 + 2, pinned: true);
            }
            if (fresh || relaid || !ReferenceEquals(_carryField[m], mc.Field))
            {
                // −1 everywhere: no distance that settles anything, so every record misses until a measure fills it.
                Array.Fill(carry!, -1f);
                Array.Fill(_carryFar[m]!, float.NegativeInfinity);
                _carryField[m] = mc.Field;
            }
        }
    }

    /// <summary>
    /// A distance at or above this can neither be pushed (it is above the margin) nor start a midpoint test (less half
    /// the longest segment, <paramref name="maxRest"/>, it is still above the threshold), so its exact value is not needed.
    /// </summary>
    private static float FarDistance(MeshCollider mc, float maxRest) =>
        MeshCollideSystem.MidpointThreshold(mc) + 0.5f * maxRest + 1e-3f * mc.Field.CellSize;

    float[]? IStrandChunkSystem.ChunkBlock(int s0, int first, int cells, out int offset, out int fields)
    {
        // The first mesh's carried clearances, fetched with the chunk's fields.
        var carry = _carry.Length > 0 ? _carry[0] : null;
        offset = (carry != null ? _carryBase[0] : 0) + CarryFloats * first; fields = CarryFloats;
        return carry != null && offset + (long)fields * cells <= carry.Length ? carry : null;
    }

    unsafe bool IStrandChunkSystem.RunChunk(HairScene scene, FrameContext ctx, int substep, scoped in StrandChunk chunk)
    {
        bool mine = ReferenceEquals(scene, _scene);
        var colliders = mine ? _colliders : scene.MeshColliderArray;
        if (colliders.Length == 0) return true;
        const int L = StrandChunk.Lanes;
        bool carried = mine && _carry.Length == colliders.Length;
        // The longest segment, measured at the chunk's first substep and kept for the rest (rest lengths hold all frame).
        bool keeps = mine && chunk.FirstStrand < _chunkMaxRest.Length;
        float maxRest = substep > 0 && keeps ? _chunkMaxRest[chunk.FirstStrand] : ChunkMaxRest(chunk);
        if (substep == 0 && keeps) _chunkMaxRest[chunk.FirstStrand] = maxRest;
        ref int live = ref Unsafe.Add(ref MemoryMarshal.GetArrayDataReference(scene.World.StrandParticleCount), chunk.FirstStrand);
        var rows = new Rows(chunk);
        // Each row's lower bound and move from its record (Kernel.Classify), 16 lanes per row.
        Vector512<float>* lower = stackalloc Vector512<float>[StrandChunk.MaxRows];
        Vector512<float>* move = stackalloc Vector512<float>[StrandChunk.MaxRows];
        // One mesh after the other, as the reference does over its strands.
        for (int m = 0; m < colliders.Length; m++)
        {
            var mc = colliders[m];
            // Another scene's collider (a pipeline stepping a scene it was not built for): its pose for this substep.
            var pose = mine ? _poses[substep * colliders.Length + m] : new MeshCollideSystem.Pose(ctx.MeshPoseAt(substep, m, colliders));
            var field = mc.Field;
            fixed (float* data = field.Data, bricks = field.Bricks)
            {
                float* memo = CornerMemo.For(m, field);
                float* clear = memo + 2 * MemoFloats, midClear = memo + 2 * MemoFloats + ClearanceFloats;
                float* stamps = memo + 2 * MemoFloats + 2 * ClearanceFloats;
                var carry = carried ? _carry[m] : null;
                if (carry != null && _carryBase[m] + (long)CarryFloats * (chunk.Firsts[0] + L * chunk.Height) <= carry.Length)
                {
                    // Pinned: its records are read and written in place. Row o's stamp is at (first + o) / 8, which is
                    // first / 8 + o / 8 (o is a multiple of 8): no two rows share one.
                    clear = (float*)Unsafe.AsPointer(ref carry[_carryBase[m] + CarryFloats * chunk.Firsts[0]]);
                    stamps = (float*)Unsafe.AsPointer(ref _carryFar[m]![chunk.Firsts[0] >> 3]);
                }
                else
                {
                    carry = null;
                    // The thread's records are another chunk's at its first substep: none of this one's.
                    if (substep == 0) new Span<float>(stamps, chunk.Height * L / 8).Fill(float.NegativeInfinity);
                }
                var k = new Kernel(mc, data, bricks, maxRest, ctx.Settings.ContactSlide, in pose, memo, memo + MemoFloats, clear, midClear, stamps,
                    reuse: substep > 0 || carry != null, reuseMidpoints: substep > 0);
                // What the records settle, 16 lanes at a time, then each 8-lane column's walk over the rows where
                // something happens.
                for (int g = 0; g < L; g += 16)
                {
                    k.Classify(in rows, g, chunk.Height, lower, move, out ulong farA, out ulong boundedA, out ulong farB, out ulong boundedB);
                    k.Column(in rows, g, chunk.Height, Vector256.LoadUnsafe(ref live, (nuint)g), (Vector256<float>*)lower, (Vector256<float>*)move, farA, boundedA);
                    k.Column(in rows, g + 8, chunk.Height, Vector256.LoadUnsafe(ref live, (nuint)(g + 8)), (Vector256<float>*)lower + 1, (Vector256<float>*)move + 1, farB, boundedB);
                }
            }
        }
        return true;
    }

    /// <summary>The chunk's longest segment (rows 1 … height − 1 hold the segments' rest lengths).</summary>
    private static float ChunkMaxRest(scoped in StrandChunk chunk)
    {
        const int L = StrandChunk.Lanes;
        ref float rest0 = ref chunk.Row(StrandChunk.RestLength, 0);
        // maxps, not Vector256.Max (its IEEE −0/NaN handling is a chain of three instructions per row, and this runs
        // every substep): rest lengths are positive and finite. A row at a time, one accumulator per 8 lanes.
        Vector256<float> a = Vector256<float>.Zero, b = a, c = a, d = a;
        for (int i = L, n = chunk.Height * L; i < n; i += L)
        {
            a = Avx.Max(a, Vector256.LoadUnsafe(ref rest0, (nuint)i)); b = Avx.Max(b, Vector256.LoadUnsafe(ref rest0, (nuint)(i + 8)));
            c = Avx.Max(c, Vector256.LoadUnsafe(ref rest0, (nuint)(i + 16))); d = Avx.Max(d, Vector256.LoadUnsafe(ref rest0, (nuint)(i + 24)));
        }
        var longest = Avx.Max(Avx.Max(a, b), Avx.Max(c, d));
        float maxRest = 0f;
        for (int l = 0; l < 8; l++) maxRest = MathF.Max(maxRest, longest.GetElement(l));
        return maxRest;
    }

    /// <summary>Floats of one 8-lane row's corner memo: 8 cell indices and 8 corner values, 8 lanes each.</summary>
    private const int CornerFloats = 72;
    /// <summary>Floats of the particle (or the midpoint) memos of the tallest chunk: one per 8 lanes of each row.</summary>
    private const int MemoFloats = StrandChunk.MaxRows * StrandChunk.Lanes / 8 * CornerFloats;
    /// <summary>
    /// Floats of one 8-lane row's clearance record: head-space x, y, z where the row was last measured, and for a
    /// particle row the distance (a lower bound) measured there (laid out 16 lanes to a field, <see cref="RecordAt"/>),
    /// for a midpoint row the squared distance it may move (8 lanes to a field).
    /// </summary>
    private const int ClearFloats = 32;
    /// <summary>
    /// Where row o's particle records are (o = 32k + g): each 16 lanes of a row keep x, y, z and d as 16 floats each,
    /// so <see cref="Kernel.Classify"/> reads a field of 16 lanes with one load; an 8-lane column's record lies at
    /// g mod 16 in them.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static nuint RecordAt(nuint o) => (o & ~(nuint)15) * 4 + (o & 15);
    private const int RecordY = 16, RecordZ = 32, RecordD = 48;
    /// <summary>Floats of one mesh's memos per thread: particle and midpoint corners, then the rows' clearances.</summary>
    private const int ClearanceFloats = StrandChunk.MaxRows * StrandChunk.Lanes / 8 * ClearFloats;
    /// <summary>Floats of one mesh's row stamps per thread: one per 8-lane row, the far distance its record was written with.</summary>
    private const int StampFloats = StrandChunk.MaxRows * StrandChunk.Lanes / 8;
    private const int SlotFloats = 2 * MemoFloats + 2 * ClearanceFloats + StampFloats;
    /// <summary>
    /// 1/√3 less a margin: the trilinear field changes by at most √3 × a move (each axis's slope is a blend of grid
    /// differences of at most one cell per cell), and the brick bounds and exact samples it is compared against carry
    /// float roundings of about 1e-5 of the largest value.
    /// </summary>
    private const float ClearanceShare = 0.5770f;


    /// <summary>
    /// Each thread's corner memos, per mesh collider: a particle memo and a midpoint memo per row of a chunk (the
    /// chunk runs all its substeps on one thread). Pinned, made once per thread and mesh count; a memo made for another
    /// field is cleared before use, since a memo is only valid for the field it was gathered from.
    /// </summary>
    private sealed unsafe class CornerMemo
    {
        [ThreadStatic] private static CornerMemo? t_memo;
        private float[] _floats = [];
        private SignedDistanceField?[] _fields = [];

        public static float* For(int mesh, SignedDistanceField field)
        {
            var memo = t_memo ??= new CornerMemo();
            if (memo._fields.Length <= mesh)
            {
                var floats = GC.AllocateUninitializedArray<float>((mesh + 1) * SlotFloats + 16, pinned: true);
                memo._floats = floats;
                memo._fields = new SignedDistanceField?[mesh + 1];
            }
            // 64-byte aligned (16-lane loads of records do not split lines).
            ref float first = ref MemoryMarshal.GetArrayDataReference(memo._floats);
            float* base0 = (float*)Unsafe.AsPointer(ref first) + StrandScratch.ToLine(ref first);
            float* slot = base0 + mesh * SlotFloats;
            if (!ReferenceEquals(memo._fields[mesh], field))
            {
                // No cell has index −1: every lookup misses until a gather fills the row.
                for (int r = 0; r < 2 * MemoFloats; r += CornerFloats) Vector256.Create(-1).AsSingle().Store(slot + r);
                // Clearances are lower bounds of this field: none carried over from another (−1: never within).
                new Span<float>(slot + 2 * MemoFloats, 2 * ClearanceFloats).Fill(-1f);
                memo._fields[mesh] = field;
            }
            return slot;
        }
    }

    /// <summary>The chunk's rows the kernel reads and writes (row k of a field starts k · 32 floats after its row 0).</summary>
    private readonly ref struct Rows(in StrandChunk chunk)
    {
        public readonly ref float X = ref chunk.Row(StrandChunk.X, 0), Y = ref chunk.Row(StrandChunk.Y, 0), Z = ref chunk.Row(StrandChunk.Z, 0);
        public readonly ref float Vx = ref chunk.Row(StrandChunk.VelX, 0), Vy = ref chunk.Row(StrandChunk.VelY, 0), Vz = ref chunk.Row(StrandChunk.VelZ, 0);
        public readonly ref float M = ref chunk.Row(StrandChunk.InvMass, 0), Rest = ref chunk.Row(StrandChunk.RestLength, 0);
    }

    private unsafe readonly struct Kernel
    {
        private readonly float* _d, _bricks, _particleCorners, _midpointCorners, _clearance, _midpointClearance;
#if DEBUG
        private readonly SignedDistanceField _field; // for CheckBounds only: a reference in the kernel changes its release code
#endif
        private readonly float* _stamps;
        private readonly bool _reuse, _reuseMidpoints;
        private readonly float _farScalar;
        private readonly int _sy, _sz;
        private readonly Vector256<float> _ox, _oy, _oz, _inv, _cell, _hx, _hy, _hz, _margin, _threshold, _far, _slide, _tx, _ty, _tz;
        private readonly Vector256<float> _l00, _l01, _l02, _l10, _l11, _l12, _l20, _l21, _l22;
        private readonly Vector256<float> _w00, _w01, _w02, _w10, _w11, _w12, _w20, _w21, _w22;
        private readonly Vector256<int> _nx, _nxy, _bx, _bxy, _lastX, _lastY, _lastZ;

        public Kernel(MeshCollider mc, float* d, float* bricks, float maxRest, float slide, in MeshCollideSystem.Pose pose, float* particleCorners, float* midpointCorners,
            float* clearance, float* midpointClearance, float* stamps, bool reuse, bool reuseMidpoints)
        {
            _stamps = stamps;
            var f = mc.Field;
#if DEBUG
            _field = f;
#endif
            _d = d; _bricks = bricks; _particleCorners = particleCorners; _midpointCorners = midpointCorners; _clearance = clearance; _reuse = reuse; _reuseMidpoints = reuseMidpoints;
            _midpointClearance = midpointClearance;
            _sy = f.Nx; _sz = f.Nx * f.Ny;
            _ox = Vector256.Create(f.Origin.X); _oy = Vector256.Create(f.Origin.Y); _oz = Vector256.Create(f.Origin.Z);
            _inv = Vector256.Create(f.InvCell); _cell = Vector256.Create(f.CellSize);
            _hx = Vector256.Create((float)(f.Nx - 1)); _hy = Vector256.Create((float)(f.Ny - 1)); _hz = Vector256.Create((float)(f.Nz - 1));
            _margin = Vector256.Create(mc.Margin);
            float threshold = MeshCollideSystem.MidpointThreshold(mc);
            _threshold = Vector256.Create(threshold);
            _farScalar = FarDistance(mc, maxRest);
            _far = Vector256.Create(_farScalar);
            _slide = Vector256.Create(slide);
            _tx = Vector256.Create(pose.T.X); _ty = Vector256.Create(pose.T.Y); _tz = Vector256.Create(pose.T.Z);
            ref readonly var l = ref pose.ToLocal;
            _l00 = Vector256.Create(l.S00); _l01 = Vector256.Create(l.S01); _l02 = Vector256.Create(l.S02);
            _l10 = Vector256.Create(l.S10); _l11 = Vector256.Create(l.S11); _l12 = Vector256.Create(l.S12);
            _l20 = Vector256.Create(l.S20); _l21 = Vector256.Create(l.S21); _l22 = Vector256.Create(l.S22);
            ref readonly var w = ref pose.ToWorld;
            _w00 = Vector256.Create(w.S00); _w01 = Vector256.Create(w.S01); _w02 = Vector256.Create(w.S02);
            _w10 = Vector256.Create(w.S10); _w11 = Vector256.Create(w.S11); _w12 = Vector256.Create(w.S12);
            _w20 = Vector256.Create(w.S20); _w21 = Vector256.Create(w.S21); _w22 = Vector256.Create(w.S22);
            _nx = Vector256.Create(f.Nx); _nxy = Vector256.Create(f.Nx * f.Ny);
            _bx = Vector256.Create(f.BricksX); _bxy = Vector256.Create(f.BricksX * f.BricksY);
            _lastX = Vector256.Create(f.Nx - 2); _lastY = Vector256.Create(f.Ny - 2); _lastZ = Vector256.Create(f.Nz - 2);
        }

        /// <summary>
        /// Lanes g … g + 7 of the chunk, root to tip, as <see cref="MeshCollideSystem.Collide"/> walks each strand, with
        /// what <see cref="Classify"/> found: which rows are settled at the far distance and which with bounds, and a
        /// bounded row k's lower bound and move at <paramref name="lower"/>[2k] and <paramref name="move"/>[2k].
        /// </summary>
        public void Column(in Rows r, int g, int height, Vector256<int> live, Vector256<float>* lower, Vector256<float>* move, ulong far, ulong bounded)
        {
            const int L = StrandChunk.Lanes;
            // Rows pinned in every lane (the roots) are never moved, and neither is a segment between two of them:
            // such a row's distance is needed only as the previous one of a segment that can move. Skipping the rest
            // changes no decision and no value (the roots are always near the scalp, so these were exact samples).
            ulong pinned = 0;
            for (int k = 0; k < height; k++)
                pinned |= (AllPinned(in r, (nuint)(k * L + g)) ? 1UL : 0UL) << k;
            ulong rows = height == 64 ? ~0UL : (1UL << height) - 1;
            ulong skip = pinned & (pinned >> 1);
            // Rows to measure (neither far nor bounded), and segments to decide: both ends short of the far distance
            // (a row there starts no midpoint test, nor ends one: the far distance less half any segment of the chunk
            // is above the threshold), and not between two pinned rows.
            ulong measure = rows & ~(far | bounded | skip);
            ulong near = rows & ~far;
            ulong segments = near & (near << 1) & ~(pinned & (pinned << 1)) & ~skip;
            // Each row's distance as bounds: lo = hi where exact; a row settled by its record has lo below and hi above
            // the exact value in its "loose" lanes, measured only if a decision needs it.
            Vector256<float> prevLo = default, prevHi = default, prevLoose = default;
            int last = -2;
            for (ulong active = measure | segments; active != 0; active &= active - 1)
            {
                int k = BitOperations.TrailingZeroCount(active);
                nuint o = (nuint)(k * L + g);
                Vector256<float> lo, hi, loose;
                if ((measure >> k & 1) != 0) { lo = PushOutMeasured(in r, o, out hi); loose = Vector256<float>.Zero; }
                else { lo = lower[2 * k]; hi = UpperBound(o, move[2 * k]); loose = Vector256<float>.AllBitsSet; }
                if ((segments >> k & 1) != 0)
                {
                    nuint prevO = o - L;
                    // A previous row the walk did not visit was settled with bounds (not far, not pinned, not measured).
                    if (last != k - 1) { prevLo = lower[2 * k - 2]; prevHi = UpperBound(prevO, move[2 * k - 2]); prevLoose = Vector256<float>.AllBitsSet; }
                    var alive = Vector256.GreaterThan(live, Vector256.Create(k)).AsSingle();
                    var half = Vector256.Create(0.5f) * Vector256.LoadUnsafe(ref r.Rest, o);
                    // The reference's test is monotone in both distances: where the lower bounds say no test, or the
                    // upper bounds say test, the exact values say the same. Elsewhere the exact values decide.
                    var test = alive & Vector256.LessThan(Avx.Max(prevLo, lo) - half, _threshold);
                    // (max(a, b) − h < t) is (a − h < t) and (b − h < t): an end whose upper bound passes is not what
                    // leaves a lane open, so only the other end is measured.
                    var prevBelow = Vector256.LessThan(prevHi - half, _threshold);
                    var below = Vector256.LessThan(hi - half, _threshold);
                    var open = test & ~(prevBelow & below);
                    if (open != Vector256<float>.Zero)
                    {
                        if ((open & ~prevBelow & prevLoose) != Vector256<float>.Zero) Measure(r, prevO, ref prevLoose, ref prevLo, ref prevHi);
                        if ((open & ~below & loose) != Vector256<float>.Zero) Measure(r, o, ref loose, ref lo, ref hi);
                        test = alive & Vector256.LessThan(Avx.Max(prevLo, lo) - half, _threshold);
                    }
                    if (test != Vector256<float>.Zero)
                    {
                        lo = Midpoint(test, r, prevO, o, lo, out var hit);
                        hi = Vector256.ConditionalSelect(hit, lo, hi);
                        loose = Vector256.AndNot(loose, hit);
                    }
                }
                prevLo = lo; prevHi = hi; prevLoose = loose; last = k;
            }
        }

        /// <summary>
        /// What each row's record settles, for lanes g … g + 15 (two columns: A is g … g + 7, B the next 8), one row at a
        /// time without a branch, so the walk visits only rows where something happens. A row's place and record are
        /// read before the walk: the walk moves a row only after reading it as its present row, so the bits are the
        /// same. <paramref name="farA"/>, <paramref name="farB"/>: rows every lane of which is still within its clearance
        /// of its last measure (the distance beyond the far distance, over √3: the field changes by at most √3 × a
        /// move), so neither pushed nor starting a midpoint test; <paramref name="boundedA"/>, <paramref name="boundedB"/>:
        /// the other rows whose lanes all stay above the margin by √3 × their move (not pushed; the exact value lies
        /// within the record ± √3 × the move, whose lower end goes to <paramref name="lower"/> and the move to
        /// <paramref name="move"/>). Nothing is settled where no record is read (a chunk's first substep without
        /// carried records).
        /// </summary>
        public void Classify(in Rows r, int g, int height, Vector512<float>* lower, Vector512<float>* move, out ulong farA, out ulong boundedA, out ulong farB, out ulong boundedB)
        {
            farA = boundedA = farB = boundedB = 0;
            if (!_reuse) return;
            // The kernel's constants in locals (registers): the stores below go through pointers, which could alias
            // the kernel's fields, so the JIT would read each field again on every row.
            var tx = Vector512.Create(_tx.ToScalar()); var ty = Vector512.Create(_ty.ToScalar()); var tz = Vector512.Create(_tz.ToScalar());
            var l00 = Vector512.Create(_l00.ToScalar()); var l01 = Vector512.Create(_l01.ToScalar()); var l02 = Vector512.Create(_l02.ToScalar());
            var l10 = Vector512.Create(_l10.ToScalar()); var l11 = Vector512.Create(_l11.ToScalar()); var l12 = Vector512.Create(_l12.ToScalar());
            var l20 = Vector512.Create(_l20.ToScalar()); var l21 = Vector512.Create(_l21.ToScalar()); var l22 = Vector512.Create(_l22.ToScalar());
            var farDistance = Vector512.Create(_farScalar); var margin = Vector512.Create(_margin.ToScalar());
            var share = Vector512.Create(ClearanceShare); var inverseShare = Vector512.Create(1f / ClearanceShare);
            float* records = _clearance;
            ulong fa = 0, ba = 0, fb = 0, bb = 0;
            ref float rx = ref r.X, ry = ref r.Y, rz = ref r.Z;
            for (int k = 0; k < height; k++)
            {
                nuint o = (nuint)(k * StrandChunk.Lanes + g);
                var x = Vector512.LoadUnsafe(ref rx, o) - tx; var y = Vector512.LoadUnsafe(ref ry, o) - ty; var z = Vector512.LoadUnsafe(ref rz, o) - tz;
                var lx = l00 * x + l01 * y + l02 * z; var ly = l10 * x + l11 * y + l12 * z; var lz = l20 * x + l21 * y + l22 * z;
                float* clear = records + RecordAt(o);
                var mx = lx - Vector512.Load(clear); var my = ly - Vector512.Load(clear + RecordY); var mz = lz - Vector512.Load(clear + RecordZ);
                var m2 = mx * mx + my * my + mz * mz;
                var recorded = Vector512.Load(clear + RecordD);
                // maxps: squared below, so ±0 alike.
                var c = Avx512F.Max(recorded - farDistance, Vector512<float>.Zero) * share;
                ulong isFar = Vector512.ExtractMostSignificantBits(Vector512.LessThan(m2, c * c));
                if (isFar == 0xFFFF)
                {
                    // Far in all 16 lanes (both columns): the walk never reads this row's bounds, so no root for them.
                    fa |= 1UL << k; fb |= 1UL << k;
                    continue;
                }
                var m = Vector512.Sqrt(m2) * inverseShare;
                var lw = recorded - m;
                lower[k] = lw; move[k] = m;
                ulong isAbove = Vector512.ExtractMostSignificantBits(Vector512.GreaterThanOrEqual(lw, margin)) & ~isFar;
                // All 8 lanes of a column: (mask + 1) >> 8 is 1 for 0xFF, else 0.
                fa |= ((isFar & 0xFF) + 1 >> 8) << k; fb |= ((isFar >> 8) + 1 >> 8) << k;
                ba |= ((isAbove & 0xFF) + 1 >> 8) << k; bb |= ((isAbove >> 8) + 1 >> 8) << k;
            }
            farA = fa; boundedA = ba; farB = fb; boundedB = bb;
            CheckSettled(in r, g, height, (Vector256<float>*)lower, (Vector256<float>*)move, farA, boundedA);
            CheckSettled(in r, g + 8, height, (Vector256<float>*)lower + 1, (Vector256<float>*)move + 1, farB, boundedB);
        }

        /// <summary>Debug builds: every row of column g that its record settled, checked against the reference's distance (<see cref="CheckBounds"/>).</summary>
        [Conditional("DEBUG")]
        private void CheckSettled(in Rows r, int g, int height, Vector256<float>* lower, Vector256<float>* move, ulong far, ulong bounded)
        {
            for (int k = 0; k < height; k++)
            {
                if (((far | bounded) >> k & 1) == 0) continue;
                nuint o = (nuint)(k * StrandChunk.Lanes + g);
                var x = Vector256.LoadUnsafe(ref r.X, o); var y = Vector256.LoadUnsafe(ref r.Y, o); var z = Vector256.LoadUnsafe(ref r.Z, o);
                ToLocal(x - _tx, y - _ty, z - _tz, out var lx, out var ly, out var lz);
                if ((far >> k & 1) != 0) CheckBounds(lx, ly, lz, _far, Vector256.Create(float.PositiveInfinity));
                else { Counts.Add(ref Counts.BoundedRows); CheckBounds(lx, ly, lz, lower[2 * k], UpperBound(o, move[2 * k])); }
            }
        }

        /// <summary>
        /// The upper bound of row o's distance its record gives with the move <paramref name="m"/> (√3 × the move, from
        /// <see cref="Classify"/>): the record plus the move where the record is exact (below the far distance of the
        /// visit that wrote it), else none.
        /// </summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        private Vector256<float> UpperBound(nuint o, Vector256<float> m)
        {
            var recorded = Vector256.Load(_clearance + RecordAt(o) + RecordD);
            var exact = Vector256.LessThan(recorded, Vector256.Create(_stamps[o / 8]));
            return Vector256.ConditionalSelect(exact, recorded + m, Vector256.Create(float.PositiveInfinity));
        }

        /// <summary>
        /// The exact distances of row o's loose lanes (lanes settled by their record, not moved since): lo and hi
        /// become the value the reference has. The row is measured afresh, and that is recorded.
        /// </summary>
        private void Measure(in Rows r, nuint o, ref Vector256<float> loose, ref Vector256<float> lo, ref Vector256<float> hi)
        {
            var x = Vector256.LoadUnsafe(ref r.X, o); var y = Vector256.LoadUnsafe(ref r.Y, o); var z = Vector256.LoadUnsafe(ref r.Z, o);
            ToLocal(x - _tx, y - _ty, z - _tz, out var lx, out var ly, out var lz);
            var d = Distance(lx, ly, lz, _particleCorners + o * CornerFloats / 8);
            Record(o, lx, ly, lz, d);
            lo = Vector256.ConditionalSelect(loose, d, lo);
            hi = Vector256.ConditionalSelect(loose, Upper(d), hi);
            loose = Vector256<float>.Zero;
            Counts.Add(ref Counts.Measured);
        }

        /// <summary>
        /// Debug builds check every row a record settled, like a NaN checker: at each lane, the reference's distance lies
        /// within the bounds the record gave (the field changes by at most √3 × a move, inside the grid and out).
        /// </summary>
        [Conditional("DEBUG")]
        private void CheckBounds(Vector256<float> lx, Vector256<float> ly, Vector256<float> lz, Vector256<float> lo, Vector256<float> hi)
        {
#if DEBUG
            var f = _field;
            for (int l = 0; l < 8; l++)
            {
                float x = lx.GetElement(l), y = ly.GetElement(l), z = lz.GetElement(l);
                float d = f.DistanceAt(x, y, z), slack = 1e-5f * (MathF.Abs(d) + f.CellSize);
                if (d < lo.GetElement(l) - slack || d > hi.GetElement(l) + slack)
                    throw new InvalidOperationException($"A mesh record settled lane {l} at ({x}, {y}, {z}) within [{lo.GetElement(l)}, {hi.GetElement(l)}], where the field is {d}.");
            }
#endif
        }

        /// <summary>An upper bound of a distance from <see cref="Distance"/>: itself below the far distance (exact), else none.</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        private Vector256<float> Upper(Vector256<float> d) =>
            Vector256.ConditionalSelect(Vector256.LessThan(d, _far), d, Vector256.Create(float.PositiveInfinity));

        /// <summary>Remembers where row o was measured and what (a lower bound; exact below the far distance, which is stamped with it).</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        private void Record(nuint o, Vector256<float> lx, Vector256<float> ly, Vector256<float> lz, Vector256<float> d)
        {
            float* clear = _clearance + RecordAt(o);
            lx.Store(clear); ly.Store(clear + RecordY); lz.Store(clear + RecordZ); d.Store(clear + RecordD);
            _stamps[o / 8] = _farScalar;
        }

        /// <summary>Every lane of the row at o pinned (inverse mass 0).</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        private static bool AllPinned(in Rows r, nuint o) => Vector256.EqualsAll(Vector256.LoadUnsafe(ref r.M, o), Vector256<float>.Zero);

        /// <summary>Head space: Rᵀ(p − t).</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        private void ToLocal(Vector256<float> x, Vector256<float> y, Vector256<float> z, out Vector256<float> lx, out Vector256<float> ly, out Vector256<float> lz)
        {
            lx = _l00 * x + _l01 * y + _l02 * z;
            ly = _l10 * x + _l11 * y + _l12 * z;
            lz = _l20 * x + _l21 * y + _l22 * z;
        }

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        private void ToWorld(Vector256<float> x, Vector256<float> y, Vector256<float> z, out Vector256<float> wx, out Vector256<float> wy, out Vector256<float> wz)
        {
            wx = _w00 * x + _w01 * y + _w02 * z;
            wy = _w10 * x + _w11 * y + _w12 * z;
            wz = _w20 * x + _w21 * y + _w22 * z;
        }

        /// <summary>Row o measured, recorded and pushed out to the margin as <see cref="PushOut"/> does: returns the distances, and in <paramref name="hi"/> their upper bounds.</summary>
        private Vector256<float> PushOutMeasured(in Rows r, nuint o, out Vector256<float> hi)
        {
            var x = Vector256.LoadUnsafe(ref r.X, o); var y = Vector256.LoadUnsafe(ref r.Y, o); var z = Vector256.LoadUnsafe(ref r.Z, o);
            ToLocal(x - _tx, y - _ty, z - _tz, out var lx, out var ly, out var lz);
            var d = Distance(lx, ly, lz, _particleCorners + o * CornerFloats / 8);
            Record(o, lx, ly, lz, d);
            d = Push(Vector256<float>.AllBitsSet, r, o, x, y, z, lx, ly, lz, d);
            hi = Upper(d);
            return d;
        }

        /// <summary>The particles of row o in <paramref name="mask"/> pushed out to the margin (MeshCollideSystem.PushOut); returns their distances.</summary>
        private Vector256<float> PushOut(Vector256<float> mask, in Rows r, nuint o)
        {
            var x = Vector256.LoadUnsafe(ref r.X, o); var y = Vector256.LoadUnsafe(ref r.Y, o); var z = Vector256.LoadUnsafe(ref r.Z, o);
            ToLocal(x - _tx, y - _ty, z - _tz, out var lx, out var ly, out var lz);
            var d = Distance(lx, ly, lz, _particleCorners + o * CornerFloats / 8);
            return Push(mask, r, o, x, y, z, lx, ly, lz, d);
        }

        /// <summary>Pushes the lanes in <paramref name="mask"/> below the margin out (up to three steps); returns the distances after.</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        private Vector256<float> Push(Vector256<float> mask, in Rows r, nuint o, Vector256<float> x, Vector256<float> y, Vector256<float> z,
            Vector256<float> lx, Vector256<float> ly, Vector256<float> lz, Vector256<float> d)
        {
            float* corners = _particleCorners + o * CornerFloats / 8;
            var push = mask & Vector256.LessThan(d, _margin) & ~Vector256.Equals(Vector256.LoadUnsafe(ref r.M, o), Vector256<float>.Zero);
            if (push == Vector256<float>.Zero) return d;
            var running = push;
            for (int it = 0; it < 3; it++)
            {
                Gradient(lx, ly, lz, running, corners, out var gx, out var gy, out var gz);
                var g2 = gx * gx + gy * gy + gz * gz;
                running &= Vector256.GreaterThan(g2, Vector256.Create(1e-12f));
                if (running == Vector256<float>.Zero) break;
                var len = Vector256.Sqrt(g2);
                var amount = _margin - d;
                var nx = gx / len; var ny = gy / len; var nz = gz / len;
                lx = Vector256.ConditionalSelect(running, lx + nx * amount, lx);
                ly = Vector256.ConditionalSelect(running, ly + ny * amount, ly);
                lz = Vector256.ConditionalSelect(running, lz + nz * amount, lz);
                ToWorld(nx, ny, nz, out var wnx, out var wny, out var wnz);
                RemoveInward(running, wnx, wny, wnz, r, o);
                d = Vector256.ConditionalSelect(running, Distance(lx, ly, lz, corners), d);
                running &= Vector256.LessThan(d, _margin);
                if (running == Vector256<float>.Zero) break;
            }
            ToWorld(lx, ly, lz, out var px, out var py, out var pz);
            Vector256.ConditionalSelect(push, px + _tx, x).StoreUnsafe(ref r.X, o);
            Vector256.ConditionalSelect(push, py + _ty, y).StoreUnsafe(ref r.Y, o);
            Vector256.ConditionalSelect(push, pz + _tz, z).StoreUnsafe(ref r.Z, o);
            return d;
        }

        /// <summary>The midpoint test of the segments ending at row o1 (lanes in <paramref name="test"/>); returns the distances of row o1.</summary>
        private Vector256<float> Midpoint(Vector256<float> test, in Rows r, nuint o0, nuint o1, Vector256<float> d, out Vector256<float> hit)
        {
            hit = Vector256<float>.Zero;
            var half = Vector256.Create(0.5f);
            var x0 = Vector256.LoadUnsafe(ref r.X, o0); var y0 = Vector256.LoadUnsafe(ref r.Y, o0); var z0 = Vector256.LoadUnsafe(ref r.Z, o0);
            var x1 = Vector256.LoadUnsafe(ref r.X, o1); var y1 = Vector256.LoadUnsafe(ref r.Y, o1); var z1 = Vector256.LoadUnsafe(ref r.Z, o1);
            ToLocal(half * (x0 + x1) - _tx, half * (y0 + y1) - _ty, half * (z0 + z1) - _tz, out var lx, out var ly, out var lz);
            // Every tested midpoint still within its clearance of where it was last measured: none can be inside the margin.
            float* clear = _midpointClearance + o1 * ClearFloats / 8;
            if (_reuseMidpoints)
            {
                var mx = lx - Vector256.Load(clear); var my = ly - Vector256.Load(clear + 8); var mz = lz - Vector256.Load(clear + 16);
                var within = Vector256.LessThan(mx * mx + my * my + mz * mz, Vector256.Load(clear + 24));
                if (Vector256.EqualsAll((within | ~test).AsInt32(), Vector256<int>.AllBitsSet)) return d;
            }
            // Only midpoints whose brick reaches below the margin can be pushed.
            var inside = Grid(lx, ly, lz, out var ix, out var iy, out var iz, out var fx, out var fy, out var fz);
            var near = test & inside;
            if (near == Vector256<float>.Zero) return d;
            var brick = Brick(ix, iy, iz);
            near &= Vector256.LessThan(brick, _margin);
            if (near == Vector256<float>.Zero)
            {
                Clearance(clear, lx, ly, lz, inside & brick);
                return d;
            }
            var dm = Sample(ix, iy, iz, fx, fy, fz, near, _midpointCorners + o1 * CornerFloats / 8, out var gx, out var gy, out var gz);
            Clearance(clear, lx, ly, lz, inside & Vector256.ConditionalSelect(near, dm, brick));
            var g2 = gx * gx + gy * gy + gz * gz;
            hit = near & Vector256.LessThan(dm, _margin) & Vector256.GreaterThan(g2, Vector256.Create(1e-12f));
            if (hit == Vector256<float>.Zero) return d;
            var len = Vector256.Sqrt(g2);
            ToWorld(gx / len, gy / len, gz / len, out var nx, out var ny, out var nz);
            var amount = _margin - dm;
            foreach (var o in (ReadOnlySpan<nuint>)[o0, o1])
            {
                var move = hit & ~Vector256.Equals(Vector256.LoadUnsafe(ref r.M, o), Vector256<float>.Zero);
                if (move == Vector256<float>.Zero) continue;
                var x = Vector256.LoadUnsafe(ref r.X, o); var y = Vector256.LoadUnsafe(ref r.Y, o); var z = Vector256.LoadUnsafe(ref r.Z, o);
                Vector256.ConditionalSelect(move, x + nx * amount, x).StoreUnsafe(ref r.X, o);
                Vector256.ConditionalSelect(move, y + ny * amount, y).StoreUnsafe(ref r.Y, o);
                Vector256.ConditionalSelect(move, z + nz * amount, z).StoreUnsafe(ref r.Z, o);
                RemoveInward(move, nx, ny, nz, r, o);
            }
            // Lifting a segment over a thin part (an ear) can push an end into it from the other side.
            PushOut(hit, r, o0);
            return Vector256.ConditionalSelect(hit, PushOut(hit, r, o1), d);
        }

        /// <summary>
        /// Remembers midpoints measured at least <paramref name="value"/> from the surface (a lower bound; zero for lanes
        /// not measured): each may move (value − margin)/√3 before it could be inside the margin.
        /// </summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        private void Clearance(float* clear, Vector256<float> lx, Vector256<float> ly, Vector256<float> lz, Vector256<float> value)
        {
            var c = Avx.Max(value - _margin, Vector256<float>.Zero) * Vector256.Create(ClearanceShare);
            lx.Store(clear); ly.Store(clear + 8); lz.Store(clear + 16); (c * c).Store(clear + 24);
        }

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        private void RemoveInward(Vector256<float> mask, Vector256<float> nx, Vector256<float> ny, Vector256<float> nz, in Rows r, nuint o)
        {
            var vx = Vector256.LoadUnsafe(ref r.Vx, o); var vy = Vector256.LoadUnsafe(ref r.Vy, o); var vz = Vector256.LoadUnsafe(ref r.Vz, o);
            var vn = vx * nx + vy * ny + vz * nz;
            var m = mask & Vector256.LessThan(vn, Vector256<float>.Zero);
            if (m == Vector256<float>.Zero) return;
            Vector256.ConditionalSelect(m, (vx - vn * nx) * _slide, vx).StoreUnsafe(ref r.Vx, o);
            Vector256.ConditionalSelect(m, (vy - vn * ny) * _slide, vy).StoreUnsafe(ref r.Vy, o);
            Vector256.ConditionalSelect(m, (vz - vn * nz) * _slide, vz).StoreUnsafe(ref r.Vz, o);
        }

        /// <summary>The lanes whose grid coordinates lie in a cell of the grid (0 ≤ g &lt; n − 1 on every axis).</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        private Vector256<float> Inside(Vector256<float> gx, Vector256<float> gy, Vector256<float> gz) =>
            Vector256.GreaterThanOrEqual(gx, Vector256<float>.Zero) & Vector256.GreaterThanOrEqual(gy, Vector256<float>.Zero)
            & Vector256.GreaterThanOrEqual(gz, Vector256<float>.Zero) & Vector256.LessThan(gx, _hx) & Vector256.LessThan(gy, _hy) & Vector256.LessThan(gz, _hz);

        /// <summary>Grid coordinates of head-space points: the lanes inside the grid (the others get cell 0).</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        private Vector256<float> Grid(Vector256<float> lx, Vector256<float> ly, Vector256<float> lz, out Vector256<int> ix, out Vector256<int> iy, out Vector256<int> iz,
            out Vector256<float> fx, out Vector256<float> fy, out Vector256<float> fz)
        {
            var gx = (lx - _ox) * _inv; var gy = (ly - _oy) * _inv; var gz = (lz - _oz) * _inv;
            return Cells(ref gx, ref gy, ref gz, out ix, out iy, out iz, out fx, out fy, out fz);
        }

        /// <summary>Cells and fractions of grid coordinates (g is left masked to the grid: 0 outside).</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        private Vector256<float> Cells(ref Vector256<float> gx, ref Vector256<float> gy, ref Vector256<float> gz, out Vector256<int> ix, out Vector256<int> iy, out Vector256<int> iz,
            out Vector256<float> fx, out Vector256<float> fy, out Vector256<float> fz)
        {
            var inside = Inside(gx, gy, gz);
            gx &= inside; gy &= inside; gz &= inside;
            ix = Avx.ConvertToVector256Int32WithTruncation(gx); iy = Avx.ConvertToVector256Int32WithTruncation(gy); iz = Avx.ConvertToVector256Int32WithTruncation(gz);
            fx = gx - Avx.ConvertToVector256Single(ix); fy = gy - Avx.ConvertToVector256Single(iy); fz = gz - Avx.ConvertToVector256Single(iz);
            return inside;
        }

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        private Vector256<float> Brick(Vector256<int> ix, Vector256<int> iy, Vector256<int> iz)
        {
            const byte S = SignedDistanceField.BrickShift;
            var b = Vector256.ShiftRightLogical(ix, S) + _bx * Vector256.ShiftRightLogical(iy, S) + _bxy * Vector256.ShiftRightLogical(iz, S);
            return Avx2.GatherVector256(_bricks, b, 4);
        }

        /// <summary>
        /// The field at head-space points (outside the grid, the field at its nearest point plus the distance to it, as
        /// SignedDistanceField.Outside), exact where a decision could depend on it, else a lower bound at or above the
        /// far threshold.
        /// </summary>
        private Vector256<float> Distance(Vector256<float> lx, Vector256<float> ly, Vector256<float> lz, float* corners)
        {
            var gx = (lx - _ox) * _inv; var gy = (ly - _oy) * _inv; var gz = (lz - _oz) * _inv;
            var inside = Inside(gx, gy, gz);
            bool allInside = inside == Vector256<float>.AllBitsSet;
            var beyond = Vector256<float>.Zero;
            if (!allInside)
            {
                // Outside lanes move to the grid's nearest point; beyond is the distance to it (maxps and minps, as
                // the reference's comparisons: a NaN clamps to 0, and its distance stays NaN).
                var zero = Vector256<float>.Zero;
                var cx = Avx.Min(Avx.Max(gx, zero), _hx); var cy = Avx.Min(Avx.Max(gy, zero), _hy); var cz = Avx.Min(Avx.Max(gz, zero), _hz);
                var ex = gx - cx; var ey = gy - cy; var ez = gz - cz;
                beyond = Vector256.Sqrt(ex * ex + ey * ey + ez * ez) * _cell;
                gx = cx; gy = cy; gz = cz;
            }
            var ix = Avx.ConvertToVector256Int32WithTruncation(gx); var iy = Avx.ConvertToVector256Int32WithTruncation(gy); var iz = Avx.ConvertToVector256Int32WithTruncation(gz);
            // A point on the top face lies in the last cell at fraction 1.
            if (!allInside) { ix = Avx2.Min(ix, _lastX); iy = Avx2.Min(iy, _lastY); iz = Avx2.Min(iz, _lastZ); }
            var fx = gx - Avx.ConvertToVector256Single(ix); var fy = gy - Avx.ConvertToVector256Single(iy); var fz = gz - Avx.ConvertToVector256Single(iz);
            var bound = Brick(ix, iy, iz);
            if (!allInside) bound += beyond;
            var exact = Vector256.LessThan(bound, _far);
            if (exact == Vector256<float>.Zero) return bound;
            Corners(ix + _nx * iy + _nxy * iz, exact, corners, out var d000, out var d100, out var d010, out var d110, out var d001, out var d101, out var d011, out var d111);
            var x00 = d000 + fx * (d100 - d000); var x10 = d010 + fx * (d110 - d010);
            var x01 = d001 + fx * (d101 - d001); var x11 = d011 + fx * (d111 - d011);
            var y0 = x00 + fy * (x10 - x00); var y1 = x01 + fy * (x11 - x01);
            var value = y0 + fz * (y1 - y0);
            if (!allInside) value = Vector256.ConditionalSelect(inside, value, value + beyond);
            return Vector256.ConditionalSelect(exact, value, bound);
        }

        /// <summary>
        /// The eight corner values of cells i. An 8-lane row remembers the last cells it gathered and their values
        /// (<paramref name="memo"/>: 8 cell indices, then the 8 corners, 8 lanes each): hair near the mesh stays in its
        /// cells from one substep to the next (81 % of such rows in all 8 lanes, 97 % of lanes, head shaking), and the
        /// chunk runs all its substeps on one thread, so most samples after a chunk's first substep read 9 vectors
        /// from L1 instead of 8 gathers. A memo holds field values, so a hit gives the bits a gather would.
        /// </summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        private void Corners(Vector256<int> i, Vector256<float> need, float* memo, out Vector256<float> d000, out Vector256<float> d100, out Vector256<float> d010, out Vector256<float> d110,
            out Vector256<float> d001, out Vector256<float> d101, out Vector256<float> d011, out Vector256<float> d111)
        {
            // Only the lanes whose values are used must match: the others take the memo's values and drop them.
            if (Vector256.EqualsAll(Vector256.Equals(Vector256.Load((int*)memo), i) | ~need.AsInt32(), Vector256<int>.AllBitsSet))
            {
                d000 = Vector256.Load(memo + 8); d100 = Vector256.Load(memo + 16); d010 = Vector256.Load(memo + 24); d110 = Vector256.Load(memo + 32);
                d001 = Vector256.Load(memo + 40); d101 = Vector256.Load(memo + 48); d011 = Vector256.Load(memo + 56); d111 = Vector256.Load(memo + 64);
                return;
            }
            float* d = _d;
            int sy = _sy, sz = _sz;
            Pair(d, i, out d000, out d100); Pair(d + sy, i, out d010, out d110);
            Pair(d + sz, i, out d001, out d101); Pair(d + sz + sy, i, out d011, out d111);
            i.AsSingle().Store(memo);
            d000.Store(memo + 8); d100.Store(memo + 16); d010.Store(memo + 24); d110.Store(memo + 32);
            d001.Store(memo + 40); d101.Store(memo + 48); d011.Store(memo + 56); d111.Store(memo + 64);
        }

        /// <summary>
        /// Each lane's two neighbours along x, d[i] and d[i + 1], gathered as one 8-byte element (half the gathered
        /// elements of two float gathers), then split into the two values in lane order.
        /// </summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        private static void Pair(float* d, Vector256<int> i, out Vector256<float> lo, out Vector256<float> hi)
        {
            var a = Avx2.GatherVector256((long*)d, i.GetLower(), 4).AsSingle();   // lanes 0 … 3: (lo, hi) pairs
            var b = Avx2.GatherVector256((long*)d, i.GetUpper(), 4).AsSingle();   // lanes 4 … 7
            // Even floats are the lo values, odd the hi, in lane order 0 1 4 5 2 3 6 7: swap the middle 8-byte blocks.
            lo = Avx2.Permute4x64(Avx.Shuffle(a, b, 0b10_00_10_00).AsDouble(), 0b11_01_10_00).AsSingle();
            hi = Avx2.Permute4x64(Avx.Shuffle(a, b, 0b11_01_11_01).AsDouble(), 0b11_01_10_00).AsSingle();
        }

        /// <summary>The field's gradient at head-space points (zero outside the grid), as SignedDistanceField.SampleAt.</summary>
        private void Gradient(Vector256<float> lx, Vector256<float> ly, Vector256<float> lz, Vector256<float> need, float* corners, out Vector256<float> gx, out Vector256<float> gy, out Vector256<float> gz)
        {
            var inside = Grid(lx, ly, lz, out var ix, out var iy, out var iz, out var fx, out var fy, out var fz);
            Sample(ix, iy, iz, fx, fy, fz, need, corners, out gx, out gy, out gz);
            gx &= inside; gy &= inside; gz &= inside;
        }

        /// <summary>Value and gradient in the cells (ix, iy, iz) at fractions (fx, fy, fz): SignedDistanceField.SampleAt's arithmetic.</summary>
        private Vector256<float> Sample(Vector256<int> ix, Vector256<int> iy, Vector256<int> iz, Vector256<float> fx, Vector256<float> fy, Vector256<float> fz,
            Vector256<float> need, float* corners, out Vector256<float> gx, out Vector256<float> gy, out Vector256<float> gz)
        {
            Corners(ix + _nx * iy + _nxy * iz, need, corners, out var d000, out var d100, out var d010, out var d110, out var d001, out var d101, out var d011, out var d111);
            var x00 = d000 + fx * (d100 - d000); var x10 = d010 + fx * (d110 - d010);
            var x01 = d001 + fx * (d101 - d001); var x11 = d011 + fx * (d111 - d011);
            var y0 = x00 + fy * (x10 - x00); var y1 = x01 + fy * (x11 - x01);
            var one = Vector256<float>.One;
            var ux = one - fy; var uz = one - fz;
            gx = (uz * (ux * (d100 - d000) + fy * (d110 - d010)) + fz * (ux * (d101 - d001) + fy * (d111 - d011))) * _inv;
            gy = (uz * (x10 - x00) + fz * (x11 - x01)) * _inv;
            gz = (y1 - y0) * _inv;
            return y0 + fz * (y1 - y0);
        }
    }
}
