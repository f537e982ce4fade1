using System.Runtime.Intrinsics;
using System.Runtime.Intrinsics.X86;
using System.Runtime.InteropServices;
using System.Runtime.CompilerServices;
using System.Numerics;

namespace HairSim.Fast;

/// <summary>
/// Fast <see cref="HeadFollowSystem"/>: pinned particles go to head·rest with zero velocity (SIMD, masked by
/// InvMass == 0); on a teleport frame the block's particles (every slot, live or cut) are first carried rigidly.
/// </summary>
public sealed class FastHeadFollowSystem : IHairSystem, IStrandChunkSystem
{
    /// <summary>Pins cached per strand; a strand with more goes through the SIMD kernel.</summary>
    private const int MaxCachedPins = 2;

    // Per strand: the world's edit stamp + 1 when its pins were cached (0: never), how many (or −1: too many), and
    // their indices and rest positions, so a substep reads neither the masses nor the rest arrays.
    private readonly long[] _cachedAt;
    private readonly int[] _pinCount, _pinIndex;
    private readonly float[] _pinRest;
    private readonly bool _cache;
    // Per chunk (at 3 × its first particle): the rest rows PrepareChunk fills, in row layout (RestX, RestY, RestZ, 32
    // lanes a row), with the edit stamp + 1 and the pinned-row mask they were made for, keyed by the chunk's first strand.
    // A chunk seen again unedited copies its pinned rows from there: a few vector copies instead of a scalar store per pin.
    private readonly float[] _pinRows;
    private readonly long[] _pinRowsAt;
    private readonly ulong[] _pinRowsMask;
    // Per strand: the chunk (its first strand) whose block holds this strand's rows. A chunk that started elsewhere
    // (another frame's chunk boundaries, e.g. a teleport's) overwrote part of the blocks and owns those strands now.
    private readonly int[] _pinRowsOwner;

    /// <param name="world">The world this system runs on (sizes the per-strand pin cache).</param>
    /// <param name="cachePins">Cache each strand's pinned particles until the world is edited (off: scan every substep).</param>
    public FastHeadFollowSystem(HairWorld world, bool cachePins = true)
    {
        ArgumentNullException.ThrowIfNull(world);
        _cache = cachePins;
        int n = cachePins ? world.StrandCount : 0;
        _cachedAt = new long[n]; _pinCount = new int[n]; _pinIndex = new int[n * MaxCachedPins]; _pinRest = new float[n * MaxCachedPins * 3];
        _pinRows = new float[cachePins ? 3 * world.ParticleCount : 0]; _pinRowsAt = new long[n]; _pinRowsMask = new ulong[n];
        _pinRowsOwner = new int[n];
        Array.Fill(_pinRowsOwner, -1);
    }

    public string Name => HeadFollowSystem.SystemName;
    public SystemPhase Phase => SystemPhase.Substep;

    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        if (begin >= end) return;
        var w = scene.World;
        if (substep == 0 && ctx.Teleported) CarryRigidly(w, ctx.TeleportDelta, begin, end);
        var pose = new PoseLanes(ctx.HeadAt(substep));
        if (!_cache || _cachedAt.Length != w.StrandCount)
        {
            var all = new PinKernel(pose);
            ParticleRuns.ForEachLive(w, begin, end, ref all);
            return;
        }
        long stamp = w.EditStamp + 1L;
        float[] px = w.PosX, py = w.PosY, pz = w.PosZ, vx = w.VelX, vy = w.VelY, vz = w.VelZ;
        for (int s = begin; s < end; s++)
        {
            if (_cachedAt[s] != stamp) CachePins(w, s, stamp);
            int count = _pinCount[s];
            if (count < 0)
            {
                var kernel = new PinKernel(pose);
                ParticleRuns.ForEachLive(w, s, s + 1, ref kernel);
                continue;
            }
            for (int k = 0; k < count; k++)
            {
                int c = s * MaxCachedPins + k, i = _pinIndex[c];
                // Same arithmetic, same order as the SIMD lanes of PinKernel.
                var g = pose.Point(new Vector3(_pinRest[3 * c], _pinRest[3 * c + 1], _pinRest[3 * c + 2]));
                px[i] = g.X; py[i] = g.Y; pz[i] = g.Z;
                vx[i] = 0f; vy[i] = 0f; vz[i] = 0f;
            }
        }
    }

    bool IStrandChunkSystem.SupportsChunks => FastPathInfo.Avx512;
    ChunkFields IStrandChunkSystem.ChunkNeeds => ChunkFields.PinRest;
    bool IStrandChunkSystem.TakesCutStrands => true;

    void IStrandChunkSystem.PrefetchChunkState(int s0)
    {
        if (!_cache) return;
        Prefetcher.First(_pinRowsAt, s0); Prefetcher.First(_pinRowsMask, s0); Prefetcher.Ends(_pinRowsOwner, s0);
    }

    /// <summary>
    /// The rest positions of the chunk's pinned particles, into the rest rows of the rows that hold pins: from the
    /// per-strand pin cache (the world's rest arrays are not touched), else from the world.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    void IStrandChunkSystem.PrepareChunk(HairWorld w, int s0, scoped in StrandChunk chunk)
    {
        bool rowsCached = _cache && _cachedAt.Length == w.StrandCount && _pinRows.Length == 3 * w.ParticleCount;
        long at = w.EditStamp + 1L;
        if (rowsCached) PrefetchPinRows(w, s0 + StrandChunk.Lanes);
        if (rowsCached && _pinRowsAt[s0] == at && _pinRowsMask[s0] == chunk.PinnedRows && StrandChunk.OwnsBlock(_pinRowsOwner, s0))
        {
            CopyPinRows(chunk, fromBlock: true);
            return;
        }
        FillPinRows(w, s0, chunk);
        if (!rowsCached) return;
        CopyPinRows(chunk, fromBlock: false);
        _pinRowsAt[s0] = at; _pinRowsMask[s0] = chunk.PinnedRows;
        StrandChunk.ClaimBlock(_pinRowsOwner, s0);
    }

    /// <summary>
    /// The next chunk's cached pinned rows (a few scattered lines per chunk, which the hardware prefetcher does not
    /// foresee), fetched while this chunk computes.
    /// </summary>
    private unsafe void PrefetchPinRows(HairWorld w, int s0)
    {
        if (!Sse.IsSupported || s0 >= w.StrandCount) return;
        const int L = StrandChunk.Lanes;
        int block = 3 * w.StrandFirst[s0], h = w.StrandCapacity[s0];
        if (block + 3 * h * L > _pinRows.Length) return;
        fixed (float* p = &_pinRows[block])
            for (ulong rows = _pinRowsMask[s0]; rows != 0; rows &= rows - 1)
            {
                int k = BitOperations.TrailingZeroCount(rows);
                for (int f = 0; f < 3; f++)
                {
                    byte* line = (byte*)(p + (f * h + k) * L);
                    Sse.Prefetch0(line); Sse.Prefetch0(line + 64);
                }
            }
    }

    /// <summary>The chunk's pinned rest rows to (or from) its block of <see cref="_pinRows"/>.</summary>
    private void CopyPinRows(scoped in StrandChunk chunk, bool fromBlock)
    {
        const int L = StrandChunk.Lanes;
        int block = 3 * chunk.Firsts[0], h = chunk.Height;
        if (block + 3 * h * L > _pinRows.Length) throw new InvalidOperationException("The pin rows' block is outside the cache.");
        ref float cache = ref MemoryMarshal.GetArrayDataReference(_pinRows);
        for (ulong rows = chunk.PinnedRows; rows != 0; rows &= rows - 1)
        {
            int k = BitOperations.TrailingZeroCount(rows);
            for (int f = 0; f < 3; f++)
            {
                // Two 64-byte vectors per row (a span copy per row cost a call each).
                ref float stored = ref Unsafe.Add(ref cache, block + (f * h + k) * L);
                ref float row = ref chunk.Row(StrandChunk.RestX + f, k);
                if (fromBlock) { Vector512.LoadUnsafe(ref stored).StoreUnsafe(ref row); Vector512.LoadUnsafe(ref stored, 16).StoreUnsafe(ref row, 16); }
                else { Vector512.LoadUnsafe(ref row).StoreUnsafe(ref stored); Vector512.LoadUnsafe(ref row, 16).StoreUnsafe(ref stored, 16); }
            }
        }
    }

    /// <summary>The rest positions of the chunk's pinned particles, into its pinned rest rows (zero where a lane has no pin there).</summary>
    private void FillPinRows(HairWorld w, int s0, scoped in StrandChunk chunk)
    {
        for (ulong rows = chunk.PinnedRows; rows != 0; rows &= rows - 1)
        {
            int k = BitOperations.TrailingZeroCount(rows);
            for (int f = StrandChunk.RestX; f <= StrandChunk.RestZ; f++)
                MemoryMarshal.CreateSpan(ref chunk.Row(f, k), StrandChunk.Lanes).Clear();
        }
        bool cached = _cache && _cachedAt.Length == w.StrandCount;
        long stamp = w.EditStamp + 1L;
        for (int l = 0; l < StrandChunk.Lanes; l++)
        {
            int s = s0 + l, first = chunk.Firsts[l];
            if (cached && _cachedAt[s] != stamp) CachePins(w, s, stamp);
            if (cached && _pinCount[s] >= 0)
            {
                for (int p = 0; p < _pinCount[s]; p++)
                {
                    int c = s * MaxCachedPins + p, k = _pinIndex[c] - first;
                    Unsafe.Add(ref chunk.Row(StrandChunk.RestX, k), l) = _pinRest[3 * c];
                    Unsafe.Add(ref chunk.Row(StrandChunk.RestY, k), l) = _pinRest[3 * c + 1];
                    Unsafe.Add(ref chunk.Row(StrandChunk.RestZ, k), l) = _pinRest[3 * c + 2];
                }
                continue;
            }
            for (ulong rows = chunk.PinnedRows; rows != 0; rows &= rows - 1)
            {
                int k = BitOperations.TrailingZeroCount(rows), i = first + k;
                // A row pinned only by particles past a cut or a shorter capacity holds no pin of this strand.
                if (k >= w.StrandParticleCount[s] || w.InvMass[i] != 0f) continue;
                Unsafe.Add(ref chunk.Row(StrandChunk.RestX, k), l) = w.RestX[i];
                Unsafe.Add(ref chunk.Row(StrandChunk.RestY, k), l) = w.RestY[i];
                Unsafe.Add(ref chunk.Row(StrandChunk.RestZ, k), l) = w.RestZ[i];
            }
        }
    }

    // This frame's rigid carry and each substep's head pose on 16 lanes, built once for all chunks.
    private PoseLanes _chunkCarry;
    private PoseLanes16[] _chunkPins16 = [];

    bool IStrandChunkSystem.BeginChunkFrame(FrameContext ctx)
    {
        _chunkCarry = new PoseLanes(ctx.TeleportDelta);
        if (_chunkPins16.Length < ctx.Substeps) _chunkPins16 = new PoseLanes16[ctx.Substeps];
        for (int s = 0; s < ctx.Substeps; s++) _chunkPins16[s] = new PoseLanes16(new PoseLanes(ctx.HeadAt(s)));
        return true;
    }

    /// <summary>As <see cref="Run"/> on a chunk: the rigid carry on a teleport, then the rows that hold pins, 16 lanes at a time with <see cref="PinKernel"/>'s arithmetic.</summary>
    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    bool IStrandChunkSystem.RunChunk(HairScene scene, FrameContext ctx, int substep, scoped in StrandChunk chunk)
    {
        int width = Vector<float>.Count;
        if (substep == 0 && ctx.Teleported)
        {
            ref readonly var delta = ref _chunkCarry;
            ref float px = ref chunk.Row(StrandChunk.X, 0), py = ref chunk.Row(StrandChunk.Y, 0), pz = ref chunk.Row(StrandChunk.Z, 0);
            ref float vx = ref chunk.Row(StrandChunk.VelX, 0), vy = ref chunk.Row(StrandChunk.VelY, 0), vz = ref chunk.Row(StrandChunk.VelZ, 0);
            for (int i = 0, cells = chunk.Height * StrandChunk.Lanes; i < cells; i += width)
            {
                delta.Point(Simd.Ld(ref px, i), Simd.Ld(ref py, i), Simd.Ld(ref pz, i), out var x, out var y, out var z);
                Simd.St(ref px, i, x); Simd.St(ref py, i, y); Simd.St(ref pz, i, z);
                delta.Direction(Simd.Ld(ref vx, i), Simd.Ld(ref vy, i), Simd.Ld(ref vz, i), out x, out y, out z);
                Simd.St(ref vx, i, x); Simd.St(ref vy, i, y); Simd.St(ref vz, i, z);
            }
        }
        if (chunk.PinnedRows == 0) return true;
        // 16 lanes at a time, the PinKernel's arithmetic (PoseLanes16: the same, in the same order).
        ref readonly var head = ref _chunkPins16[substep];
        ref float x0 = ref chunk.Row(StrandChunk.X, 0), y0 = ref chunk.Row(StrandChunk.Y, 0), z0 = ref chunk.Row(StrandChunk.Z, 0);
        ref float vx0 = ref chunk.Row(StrandChunk.VelX, 0), vy0 = ref chunk.Row(StrandChunk.VelY, 0), vz0 = ref chunk.Row(StrandChunk.VelZ, 0);
        ref float m0 = ref chunk.Row(StrandChunk.InvMass, 0);
        ref float rx0 = ref chunk.Row(StrandChunk.RestX, 0), ry0 = ref chunk.Row(StrandChunk.RestY, 0), rz0 = ref chunk.Row(StrandChunk.RestZ, 0);
        var zero = Vector512<float>.Zero;
        for (ulong rows = chunk.PinnedRows; rows != 0; rows &= rows - 1)
        {
            nuint row = (nuint)(BitOperations.TrailingZeroCount(rows) * StrandChunk.Lanes);
            for (nuint o = row; o < row + StrandChunk.Lanes; o += 16)
            {
                var pinned = Vector512.Equals(Vector512.LoadUnsafe(ref m0, o), zero);
                if (pinned == zero) continue;
                head.Point(Vector512.LoadUnsafe(ref rx0, o), Vector512.LoadUnsafe(ref ry0, o), Vector512.LoadUnsafe(ref rz0, o), out var gx, out var gy, out var gz);
                Vector512.ConditionalSelect(pinned, gx, Vector512.LoadUnsafe(ref x0, o)).StoreUnsafe(ref x0, o);
                Vector512.ConditionalSelect(pinned, gy, Vector512.LoadUnsafe(ref y0, o)).StoreUnsafe(ref y0, o);
                Vector512.ConditionalSelect(pinned, gz, Vector512.LoadUnsafe(ref z0, o)).StoreUnsafe(ref z0, o);
                Vector512.ConditionalSelect(pinned, zero, Vector512.LoadUnsafe(ref vx0, o)).StoreUnsafe(ref vx0, o);
                Vector512.ConditionalSelect(pinned, zero, Vector512.LoadUnsafe(ref vy0, o)).StoreUnsafe(ref vy0, o);
                Vector512.ConditionalSelect(pinned, zero, Vector512.LoadUnsafe(ref vz0, o)).StoreUnsafe(ref vz0, o);
            }
        }
        return true;
    }

    /// <summary>Finds strand s's pinned live particles (InvMass = 0) and caches up to two with their rest positions.</summary>
    private void CachePins(HairWorld w, int s, long stamp)
    {
        int width = Vector<float>.Count;
        int i = w.StrandFirst[s], stop = i + w.StrandParticleCount[s], count = 0;
        ref float m = ref Simd.At(w.InvMass, 0);
        for (; i < stop && count >= 0; i += width)
        {
            // Whole chunks by SIMD compare; the strand's last partial chunk lane by lane (never read past it).
            uint bits;
            if (i + width <= stop) bits = Simd.MaskBits(Vector.Equals(Simd.Ld(ref m, i), Vector<float>.Zero));
            else
            {
                bits = 0;
                for (int l = 0; l < stop - i; l++) if (Unsafe.Add(ref m, i + l) == 0f) bits |= 1u << l;
            }
            for (; bits != 0 && count >= 0; bits &= bits - 1)
            {
                if (count == MaxCachedPins) { count = -1; break; }
                int p = i + BitOperations.TrailingZeroCount(bits), c = s * MaxCachedPins + count++;
                _pinIndex[c] = p;
                _pinRest[3 * c] = w.RestX[p]; _pinRest[3 * c + 1] = w.RestY[p]; _pinRest[3 * c + 2] = w.RestZ[p];
            }
        }
        _pinCount[s] = count;
        _cachedAt[s] = stamp;
    }

    private static void CarryRigidly(HairWorld w, in RigidTransform delta, int begin, int end)
    {
        var pose = new PoseLanes(delta);
        int i = w.StrandFirst[begin], stop = w.StrandFirst[end - 1] + w.StrandCapacity[end - 1];
        int width = Vector<float>.Count;
        ref float px = ref Simd.At(w.PosX, 0), py = ref Simd.At(w.PosY, 0), pz = ref Simd.At(w.PosZ, 0);
        ref float vx = ref Simd.At(w.VelX, 0), vy = ref Simd.At(w.VelY, 0), vz = ref Simd.At(w.VelZ, 0);
        for (; i <= stop - width; i += width)
        {
            pose.Point(Simd.Ld(ref px, i), Simd.Ld(ref py, i), Simd.Ld(ref pz, i), out var x, out var y, out var z);
            Simd.St(ref px, i, x); Simd.St(ref py, i, y); Simd.St(ref pz, i, z);
            pose.Direction(Simd.Ld(ref vx, i), Simd.Ld(ref vy, i), Simd.Ld(ref vz, i), out x, out y, out z);
            Simd.St(ref vx, i, x); Simd.St(ref vy, i, y); Simd.St(ref vz, i, z);
        }
        for (; i < stop; i++)
        {
            w.PutPosition(i, pose.Point(w.GetPosition(i)));
            w.PutVelocity(i, pose.Direction(w.GetVelocity(i)));
        }
    }

    private readonly struct PinKernel : IParticleKernel
    {
        private readonly PoseLanes _head;
        public PinKernel(PoseLanes head) => _head = head;

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public void Chunk(ref float px, ref float py, ref float pz, ref float vx, ref float vy, ref float vz,
                          ref float invMass, ref float rx, ref float ry, ref float rz)
        {
            var pinned = Vector.Equals(Simd.Ld(ref invMass, 0), Vector<float>.Zero);
            if (Vector.EqualsAll(pinned, Vector<int>.Zero)) return;
            _head.Point(Simd.Ld(ref rx, 0), Simd.Ld(ref ry, 0), Simd.Ld(ref rz, 0), out var gx, out var gy, out var gz);
            Simd.St(ref px, 0, Simd.Sel(pinned, gx, Simd.Ld(ref px, 0)));
            Simd.St(ref py, 0, Simd.Sel(pinned, gy, Simd.Ld(ref py, 0)));
            Simd.St(ref pz, 0, Simd.Sel(pinned, gz, Simd.Ld(ref pz, 0)));
            Simd.St(ref vx, 0, Simd.Sel(pinned, Vector<float>.Zero, Simd.Ld(ref vx, 0)));
            Simd.St(ref vy, 0, Simd.Sel(pinned, Vector<float>.Zero, Simd.Ld(ref vy, 0)));
            Simd.St(ref vz, 0, Simd.Sel(pinned, Vector<float>.Zero, Simd.Ld(ref vz, 0)));
        }
    }
}
