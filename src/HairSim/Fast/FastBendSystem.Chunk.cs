using System.Runtime.CompilerServices;
namespace HairSim.Fast;

/// <summary>
/// The bend sweep on a <see cref="StrandChunk"/>: 32 uncut 16-particle strands in rows, the 16-lane sweep's two
/// chains, so the default pipeline steps chunks (every system's substeps in L1) like the source's did. The sweep
/// updates the chunk's velocity rows in place; its per-strand rest directions and spring shares are transposed into
/// the chunk's bend rows once per chunk and frame. The same arithmetic on the same rows as the tiled sweep, so the
/// same bits (StrandChunkTests).
/// </summary>
public sealed partial class FastBendSystem : IStrandChunkSystem
{
    bool IStrandChunkSystem.SupportsChunks => UsesWide;
    ChunkFields IStrandChunkSystem.ChunkNeeds => ChunkFields.RestLength;
    bool IStrandChunkSystem.TakesCutStrands => true;

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

    void IStrandChunkSystem.PrepareChunk(HairWorld w, int s0, scoped StrandChunk chunk)
    {
        if (!_chunkActive) return;
        for (int s = s0; s < s0 + StrandChunk.Lanes; s++) EnsureCache(w, s, _chunkSag, _chunkH, _chunkZeta);
        int first = w.StrandFirst[s0], height = chunk.Height;
        StrandChunkRunner.LoadRows(_restX, first, height, ref chunk.Row(StrandChunk.BendRestX, 0));
        StrandChunkRunner.LoadRows(_restY, first, height, ref chunk.Row(StrandChunk.BendRestY, 0));
        StrandChunkRunner.LoadRows(_restZ, first, height, ref chunk.Row(StrandChunk.BendRestZ, 0));
        StrandChunkRunner.LoadRows(_jointA, first, height, ref chunk.Row(StrandChunk.BendA, 0));
        StrandChunkRunner.LoadRows(_jointB, first, height, ref chunk.Row(StrandChunk.BendB, 0));
    }

    bool IStrandChunkSystem.RunChunk(HairScene scene, FrameContext ctx, int substep, scoped StrandChunk chunk)
    {
        if (!_chunkActive) return true;
        var t = chunk.Tile;
        var p = new SweepParams(ctx, substep, StrandChunk.Lanes,
            t.Offset(StrandChunk.X), t.Offset(StrandChunk.Y), t.Offset(StrandChunk.Z),
            t.Offset(StrandChunk.VelX), t.Offset(StrandChunk.VelY), t.Offset(StrandChunk.VelZ),
            t.Offset(StrandChunk.InvMass), t.Offset(StrandChunk.RestLength),
            t.Offset(StrandChunk.BendRestX), t.Offset(StrandChunk.BendRestY), t.Offset(StrandChunk.BendRestZ),
            t.Offset(StrandChunk.BendA), t.Offset(StrandChunk.BendB));
        ref float d = ref t.Data[0];
        Sweep16(ref d, ref d, chunk.Height, in p);
        return true;
    }
}
