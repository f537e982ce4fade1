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
        var t = chunk.Tile;
        if (height == StrandChunk.Rows)
        {
            Transpose.StrandsIn(_restX, first, StrandChunk.Rows, t, StrandChunk.BendRestX, StrandChunk.Lanes);
            Transpose.StrandsIn(_restY, first, StrandChunk.Rows, t, StrandChunk.BendRestY, StrandChunk.Lanes);
            Transpose.StrandsIn(_restZ, first, StrandChunk.Rows, t, StrandChunk.BendRestZ, StrandChunk.Lanes);
            Transpose.StrandsIn(_jointA, first, StrandChunk.Rows, t, StrandChunk.BendA, StrandChunk.Lanes);
            Transpose.StrandsIn(_jointB, first, StrandChunk.Rows, t, StrandChunk.BendB, StrandChunk.Lanes);
            return;
        }
        // Shorter strands (the sweep stops at the chunk's height): strided transposes where 16 floats past the last
        // strand are readable, else element by element; once per chunk and frame.
        ReadOnlySpan<float[]> src = [_restX, _restY, _restZ, _jointA, _jointB];
        int blocks = (height + 15) / 16;
        bool strided = first + (StrandChunk.Lanes - 1) * height + 16 * blocks <= _restX.Length;
        for (int f = 0; f < src.Length; f++)
        {
            ref float row0 = ref chunk.Row(StrandChunk.BendRestX + f, 0);
            ref float s = ref Simd.At(src[f], first);
            if (strided)
            {
                for (int b = 0; b < blocks; b++)
                {
                    ref float rows = ref Unsafe.Add(ref row0, 16 * b * StrandChunk.Lanes);
                    Transpose.In16Strided(ref Unsafe.Add(ref s, 16 * b), height, ref rows, StrandChunk.Lanes);
                    Transpose.In16Strided(ref Unsafe.Add(ref s, 16 * height + 16 * b), height, ref Unsafe.Add(ref rows, 16), StrandChunk.Lanes);
                }
                continue;
            }
            for (int l = 0; l < StrandChunk.Lanes; l++)
                for (int k = 0; k < height; k++) Unsafe.Add(ref row0, k * StrandChunk.Lanes + l) = Unsafe.Add(ref s, l * height + k);
        }
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
