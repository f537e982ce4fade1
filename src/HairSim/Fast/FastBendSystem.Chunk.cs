using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
namespace HairSim.Fast;

/// <summary>
/// The bend sweep on a <see cref="StrandChunk"/>: 32 uncut 16-particle strands in rows, the 16-lane sweep's two
/// chains, so the default pipeline steps chunks (every system's substeps in L1) like the source's did. The sweep
/// updates the chunk's velocity rows in place; its per-strand rest directions and spring shares are read from a
/// block kept in the chunk's row layout (refilled only when they change). The same arithmetic on the same rows as the tiled sweep, so the
/// same bits (StrandChunkTests).
/// </summary>
public sealed partial class FastBendSystem : IStrandChunkSystem
{
    bool IStrandChunkSystem.SupportsChunks => UsesWide;
    ChunkFields IStrandChunkSystem.ChunkNeeds => ChunkFields.RestLength;
    bool IStrandChunkSystem.TakesCutStrands => true;
    /// <summary>The sweep fetches a share of the next chunk's data per half row (<see cref="Prefetcher.Row"/>).</summary>
    bool IStrandChunkSystem.SweepsRows => _chunkActive;

    // This frame: the sweep integrates each row first, in place of FastIntegrateSystem's own pass (see FuseIntegrate).
    private bool _fuseIntegrate;

    /// <summary>
    /// Called by the chunk runner after <see cref="IStrandChunkSystem.BeginChunkFrame"/> when <see cref="FastIntegrateSystem"/>
    /// runs just before this system: whether this frame's chunk sweeps take its pass over (<see cref="Sweep16{TIntegrate}"/>),
    /// so the runner skips it. Only while the sweep runs (the rest-shape model).
    /// </summary>
    internal bool FuseIntegrate(bool wanted) => _fuseIntegrate = wanted && _chunkActive;

    /// <summary>Whether this frame's chunks are swept (the rest-shape model): set by <see cref="IStrandChunkSystem.BeginChunkFrame"/>.</summary>
    internal bool SweepsChunks => _chunkActive;

    // This frame's settings, for PrepareChunk (which gets no context).
    private float _chunkSag, _chunkH, _chunkZeta;
    private bool _chunkActive;

    bool IStrandChunkSystem.BeginChunkFrame(FrameContext ctx)
    {
        var st = ctx.Settings;
        _chunkActive = st.Bend == BendModel.RestShape;
        _chunkSag = st.Sag; _chunkH = ctx.H; _chunkZeta = st.BendDamping;
        return true;
    }

    // The chunk's rest directions and joint shares, kept in its row layout between frames: the block of the chunk whose
    // first particle is F holds field f's row k, lane l at ChunkBendFields·F + f·32·height + 32k + l, so the blocks of
    // disjoint chunks never overlap and follow one another in memory as the chunks do. A chunk's sweep reads its block
    // in place (no transposes per frame); the block is refilled only when a strand's cache changed (FillCache and
    // CacheShares clear _chunkBlock) or its strands were last laid out by another chunk.
    private const int ChunkBendFields = 5;
    private readonly float[] _chunkBend;
    /// <summary>Per strand: the first strand of the chunk whose block holds its current rest data, or −1.</summary>
    private readonly int[] _chunkBlock;

    // Per chunk (keyed by its first strand): the edit stamp, settings and cache generation under which its 32 strands
    // were last checked and laid out. While they all hold (and no other chunk took over its strands' blocks), the
    // chunk needs no per-strand check: a frame's chunks then cost one comparison each instead of 32 cache checks.
    private readonly long[] _checkedGeneration, _checkedStamp;
    private readonly float[] _checkedSag, _checkedH, _checkedZeta;
    /// <summary>Bumped whenever a strand's cached rest data or shares change (FillCache, CacheShares).</summary>
    private long _cacheGeneration;

    void IStrandChunkSystem.PrefetchChunkState(int s0)
    {
        if (!_chunkActive) return;
        Prefetcher.First(_checkedGeneration, s0); Prefetcher.First(_checkedStamp, s0); Prefetcher.First(_checkedSag, s0);
        Prefetcher.First(_checkedH, s0); Prefetcher.First(_checkedZeta, s0); Prefetcher.Ends(_chunkBlock, s0);
    }

    void IStrandChunkSystem.PrepareChunk(HairWorld w, int s0, scoped in StrandChunk chunk)
    {
        if (!_chunkActive) return;
        long stamp = w.EditStamp + 1L;
        if (_checkedGeneration[s0] == Volatile.Read(ref _cacheGeneration) + 1 && _checkedStamp[s0] == stamp && _checkedSag[s0] == _chunkSag
            && _checkedH[s0] == _chunkH && _checkedZeta[s0] == _chunkZeta && StrandChunk.OwnsBlock(_chunkBlock, s0)) return;
        PrepareStrands(w, s0, chunk);
        // Read after the strands' own updates: a bump by another thread meanwhile was for strands of another chunk.
        _checkedGeneration[s0] = Volatile.Read(ref _cacheGeneration) + 1;
        _checkedStamp[s0] = stamp; _checkedSag[s0] = _chunkSag; _checkedH[s0] = _chunkH; _checkedZeta[s0] = _chunkZeta;
    }

    private void PrepareStrands(HairWorld w, int s0, scoped in StrandChunk chunk)
    {
        bool laidOut = true;
        for (int s = s0; s < s0 + StrandChunk.Lanes; s++)
        {
            EnsureCache(w, s, _chunkSag, _chunkH, _chunkZeta);
            laidOut &= _chunkBlock[s] == s0;
        }
        if (laidOut) return;
        int first = w.StrandFirst[s0], height = chunk.Height, cells = StrandChunk.Lanes * height;
        // Transposed through the tile's bend rows (whole 16-row blocks), then the chunk's own rows copied out.
        ReadOnlySpan<float[]> src = [_restX, _restY, _restZ, _jointA, _jointB];
        for (int f = 0; f < ChunkBendFields; f++)
        {
            ref float rows = ref chunk.Row(StrandChunk.BendRestX + f, 0);
            StrandChunkRunner.LoadRows(src[f], first, height, ref rows);
            MemoryMarshal.CreateReadOnlySpan(ref rows, cells).CopyTo(_chunkBend.AsSpan(ChunkBendFields * first + f * cells, cells));
        }
        StrandChunk.ClaimBlock(_chunkBlock, s0);
    }

    /// <summary>The chunk's block of rest directions and joint shares, which the sweep reads in place: prefetched with the chunk's fields.</summary>
    float[]? IStrandChunkSystem.ChunkBlock(int s0, int first, int cells, out int offset, out int fields)
    {
        offset = ChunkBendFields * first; fields = ChunkBendFields;
        return _chunkActive && s0 < _chunkBlock.Length && _chunkBlock[s0] == s0 ? _chunkBend : null;
    }

    bool IStrandChunkSystem.RunChunk(HairScene scene, FrameContext ctx, int substep, scoped in StrandChunk chunk)
    {
        if (!_chunkActive) return true;
        var t = chunk.Tile;
        int cells = StrandChunk.Lanes * chunk.Height;
        var p = new SweepParams(ctx, substep, StrandChunk.Lanes,
            t.Offset(StrandChunk.X), t.Offset(StrandChunk.Y), t.Offset(StrandChunk.Z),
            t.Offset(StrandChunk.VelX), t.Offset(StrandChunk.VelY), t.Offset(StrandChunk.VelZ),
            t.Offset(StrandChunk.InvMass), t.Offset(StrandChunk.RestLength),
            0, cells, 2 * cells, 3 * cells, 4 * cells, chunk.Prefetch, chunk.FarRows);
        ref float rest = ref _chunkBend[ChunkBendFields * chunk.Firsts[0]];
        // Rows past every lane's cut are left out (StrandChunk.LiveRows): no row before them reads them.
        if (_fuseIntegrate) Sweep16<Fused>(ref t.Data[0], ref rest, chunk.LiveRows, in p);
        else Sweep16<Apart>(ref t.Data[0], ref rest, chunk.LiveRows, in p);
        return true;
    }
}
