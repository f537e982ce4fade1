using System.Numerics;
using System.Runtime.Intrinsics.X86;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using System.Runtime.Intrinsics;

namespace HairSim.Fast;

/// <summary>
/// A strand chunk: 32 uncut 16-particle strands, laid out as rows (row k = particle k of each strand, 32 lanes),
/// the struct-of-arrays block of a DOTS archetype chunk. It lives on the stack (≈ 61 KB, about L1-sized) for one
/// frame: positions and velocities are transposed in once and out once, and every substep of every system runs on
/// its rows in between, so the length sweep needs no transposes of its own (it did 11 per substep) and the other
/// systems read L1 instead of L2. Slots 0 … 7 are <see cref="FastLengthSystem"/>'s tile fields, so its sweep runs on
/// a chunk unchanged.
/// </summary>
internal readonly ref struct StrandChunk
{
    public const int Lanes = 32, Rows = 16, Cells = Lanes * Rows;
    /// <summary>The tallest chunk: strands of up to 64 particles ride in chunks (the tile is sized per frame to the groom's longest strand).</summary>
    public const int MaxRows = 64;

    public const int X = FastLengthSystem.TX, Y = FastLengthSystem.TY, Z = FastLengthSystem.TZ,
        KickX = FastLengthSystem.TVx, KickY = FastLengthSystem.TVy, KickZ = FastLengthSystem.TVz,
        InvMass = FastLengthSystem.TM, RestLength = FastLengthSystem.TL,
        // From here on the length tile's PBD-only fields are reused (a chunk never runs PBD).
        VelX = 8, VelY = 9, VelZ = 10, ShapePrev = 11, ShapeMid = 12, ShapeNext = 13, RestX = 14, RestY = 15, RestZ = 16,
        // Shape-matching goals (prev, mid, next) × xyz, rows −1 … 16 (see GoalRow).
        Goals = 17,
        // The bend sweep's per-strand rest directions and joint shares (FastBendSystem), filled per chunk.
        BendRestX = 26, BendRestY = 27, BendRestZ = 28, BendA = 29, BendB = 30, FieldCount = 31;

    /// <summary>Rows −1 … 16: goal rows past both ends stay zero, so goal sums need no masks.</summary>
    public const int Capacity = (Rows + 2) * Lanes;

    /// <summary>Floats per field of a tile <paramref name="rows"/> tall (two spare rows for the goals).</summary>
    public static int CapacityFor(int rows) => (rows + 2) * Lanes;

    public static int SizeFor(int rows) => StrandScratch.Size(CapacityFor(rows), FieldCount);

    public readonly StrandScratch Tile;
    /// <summary>First particle of each lane's strand.</summary>
    public readonly ReadOnlySpan<int> Firsts;
    /// <summary>Bit k set: row k holds a pinned particle (its rest position is in the rest rows).</summary>
    public readonly ulong PinnedRows;
    /// <summary>
    /// Rows in use: the strands' capacity (2 … 64; all 32 strands of a chunk have the same one). Rows from here on
    /// hold no particle of the strand; they are masked like the particles past a cut and never stored.
    /// </summary>
    public readonly int Height;
    /// <summary>
    /// Rows from here on are past every lane's cut (pins in every lane, put back as they were before the chunk is
    /// stored): the row sweeps and per-particle passes stop here, with the bits of going on (nothing there moves).
    /// <see cref="Height"/> for an uncut chunk.
    /// </summary>
    public readonly int LiveRows;
    /// <summary>The world index of the strand in lane 0 (lane l holds strand FirstStrand + l).</summary>
    public readonly int FirstStrand;

    /// <summary>The runner's prefetch of the next chunk (a <see cref="Prefetcher"/> on its stack), or 0: see <see cref="Prefetcher.Row"/>.</summary>
    public readonly nint Prefetch;

    /// <summary>
    /// This frame's far-row mask (a ulong on the runner's stack), or 0: the bend sweep writes bit k where some free lane
    /// of row k ends its substep inside the collider's far sphere, and the collision that follows it takes only those rows
    /// (see <see cref="StrandChunkRunner.FuseFarRows"/>).
    /// </summary>
    public readonly nint FarRows;

    public StrandChunk(StrandScratch tile, ReadOnlySpan<int> firsts, ulong pinnedRows, int height = Rows, int firstStrand = 0, nint prefetch = 0, int liveRows = -1,
        nint farRows = 0)
    {
        Tile = tile; Firsts = firsts; PinnedRows = pinnedRows; Height = height; FirstStrand = firstStrand; Prefetch = prefetch; FarRows = farRows;
        LiveRows = liveRows < 0 ? height : Math.Min(liveRows, height);
    }

    /// <summary>Calls of <see cref="Prefetcher.Row"/> a row-sweeping system makes per row: one per 16-lane half.</summary>
    public const int RowPrefetchCalls = 2;

    /// <summary>
    /// Whether the chunk from s0 still owns the per-chunk block its 32 strands' entries in <paramref name="owner"/> point
    /// to. Only its first and last strands are looked at: owners are written for whole chunks of 32 strands, and any
    /// other chunk overlapping this one covers one of its ends.
    /// </summary>
    public static bool OwnsBlock(int[] owner, int s0) => owner[s0] == s0 && owner[s0 + Lanes - 1] == s0;

    /// <summary>Marks the chunk from s0 as the owner of its 32 strands' entries in <paramref name="owner"/> (see <see cref="OwnsBlock"/>).</summary>
    public static void ClaimBlock(int[] owner, int s0) => owner.AsSpan(s0, Lanes).Fill(s0);

    /// <summary>Row <paramref name="row"/> of a particle field.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public ref float Row(int field, int row) => ref Unsafe.Add(ref Tile.Data[0], Tile.Offset(field) + row * Lanes);

    /// <summary>Row <paramref name="row"/> (−1 … 16) of goal component <paramref name="goal"/> (0 … 8).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public ref float GoalRow(int goal, int row) => ref Unsafe.Add(ref Tile.Data[0], Tile.Offset(Goals + goal) + (row + 1) * Lanes);

    /// <summary>Runs a per-particle kernel's 16-lane chunk over every cell (all lanes are live particles).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public void ForEachCell<TKernel>(ref TKernel kernel) where TKernel : struct, IWideParticleKernel =>
        ForEachCellOfRows(ref kernel, LiveRows == 64 ? ~0UL : (1UL << LiveRows) - 1);

    /// <summary><see cref="ForEachCell"/> on the rows whose bits are set in <paramref name="rows"/> only (both halves of each).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public void ForEachCellOfRows<TKernel>(ref TKernel kernel, ulong rows) where TKernel : struct, IWideParticleKernel
    {
        ref float px = ref Row(X, 0), py = ref Row(Y, 0), pz = ref Row(Z, 0);
        ref float vx = ref Row(VelX, 0), vy = ref Row(VelY, 0), vz = ref Row(VelZ, 0), m = ref Row(InvMass, 0);
        ref float rx = ref Row(RestX, 0), ry = ref Row(RestY, 0), rz = ref Row(RestZ, 0);
        for (; rows != 0; rows &= rows - 1)
            for (int i = BitOperations.TrailingZeroCount(rows) * Lanes, end = i + Lanes; i < end; i += 16)
                kernel.Chunk16(ref Unsafe.Add(ref px, i), ref Unsafe.Add(ref py, i), ref Unsafe.Add(ref pz, i),
                    ref Unsafe.Add(ref vx, i), ref Unsafe.Add(ref vy, i), ref Unsafe.Add(ref vz, i),
                    ref Unsafe.Add(ref m, i), ref Unsafe.Add(ref rx, i), ref Unsafe.Add(ref ry, i), ref Unsafe.Add(ref rz, i));
    }
}

/// <summary>What a chunk must hold for a system, beyond positions, velocities and inverse masses.</summary>
[Flags]
internal enum ChunkFields
{
    None = 0,
    RestLength = 1,
    Shape = 2,
    /// <summary>Rest positions of the rows that hold pinned particles.</summary>
    PinRest = 4,
}

/// <summary>A fast substep system that can also run on a <see cref="StrandChunk"/> (same arithmetic per particle, same bits).</summary>
internal interface IStrandChunkSystem
{
    /// <summary>Whether this instance can run on chunks at all (the chunk kernels are 16-lane AVX-512 code).</summary>
    bool SupportsChunks { get; }
    ChunkFields ChunkNeeds => ChunkFields.None;
    /// <summary>
    /// Once per frame, before any chunk, on the calling thread: builds what every chunk of a substep shares (kernels,
    /// head poses), so no chunk builds it again. False: this frame's settings do not take the chunk kernel, and every
    /// strand goes through <see cref="IHairSystem.Run"/>.
    /// </summary>
    bool BeginChunkFrame(FrameContext ctx) => true;
    /// <summary>The first of the 32 strands from s0 that may not go into a chunk (e.g. shape matching: a bent rest shape), or −1.</summary>
    int RefusedLane(HairWorld w, int s0) => -1;
    /// <summary>
    /// Whether the system runs cut strands on chunks: the particles past a cut arrive as pins (InvMass 0) whose
    /// moves are never stored, so a per-particle system or a root-to-tip sweep that never moves pins gets the live
    /// particles' bits of the ordinary path. Systems that couple a particle to the next one (triples, segments, the
    /// source's length sweep) keep cut strands on their ordinary path.
    /// </summary>
    bool TakesCutStrands => false;
    /// <summary>
    /// Fetches into cache the lines of per-strand state that <see cref="PrepareChunk"/> and <see cref="ChunkBlock"/> will
    /// read for the chunk from s0 (<see cref="Prefetcher.Strands{T}"/>): the runner asks two chunks ahead. Each such
    /// array is read a line or two per chunk, between the chunk fields that stream through the cache, so without this
    /// every one of them missed in every chunk.
    /// </summary>
    void PrefetchChunkState(int s0) { }
    /// <summary>Fills what the system keeps in a chunk beyond the loaded fields (head follow: the pins' rest positions).</summary>
    void PrepareChunk(HairWorld w, int s0, scoped in StrandChunk chunk) { }
    /// <summary>
    /// Whether, this frame, <see cref="RunChunk"/> calls <see cref="Prefetcher.Row"/> with <see cref="StrandChunk.Prefetch"/>
    /// <see cref="StrandChunk.RowPrefetchCalls"/> times for each row it sweeps (rows 1 … height − 1, every substep): the
    /// runner then leaves the next chunk's prefetch to those calls instead of issuing it in slices after each system.
    /// Small steps spread over the rows made frames faster than a slice after each system (a burst of a hundred
    /// prefetches fills the core's miss buffers and stalls it), and a step per half row faster again.
    /// </summary>
    bool SweepsRows => false;
    /// <summary>
    /// Per-chunk data the system reads in place (not through the tile) for the chunk from strand s0 whose first
    /// particle is <paramref name="first"/>: <paramref name="fields"/> runs of <paramref name="cells"/> floats from
    /// <paramref name="offset"/>, for the runner to prefetch with the chunk's fields. Null if none.
    /// </summary>
    float[]? ChunkBlock(int s0, int first, int cells, out int offset, out int fields) { offset = 0; fields = 0; return null; }
    /// <summary>
    /// Substep <paramref name="substep"/> on the chunk. False: nothing was changed, and this system cannot handle
    /// the chunk now (e.g. coinciding particles); the runner then finishes the chunk's frame through <see cref="IHairSystem.Run"/>.
    /// Implementations stay under tiered compilation (see <see cref="Transpose"/> on <c>AggressiveOptimization</c>).
    /// </summary>
    bool RunChunk(HairScene scene, FrameContext ctx, int substep, scoped in StrandChunk chunk);
}

/// <summary>
/// A system's <see cref="IStrandChunkSystem.RunChunk"/>, bound once (see <see cref="StrandChunkRunner"/>). The chunk goes
/// by reference: by value it was copied onto the stack for every call (a microcoded string move and a dozen more),
/// a call per system and substep of every chunk.
/// </summary>
internal delegate bool ChunkStep(HairScene scene, FrameContext ctx, int substep, scoped in StrandChunk chunk);

/// <summary>A system's <see cref="IStrandChunkSystem.PrepareChunk"/>, bound once.</summary>
internal delegate void ChunkPrepare(HairWorld w, int s0, scoped in StrandChunk chunk);

/// <summary>
/// Runs a job's strands through all substeps chunk by chunk: each run of 32 uncut 16-particle strands that every
/// system accepts is loaded into a <see cref="StrandChunk"/>, stepped, and stored; every other strand (cut, other
/// lengths, bent rest shapes) goes through the systems' ordinary <see cref="IHairSystem.Run"/> over its range.
/// Both give the same bits (StrandChunkTests).
/// </summary>
internal sealed class StrandChunkRunner
{
    private readonly IHairSystem[] _systems;
    private readonly IStrandChunkSystem[] _chunkSystems;
    // The per-chunk calls, bound to each system's own method once: a call through the interface at a site that sees
    // several systems went through the runtime's resolve stub every time (a visible share of a one-substep frame). Systems
    // that keep the interface's empty default of a call are left out of that call's list.
    private readonly ChunkStep[] _steps;
    private readonly ChunkPrepare[] _prepares;
    private readonly Action<int>[] _prefetchState;
    private readonly IStrandChunkSystem[] _withBlocks;
    private readonly ChunkConstantRows _constantRows;
    private readonly ChunkFields _needs;
    private readonly bool _takesCut;
    private bool _cutThisFrame;

    /// <summary>
    /// Whether the bend sweep integrates each row itself when <see cref="FastIntegrateSystem"/> runs just before it
    /// (one pass over the chunk's rows per substep instead of two; the same bits). A switch for tests and measurement.
    /// </summary>
    public bool FuseIntegration { get; set; } = true;

    /// <summary>Whether this frame's chunk sweeps integrate each row (<see cref="FuseIntegration"/>, and integration just before the active sweep).</summary>
    public bool IntegratesInSweep => _fusedAway >= 0;
    // The integration system followed by the bend sweep (indices into _chunkSystems), or −1; and this frame's system
    // to skip because the sweep took its pass over (−1: none).
    private readonly int _integrateAt = -1;
    private int _fusedAway = -1;

    /// <summary>
    /// Whether the bend sweep tests each row it finishes against the collider's far sphere when <see cref="FastCollideSystem"/>
    /// runs just after it with one ellipsoid, so that the collision skips the rows whose every lane its own test would
    /// find far, or is pinned (the same test on the same values, so the same bits; default on). A switch for tests and measurement.
    /// </summary>
    public bool FuseFarRows { get; set; } = true;

    /// <summary>Whether this frame's chunk sweeps test their rows for the collision (<see cref="FuseFarRows"/>).</summary>
    public bool TestsFarRowsInSweep => _farRowsThisFrame;
    // The bend sweep followed by the collision (an index into _chunkSystems), or −1; and whether this frame takes it.
    private readonly int _bendAt = -1;
    private bool _farRowsThisFrame;

    private StrandChunkRunner(IHairSystem[] systems, IStrandChunkSystem[] chunkSystems)
    {
        _systems = systems;
        _chunkSystems = chunkSystems;
        _steps = new ChunkStep[chunkSystems.Length];
        var prepares = new List<ChunkPrepare>();
        var prefetchState = new List<Action<int>>();
        var withBlocks = new List<IStrandChunkSystem>();
        for (int k = 0; k < chunkSystems.Length; k++)
        {
            var c = chunkSystems[k];
            _steps[k] = c.RunChunk;
            if (Implements(c, nameof(IStrandChunkSystem.PrepareChunk))) prepares.Add(c.PrepareChunk);
            if (Implements(c, nameof(IStrandChunkSystem.PrefetchChunkState))) prefetchState.Add(c.PrefetchChunkState);
            if (Implements(c, nameof(IStrandChunkSystem.ChunkBlock))) withBlocks.Add(c);
        }
        _prepares = [.. prepares]; _prefetchState = [.. prefetchState]; _withBlocks = [.. withBlocks];
        for (int k = 0; k + 1 < chunkSystems.Length; k++)
            if (chunkSystems[k] is FastIntegrateSystem && chunkSystems[k + 1] is FastBendSystem) _integrateAt = k;
        for (int k = 0; k + 1 < chunkSystems.Length; k++)
            if (chunkSystems[k] is FastBendSystem && chunkSystems[k + 1] is FastCollideSystem) _bendAt = k;
        _takesCut = true;
        foreach (var c in chunkSystems) { _needs |= c.ChunkNeeds; _takesCut &= c.TakesCutStrands; }
        _constantRows = new ChunkConstantRows(_needs);
    }

    /// <summary>Whether the system's type has its own <paramref name="method"/> of <see cref="IStrandChunkSystem"/> (not the interface's default).</summary>
    internal static bool Implements(IStrandChunkSystem system, string method)
    {
        var map = system.GetType().GetInterfaceMap(typeof(IStrandChunkSystem));
        for (int i = 0; i < map.InterfaceMethods.Length; i++)
            if (map.InterfaceMethods[i].Name == method) return map.TargetMethods[i].DeclaringType != typeof(IStrandChunkSystem);
        throw new ArgumentException($"IStrandChunkSystem has no method {method}.", nameof(method));
    }

    /// <summary>Whether cut strands (capacity 16, fewer live particles) go into chunks: every system takes them.</summary>
    public bool TakesCutStrands => _takesCut;

    /// <summary>A runner for these substep systems, or null if one of them cannot run on chunks.</summary>
    public static StrandChunkRunner? TryCreate(IHairSystem[] substepSystems)
    {
        if (substepSystems.Length == 0 || !FastPathInfo.Avx512) return null;
        var chunk = new IStrandChunkSystem[substepSystems.Length];
        for (int k = 0; k < substepSystems.Length; k++)
        {
            if (substepSystems[k] is not IStrandChunkSystem c || !c.SupportsChunks) return null;
            chunk[k] = c;
        }
        return new StrandChunkRunner(substepSystems, chunk);
    }

    private int _stepped, _handedBack;
    // This frame: a system paces the next chunk's prefetch row by row (IStrandChunkSystem.SweepsRows).
    private bool _rowPaced;
    // Per chunk start: 2 × (edit stamp + 1) + the frame's cut flag under which the 32 strands from it last made a chunk.
    private long[] _acceptedAt = [];

    public void ResetCounts() { _stepped = 0; _handedBack = 0; }

    /// <summary>Chunks stepped since <see cref="ResetCounts"/>, and how many of them went back to the ordinary path midway.</summary>
    public (int Stepped, int HandedBack) Counts => (Volatile.Read(ref _stepped), Volatile.Read(ref _handedBack));

    /// <summary>Prepares every system's chunk kernel for this frame; false if some system's settings do not take it.</summary>
    public bool BeginFrame(FrameContext ctx, HairWorld world)
    {
        // Made on the calling thread (the jobs only read and write their own entries), once per world size.
        if (_acceptedAt.Length != world.StrandCount) _acceptedAt = new long[world.StrandCount];
        _constantRows.Fit(world);
        // A teleport carries the particles past a cut with the head (FastHeadFollowSystem.CarryRigidly), which a
        // chunk, putting them back as they were, would not: cut strands take the ordinary path on those rare frames.
        _cutThisFrame = _takesCut && !ctx.Teleported;
        foreach (var c in _chunkSystems) if (!c.BeginChunkFrame(ctx)) return false;
        _rowPaced = false;
        foreach (var c in _chunkSystems) _rowPaced |= c.SweepsRows;
        _fusedAway = _integrateAt >= 0 && ((FastBendSystem)_chunkSystems[_integrateAt + 1]).FuseIntegrate(FuseIntegration) ? _integrateAt : -1;
        _farRowsThisFrame = FuseFarRows && _bendAt >= 0 && ((FastBendSystem)_chunkSystems[_bendAt]).SweepsChunks
            && FastCollideSystem.TakesFarRows(ctx);
        return true;
    }

    /// <summary>All substeps of strands [begin, end).</summary>
    // The stack tile is written before it is read (rows that must start as zero are cleared here).
    [SkipLocalsInit]
    public void Run(HairScene scene, FrameContext ctx, int begin, int end, NonFiniteContainment containment)
    {
        var w = scene.World;
        // As tall as the groom's longest strand needs (16 rows for the source's systems; up to 64 with the default ones):
        // 71 KB of stack for 16 rows, 262 KB for 64.
        int tileRows = _takesCut ? Math.Clamp((w.MaxStrandCapacity + 15) / 16 * 16, StrandChunk.Rows, StrandChunk.MaxRows) : StrandChunk.Rows; // whole 16-row blocks
        var tile = new StrandScratch(stackalloc float[StrandChunk.SizeFor(tileRows)], StrandChunk.CapacityFor(tileRows));
        Span<int> firsts = stackalloc int[StrandChunk.Lanes];
        // The particles past each cut, as they were: written back after the chunk is stored (they never move).
        Span<float> pastCuts = _takesCut ? stackalloc float[PastCutFields * StrandChunk.Lanes * tileRows] : default;
        bool cleared = false;
        int ordinaryFrom = begin, stepped = 0, handedBack = 0;
        for (int s0 = begin; s0 + StrandChunk.Lanes <= end;)
        {
            int next = Refused(w, s0, tileRows);
            if (next > s0)
            {
                s0 = next;
                continue;
            }
            if (ordinaryFrom < s0) RunOrdinaryAndScan(scene, ctx, ordinaryFrom, s0, containment);
            PrefetchChunkState(w, s0 + 2 * StrandChunk.Lanes);
            if (!cleared) { ClearFixedRows(tile, tileRows, w.StrandCapacity[s0]); cleared = true; }
            for (int l = 0; l < StrandChunk.Lanes; l++) firsts[l] = w.StrandFirst[s0 + l];
            stepped++;
            if (!RunChunk(scene, ctx, s0, tile, tileRows, firsts, pastCuts, containment)) handedBack++;
            s0 += StrandChunk.Lanes;
            ordinaryFrom = s0;
        }
        if (ordinaryFrom < end) RunOrdinaryAndScan(scene, ctx, ordinaryFrom, end, containment);
        if (stepped > 0) Interlocked.Add(ref _stepped, stepped);
        if (handedBack > 0) Interlocked.Add(ref _handedBack, handedBack);
    }

    /// <summary>
    /// s0 when the 32 strands from s0 make a chunk (whole, 16 particles, back to back, accepted by every system);
    /// else the first strand a chunk could start at (every chunk starting before it holds the strand that failed).
    /// </summary>
    private int Refused(HairWorld w, int s0, int tileRows)
    {
        // Whether strands make a chunk changes only with an edit (capacities, cuts, pins, rest shapes) or a teleport.
        long key = 2L * (w.EditStamp + 1L) + (_cutThisFrame ? 1 : 0);
        if (s0 < _acceptedAt.Length && _acceptedAt[s0] == key) return s0;
        int first = w.StrandFirst[s0], cap = w.StrandCapacity[s0];
        for (int l = 0; l < StrandChunk.Lanes; l++)
        {
            int s = s0 + l, c = w.StrandCapacity[s];
            // 16 particles; with systems that take cut strands, any capacity from 2 to the tile's height (the rows past
            // it are masked as a cut's are), all 32 strands alike.
            if (c != StrandChunk.Rows && (!_takesCut || c < 2 || c > tileRows)) return s + 1;
            if (c != cap) return s; // a chunk of the new capacity may start here
            if (w.StrandParticleCount[s] != c && !_cutThisFrame) return s + 1;
            if (w.StrandFirst[s] != first + l * cap) return s; // not contiguous with s − 1
            if (w.IsFreeStrand(s)) return s + 1; // free strands share their sweeps' corrections out (FreeStrands): not in chunks
        }
        foreach (var c in _chunkSystems)
        {
            int l = c.RefusedLane(w, s0);
            if (l >= 0) return s0 + l + 1;
        }
        if (s0 < _acceptedAt.Length) _acceptedAt[s0] = key;
        return s0;
    }

    /// <summary>One chunk through all substeps; false if a system handed it back to the ordinary path midway.</summary>
    // Every local is written before it is read (the prefetcher's addresses up to its count): no zeroing of the frame.
    [SkipLocalsInit]
    private unsafe bool RunChunk(HairScene scene, FrameContext ctx, int s0, scoped StrandScratch tile, int tileRows, ReadOnlySpan<int> firsts, Span<float> pastCuts,
        NonFiniteContainment containment)
    {
        var w = scene.World;
        int first = firsts[0], height = w.StrandCapacity[s0];
        Load(w.PosX, first, height, tile, StrandChunk.X); Load(w.PosY, first, height, tile, StrandChunk.Y); Load(w.PosZ, first, height, tile, StrandChunk.Z);
        Load(w.VelX, first, height, tile, StrandChunk.VelX); Load(w.VelY, first, height, tile, StrandChunk.VelY); Load(w.VelZ, first, height, tile, StrandChunk.VelZ);
        // Masses and rest data: copied rows kept since the last edit, else transposed from the world and kept.
        bool kept = _constantRows.Holds(w, s0, first, height);
        ulong pinned = kept ? _constantRows.CopyTo(s0, first, height, tile) : 0;
        if (!kept)
        {
            _constantRows.LoadAndKeep(w, s0, first, height, tile);
        }
        int cutFrom = _takesCut ? SavePastCuts(w, s0, height, tileRows, tile, pastCuts) : StrandChunk.Rows;
        // Rows past every strand's cut need no sweep: the longest live strand's count.
        int liveRows = cutFrom < height ? MaxLive(w, s0) : height;
        if (!kept)
        {
            // From the masses as the cut masks leave them (which change only with an edit too).
            pinned = (_needs & ChunkFields.PinRest) != 0 ? PinnedRows(tile, height) : 0;
            _constantRows.KeepPinned(w, s0, pinned);
        }
        // The next chunk's data is fetched from memory while this one computes: a share per row of a system that
        // sweeps rows, else a slice after each system.
        var prefetch = new Prefetcher(w, s0 + StrandChunk.Lanes, first + StrandChunk.Lanes * height, height, _constantRows, _withBlocks,
            twoAhead: ctx.Substeps == 1);
        int calls = ctx.Substeps * (_rowPaced ? Math.Max(1, liveRows - 1) * StrandChunk.RowPrefetchCalls : _chunkSystems.Length);
        prefetch.PerCall = (prefetch.Lines + calls - 1) / calls;
        ulong farRows = 0;
        var chunk = new StrandChunk(tile, firsts, pinned, height, s0, _rowPaced ? (nint)(&prefetch) : 0, liveRows, _farRowsThisFrame ? (nint)(&farRows) : 0);
        foreach (var prepare in _prepares) prepare(w, s0, chunk);
        for (int s = 0; s < ctx.Substeps; s++)
            for (int k = 0; k < _chunkSystems.Length; k++)
            {
                if (k == _fusedAway) continue; // the sweep after it integrates each row (FastBendSystem.FuseIntegrate)
                if (_steps[k](scene, ctx, s, chunk)) { if (!_rowPaced) prefetch.Next(prefetch.PerCall); continue; }
                if (cutFrom < height) RestorePastCuts(w, s0, cutFrom, height, tileRows, tile, pastCuts);
                Store(tile, first, height, w);
                RunOrdinary(scene, ctx, s0, s0 + StrandChunk.Lanes, s, k);
                containment.Scan(w, ctx.HeadEnd, s0, s0 + StrandChunk.Lanes);
                return false;
            }
        if (cutFrom < height) RestorePastCuts(w, s0, cutFrom, height, tileRows, tile, pastCuts);
        // The frame's containment of non-finite values (NonFiniteContainment), on the rows being stored, in registers
        // or L1: scanning the world's buffers after the job read them all from memory again.
        if (!Store(tile, first, height, w)) containment.ResetNonFinite(w, ctx.HeadEnd, s0, s0 + StrandChunk.Lanes);
        return true;
    }

    /// <summary>Whether the rows a chunk stores (every particle of its strands, past a cut too) hold only finite values.</summary>
    private static bool StoredRowsFinite(scoped StrandScratch tile, int height)
    {
        var max0 = Vector512<uint>.Zero; var max1 = Vector512<uint>.Zero;
        int cells = height * StrandChunk.Lanes;
        foreach (int f in StoredFields)
        {
            ref float row = ref tile.Data[tile.Offset(f)];
            for (int i = 0; i < cells; i += 32)
            {
                max0 = Vector512.Max(max0, Simd.FiniteProbe(Vector512.LoadUnsafe(ref row, (nuint)i)));
                max1 = Vector512.Max(max1, Simd.FiniteProbe(Vector512.LoadUnsafe(ref row, (nuint)(i + 16))));
            }
        }
        return Simd.AllFinite(Vector512.Max(max0, max1));
    }

    /// <summary>Strands [begin, end) through every substep system by system, then the containment's scan of them.</summary>
    private void RunOrdinaryAndScan(HairScene scene, FrameContext ctx, int begin, int end, NonFiniteContainment containment)
    {
        RunOrdinary(scene, ctx, begin, end, 0, 0);
        containment.Scan(scene.World, ctx.HeadEnd, begin, end);
    }

    /// <summary>The per-strand state the runner and every system read for the chunk from s0 (see <see cref="IStrandChunkSystem.PrefetchChunkState"/>).</summary>
    private void PrefetchChunkState(HairWorld w, int s0)
    {
        Prefetcher.Strands(w.StrandFirst, s0); Prefetcher.First(w.StrandCapacity, s0); Prefetcher.Strands(w.StrandParticleCount, s0);
        Prefetcher.First(_acceptedAt, s0);
        _constantRows.PrefetchState(s0);
        foreach (var prefetchState in _prefetchState) prefetchState(s0);
    }

    /// <summary>Position and velocity: what a chunk stores, so what must be put back past a cut.</summary>
    private const int PastCutFields = 6;
    private static readonly int[] StoredFields = [StrandChunk.X, StrandChunk.Y, StrandChunk.Z, StrandChunk.VelX, StrandChunk.VelY, StrandChunk.VelZ];

    /// <summary>
    /// Masks the particles past each lane's cut as pins in the chunk (InvMass 0: no system moves them into a live
    /// one's way) and keeps the rows that hold them, which go back into the chunk under the same masks before it is
    /// stored (row-wise, all in L1). Returns the first row holding a particle past a cut (the tile's rows: none).
    /// </summary>
    private static int SavePastCuts(HairWorld w, int s0, int height, int tileRows, scoped StrandScratch tile, Span<float> saved)
    {
        int from = tileRows, cells = StrandChunk.Lanes * tileRows;
        for (int l = 0; l < StrandChunk.Lanes; l++) from = Math.Min(from, w.StrandParticleCount[s0 + l]);
        // Every strand whole (short strands in a taller tile included): nothing past a cut. The rows past the strands'
        // capacity hold no particle, and no system reads them (each reads only the chunk's own rows).
        if (from >= height) return tileRows;
        var (lo, hi) = LiveCounts(w, s0);
        ref float data = ref tile.Data[0];
        ref float sv = ref saved[0];
        for (int k = from; k < height; k++)
        {
            var (deadLo, deadHi) = Dead(lo, hi, k);
            ref float m = ref Unsafe.Add(ref data, tile.Offset(StrandChunk.InvMass) + k * StrandChunk.Lanes);
            Vector512.ConditionalSelect(deadLo, Vector512<float>.Zero, Vector512.LoadUnsafe(ref m)).StoreUnsafe(ref m);
            Vector512.ConditionalSelect(deadHi, Vector512<float>.Zero, Vector512.LoadUnsafe(ref m, 16)).StoreUnsafe(ref m, 16);
            for (int f = 0; f < PastCutFields; f++)
            {
                ref float row = ref Unsafe.Add(ref data, tile.Offset(StoredFields[f]) + k * StrandChunk.Lanes);
                ref float keep = ref Unsafe.Add(ref sv, f * cells + k * StrandChunk.Lanes);
                Vector512.LoadUnsafe(ref row).StoreUnsafe(ref keep);
                Vector512.LoadUnsafe(ref row, 16).StoreUnsafe(ref keep, 16);
            }
        }
        return from;
    }

    private static void RestorePastCuts(HairWorld w, int s0, int from, int height, int tileRows, scoped StrandScratch tile, ReadOnlySpan<float> saved)
    {
        int cells = StrandChunk.Lanes * tileRows;
        var (lo, hi) = LiveCounts(w, s0);
        ref float data = ref tile.Data[0];
        ref float sv = ref MemoryMarshal.GetReference(saved);
        for (int k = from; k < height; k++)
        {
            var (deadLo, deadHi) = Dead(lo, hi, k);
            for (int f = 0; f < PastCutFields; f++)
            {
                ref float row = ref Unsafe.Add(ref data, tile.Offset(StoredFields[f]) + k * StrandChunk.Lanes);
                ref float keep = ref Unsafe.Add(ref sv, f * cells + k * StrandChunk.Lanes);
                Vector512.ConditionalSelect(deadLo, Vector512.LoadUnsafe(ref keep), Vector512.LoadUnsafe(ref row)).StoreUnsafe(ref row);
                Vector512.ConditionalSelect(deadHi, Vector512.LoadUnsafe(ref keep, 16), Vector512.LoadUnsafe(ref row, 16)).StoreUnsafe(ref row, 16);
            }
        }
    }

    /// <summary>The largest live particle count of the chunk's 32 strands.</summary>
    private static int MaxLive(HairWorld w, int s0)
    {
        var (lo, hi) = LiveCounts(w, s0);
        var m = Vector512.Max(lo, hi);
        var m8 = Vector256.Max(m.GetLower(), m.GetUpper());
        var m4 = Vector128.Max(m8.GetLower(), m8.GetUpper());
        return Math.Max(Math.Max(m4.GetElement(0), m4.GetElement(1)), Math.Max(m4.GetElement(2), m4.GetElement(3)));
    }

    /// <summary>The live particle counts of the chunk's 32 strands, as two 16-lane halves.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static (Vector512<int> Lo, Vector512<int> Hi) LiveCounts(HairWorld w, int s0)
    {
        ref int n = ref Unsafe.Add(ref MemoryMarshal.GetArrayDataReference(w.StrandParticleCount), s0);
        return (Vector512.LoadUnsafe(ref n), Vector512.LoadUnsafe(ref n, 16));
    }

    /// <summary>Lanes whose particle in row k is past the strand's cut, as float masks.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static (Vector512<float> Lo, Vector512<float> Hi) Dead(Vector512<int> lo, Vector512<int> hi, int k)
    {
        var row = Vector512.Create(k);
        return (Vector512.LessThanOrEqual(lo, row).AsSingle(), Vector512.LessThanOrEqual(hi, row).AsSingle());
    }

    /// <summary>Substeps from <paramref name="fromSubstep"/> (its systems from <paramref name="fromSystem"/>) of strands [begin, end), system by system.</summary>
    private void RunOrdinary(HairScene scene, FrameContext ctx, int begin, int end, int fromSubstep, int fromSystem)
    {
        for (int s = fromSubstep; s < ctx.Substeps; s++)
            for (int k = s == fromSubstep ? fromSystem : 0; k < _systems.Length; k++)
                _systems[k].Run(scene, ctx, s, begin, end);
    }

    private static void ClearFixedRows(scoped StrandScratch tile, int tileRows, int height)
    {
        // Short strands' loads fill only their own rows: the rows past them in the loaded fields start at zero (the
        // stack tile is not cleared), so they hold finite values, as the 16 × 16 transposes leave them (later chunks
        // leave their own finite values there). Systems read only a chunk's own rows; this keeps stray reads harmless.
        if (Transpose.TakesShort(height))
            foreach (int f in (ReadOnlySpan<int>)[StrandChunk.X, StrandChunk.Y, StrandChunk.Z, StrandChunk.VelX, StrandChunk.VelY, StrandChunk.VelZ,
                StrandChunk.InvMass, StrandChunk.RestLength, StrandChunk.ShapePrev, StrandChunk.ShapeMid, StrandChunk.ShapeNext])
                tile.Data.Slice(tile.Offset(f) + height * StrandChunk.Lanes, (tileRows - height) * StrandChunk.Lanes).Clear();
        // Goal rows −1, 0, 15 and 16: no triple fills them (triples are 1 … 14).
        for (int g = 0; g < 9; g++)
        {
            var goal = tile.Data.Slice(tile.Offset(StrandChunk.Goals + g), StrandChunk.CapacityFor(tileRows));
            goal.Slice(0, 2 * StrandChunk.Lanes).Clear();
            goal.Slice(StrandChunk.Rows * StrandChunk.Lanes, 2 * StrandChunk.Lanes).Clear();
        }
        // The root row's velocity kick: the length sweep never writes it.
        for (int f = StrandChunk.KickX; f <= StrandChunk.KickZ; f++) tile.Data.Slice(tile.Offset(f), StrandChunk.Lanes).Clear();
    }

    /// <summary>Transposes 32 strands of a world field into the chunk's rows.</summary>
    private static void Load(float[] src, int first, int height, scoped StrandScratch tile, int field) =>
        LoadRows(src, first, height, ref tile.Data[tile.Offset(field)]);

    /// <summary>
    /// 32 strands of <paramref name="height"/> particles from <paramref name="first"/> of a per-particle array into
    /// chunk rows from <paramref name="row0"/>. 16 particles: two 16 × 16 transposes. 2 … 4 particles: the short
    /// transposes (Transpose.InShort), which fill only the strands' own rows. Other capacities: 16 × 16
    /// transposes with the strands' stride, one block of 16 rows at a time, where 16 floats past the last strand's
    /// last block are readable (rows past the capacity then hold the next strands' particles, which the chunk masks);
    /// else element by element, with the rows past the capacity cleared.
    /// </summary>
    internal static void LoadRows(float[] src, int first, int height, ref float row0)
    {
        const int L = StrandChunk.Lanes;
        ref float s = ref Simd.At(src, first);
        if (height == StrandChunk.Rows)
        {
            Transpose.In16Wide(ref s, ref row0, L);
            Transpose.In16Wide(ref Unsafe.Add(ref s, 16 * StrandChunk.Rows), ref Unsafe.Add(ref row0, 16), L);
            return;
        }
        if (Transpose.TakesShort(height))
        {
            // Short strands: rows 0 … height − 1 picked out of the chunk's own floats (rows past them keep what they held).
            Transpose.InShort(ref s, height, ref row0, L);
            Transpose.InShort(ref Unsafe.Add(ref s, 16 * height), height, ref Unsafe.Add(ref row0, 16), L);
            return;
        }
        int blocks = (height + 15) / 16;
        if (first + (L - 1) * height + 16 * blocks <= src.Length)
        {
            for (int b = 0; b < blocks; b++)
            {
                ref float rows = ref Unsafe.Add(ref row0, 16 * b * L);
                Transpose.In16Strided(ref Unsafe.Add(ref s, 16 * b), height, ref rows, L);
                Transpose.In16Strided(ref Unsafe.Add(ref s, 16 * height + 16 * b), height, ref Unsafe.Add(ref rows, 16), L);
            }
            return;
        }
        for (int l = 0; l < L; l++)
            for (int k = 0; k < height; k++) Unsafe.Add(ref row0, k * L + l) = Unsafe.Add(ref s, l * height + k);
        MemoryMarshal.CreateSpan(ref Unsafe.Add(ref row0, height * L), (16 * blocks - height) * L).Clear();
    }

    /// <summary>The chunk's positions and velocities into the world; whether they were all finite.</summary>
    private static bool Store(scoped StrandScratch tile, int first, int height, HairWorld w)
    {
        if (height == StrandChunk.Rows)
        {
            // The common capacity: the check rides on the transposes' registers.
            var probes = Store16(tile, StrandChunk.X, w.PosX, first);
            probes = Vector512.Max(probes, Store16(tile, StrandChunk.Y, w.PosY, first));
            probes = Vector512.Max(probes, Store16(tile, StrandChunk.Z, w.PosZ, first));
            probes = Vector512.Max(probes, Store16(tile, StrandChunk.VelX, w.VelX, first));
            probes = Vector512.Max(probes, Store16(tile, StrandChunk.VelY, w.VelY, first));
            probes = Vector512.Max(probes, Store16(tile, StrandChunk.VelZ, w.VelZ, first));
            return Simd.AllFinite(probes);
        }
        Store(tile, StrandChunk.X, w.PosX, first, height); Store(tile, StrandChunk.Y, w.PosY, first, height); Store(tile, StrandChunk.Z, w.PosZ, first, height);
        Store(tile, StrandChunk.VelX, w.VelX, first, height); Store(tile, StrandChunk.VelY, w.VelY, first, height); Store(tile, StrandChunk.VelZ, w.VelZ, first, height);
        return StoredRowsFinite(tile, height);
    }

    /// <summary>A field of a 16-row chunk into the world: two 16 × 16 transposes, with their finite probes.</summary>
    private static Vector512<uint> Store16(scoped StrandScratch tile, int field, float[] dst, int first)
    {
        ref float row0 = ref tile.Data[tile.Offset(field)];
        return Vector512.Max(Transpose.Out16WideProbed(ref row0, StrandChunk.Lanes, ref Simd.At(dst, first)),
            Transpose.Out16WideProbed(ref Unsafe.Add(ref row0, 16), StrandChunk.Lanes, ref Simd.At(dst, first + 16 * StrandChunk.Rows)));
    }

    private static void Store(scoped StrandScratch tile, int field, float[] dst, int first, int height)
    {
        ref float row0 = ref tile.Data[tile.Offset(field)];
        if (Transpose.TakesShort(height))
        {
            // Short strands: the chunk's 32 · height floats written exactly.
            ref float to = ref Simd.At(dst, first);
            Transpose.OutShort(ref row0, StrandChunk.Lanes, ref to, height);
            Transpose.OutShort(ref Unsafe.Add(ref row0, 16), StrandChunk.Lanes, ref Unsafe.Add(ref to, 16 * height), height);
            return;
        }
        if (height != StrandChunk.Rows)
        {
            // Other capacities, 16 rows at a time. Whole blocks store 16 floats per strand, inside it. The last block
            // of a strand whose capacity is not a multiple of 16 spills into the next strand's first block: it goes
            // first, strands in order (each spill overwritten by the next strand's own store), the rest after it; and
            // strands whose spill would reach past the chunk store only their own floats.
            ref float d = ref Simd.At(dst, first);
            int blocks = (height + 15) / 16, last = blocks - 1;
            int chunkEnd = StrandChunk.Lanes * height;
            int whole = height % 16 == 0 ? StrandChunk.Lanes : Math.Min(StrandChunk.Lanes, (chunkEnd - 16 - 16 * last) / height + 1);
            for (int b = last; b >= 0; b--)
            {
                int w = b == last ? whole : StrandChunk.Lanes;
                ref float rows = ref Unsafe.Add(ref row0, 16 * b * StrandChunk.Lanes);
                Transpose.Out16Strided(ref rows, StrandChunk.Lanes, ref Unsafe.Add(ref d, 16 * b), height, Math.Min(16, w), BlockWidth(height, b));
                Transpose.Out16Strided(ref Unsafe.Add(ref rows, 16), StrandChunk.Lanes, ref Unsafe.Add(ref d, 16 * height + 16 * b), height, Math.Max(0, w - 16), BlockWidth(height, b));
            }
            return;
        }
        Store16(tile, field, dst, first);
    }

    /// <summary>Particles of block b (rows 16b …) a strand of this capacity has.</summary>
    private static int BlockWidth(int height, int b) => Math.Min(16, height - 16 * b);

    /// <summary>The rows holding pinned particles (inverse mass 0), as bits.</summary>
    private static ulong PinnedRows(scoped StrandScratch tile, int height)
    {
        ulong rows = 0;
        ref float m = ref tile.Data[tile.Offset(StrandChunk.InvMass)];
        for (int k = 0; k < height; k++)
        {
            ref float row = ref Unsafe.Add(ref m, k * StrandChunk.Lanes);
            var zero = Vector512.Equals(Vector512.LoadUnsafe(ref row), Vector512<float>.Zero)
                       | Vector512.Equals(Vector512.LoadUnsafe(ref row, 16), Vector512<float>.Zero);
            if (zero != Vector512<float>.Zero) rows |= 1UL << k;
        }
        return rows;
    }
}

/// <summary>
/// Software prefetch of the next chunk's fields (and the blocks systems read in place, such as the bend sweep's rest
/// directions) into L1, spread over the current chunk's work: into L1 rather than L2 made frames faster (the lines
/// come late enough in the chunk to stay there until its loads). The hardware
/// prefetcher alone leaves the chunk loads waiting on memory: each field is a separate 2 KB stream touched once per
/// chunk, with microseconds of compute in between, so it never runs far enough ahead. Addresses are taken once per
/// chunk; a prefetch is only a hint, so one into an array the GC has since moved costs nothing but the miss.
/// </summary>
internal unsafe struct Prefetcher
{
    // Positions, velocities, masses and rest lengths (8), the bend sweep's block (5), the mesh collision's carried clearances (4).
    private const int MaxFields = 24;
    private fixed long _field[MaxFields];
    // Per field: bytes from the next chunk's rows to the rows of the chunk after it (0: none, or not fetched).
    private fixed long _ahead[MaxFields];
    private int _cursor;
    private readonly int _linesPerField;
    private readonly bool _twoAhead;

    /// <param name="twoAhead">
    /// Also fetch the chunk after the next one into L2, line for line with the next one into L1: for frames of one
    /// substep, whose chunks compute a quarter as long as at four, so that the next chunk's lines come from L2
    /// instead of memory (the core can wait on only so many lines from memory at once).
    /// </param>
    public Prefetcher(HairWorld w, int s0, int first, int height, ChunkConstantRows constant, IStrandChunkSystem[] systems, bool twoAhead = false)
    {
        _cursor = 0; _fieldAt = 0; _lineAt = 0;
        _twoAhead = twoAhead;
        int n = 0, cells = StrandChunk.Lanes * height;
        _linesPerField = cells * sizeof(float) / 64;
        // Nothing past the world's end.
        if (first + cells <= w.ParticleCount && Sse.IsSupported)
        {
            // The chunk after the next one, where the next one's strands are followed by 32 more of its capacity.
            int after = twoAhead && first + 2 * cells <= w.ParticleCount ? cells : 0;
            Add(w.PosX, first, after, ref n); Add(w.PosY, first, after, ref n); Add(w.PosZ, first, after, ref n);
            Add(w.VelX, first, after, ref n); Add(w.VelY, first, after, ref n); Add(w.VelZ, first, after, ref n);
            // The masses and rest data as kept in row layout (what the next chunk copies if it was seen unedited).
            var kept = constant.Blocks;
            int count = constant.Fields.Length;
            if ((long)count * (first + cells) <= kept.Length)
            {
                int keptAfter = after > 0 && (long)count * (first + 2 * cells) <= kept.Length ? count * cells : 0;
                for (int f = 0; f < count; f++) Add(kept, count * first + f * cells, keptAfter, ref n);
            }
            foreach (var c in systems)
            {
                var block = c.ChunkBlock(s0, first, cells, out int offset, out int fields);
                if (block == null || offset < 0 || (long)offset + (long)fields * cells > block.Length) continue;
                // A block laid out at its chunk's first particle (fields × that): the next chunk's starts fields × cells on.
                int blockAfter = after > 0 && (long)offset + 2L * fields * cells <= block.Length ? fields * cells : 0;
                for (int f = 0; f < fields && n < MaxFields; f++) Add(block, offset + f * cells, blockAfter, ref n);
            }
        }
        Lines = n * _linesPerField;
    }

    private void Add(float[] a, int first, int after, ref int n)
    {
        _ahead[n] = (long)after * sizeof(float);
        _field[n++] = (long)Unsafe.AsPointer(ref Simd.At(a, first));
    }

    /// <summary>Bytes from field <paramref name="field"/>'s rows of the next chunk to those of the chunk after it (0: not fetched).</summary>
    internal long AheadBytes(int field) => _ahead[field];

    public int Lines { get; }

    /// <summary>Lines fetched so far.</summary>
    public int Issued => _cursor;

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public void Next(int count)
    {
        // Field by field, line by line (no division per line).
        int left = Math.Min(Lines - _cursor, count);
        if (left <= 0) return;
        _cursor += left;
        int field = _fieldAt, line = _lineAt, per = _linesPerField;
        byte* p = (byte*)_field[field] + line * 64;
        if (_twoAhead)
        {
            long ahead = _ahead[field];
            for (; left > 0; left--)
            {
                Sse.Prefetch0(p);
                if (ahead != 0) Sse.Prefetch1(p + ahead);
                p += 64;
                if (++line == per && ++field < MaxFields) { line = 0; p = (byte*)_field[field]; ahead = _ahead[field]; }
            }
        }
        else
            for (; left > 0; left--)
            {
                Sse.Prefetch0(p);
                p += 64;
                if (++line == per && ++field < MaxFields) { line = 0; p = (byte*)_field[field]; }
            }
        _fieldAt = field; _lineAt = line;
    }
    private int _fieldAt, _lineAt;

    /// <summary>Lines per call of <see cref="Row"/> (or per slice): the runner sets it so the calls of a chunk's frame fetch everything.</summary>
    public int PerCall;

    /// <summary>The lines holding a per-strand array's entries for all 32 strands of a chunk from s0 (those in range).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static unsafe void Strands<T>(T[] a, int s0) where T : unmanaged
    {
        for (int k = 0, n = StrandEntries(sizeof(T)); k < n; k++) Line(a, s0 + StrandEntry(k, sizeof(T)));
    }

    /// <summary>
    /// How many entries <see cref="Strands{T}"/> fetches the lines of, for entries of <paramref name="size"/> bytes: one
    /// every line's width apart, and the last, so that every line the 32 entries touch holds one of them.
    /// </summary>
    internal static int StrandEntries(int size) => (StrandChunk.Lanes - 2) / (64 / size) + 2;

    /// <summary>The k-th of those entries, from the chunk's first strand.</summary>
    internal static int StrandEntry(int k, int size) => k == StrandEntries(size) - 1 ? StrandChunk.Lanes - 1 : k * (64 / size);

    /// <summary>The lines holding the entries of the chunk's first and last strands (what <see cref="StrandChunk.OwnsBlock"/> reads).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void Ends<T>(T[] a, int s0) where T : unmanaged
    {
        Line(a, s0);
        Line(a, s0 + StrandChunk.Lanes - 1);
    }

    /// <summary>The line holding the entry of the chunk's first strand (state kept per chunk, at its first strand).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void First<T>(T[] a, int s0) where T : unmanaged => Line(a, s0);

    /// <summary>The lines holding entries a and b of a particle array (a strand's first and last particle: a strand of up to 17 fits in the two).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void Particle(float[] p, int a, int b)
    {
        Line(p, a);
        Line(p, b);
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Line<T>(T[] a, int i) where T : unmanaged
    {
        // A prefetch never faults, and one through an address the GC has since moved only fetches a line for nothing.
        if ((uint)i < (uint)a.Length && Sse.IsSupported) Sse.Prefetch0(Unsafe.AsPointer(ref a[i]));
    }

    /// <summary>One row's share through a pointer from <see cref="StrandChunk.Prefetch"/> (nothing for 0).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void Row(nint prefetcher)
    {
        if (prefetcher == 0) return;
        var p = (Prefetcher*)prefetcher;
        p->Next(p->PerCall);
    }
}
