namespace HairSim.Fast;

/// <summary>
/// The chunk rows of the per-particle fields that only an edit changes (inverse masses, and the rest lengths and rest
/// shape when a system needs them), kept in row layout between frames with the chunk's pinned-row mask. A chunk seen
/// again unedited copies its rows from here instead of transposing them out of the world's arrays
/// (two 16 × 16 transposes a field), and skips the pinned-row scan. Writers of masses or rest data call
/// <see cref="HairWorld.MarkEdited"/> (as every cache derived from them requires), which retires every block.
/// Keyed like head follow's pinned rows: per chunk (at its first strand) the edit stamp its block was made under,
/// and per strand the chunk whose block holds its rows (a chunk that started elsewhere overwrote part of a block).
/// Jobs write only their own chunks' entries and blocks.
/// </summary>
internal sealed class ChunkConstantRows
{
    private readonly int[] _fields;
    // Per chunk, at FieldCount × its first particle: each field's rows (32 lanes a row, the chunk's height of rows).
    private float[] _rows = [];
    private long[] _madeAt = [];
    private ulong[] _pinned = [];
    private int[] _owner = [];

    public ChunkConstantRows(ChunkFields needs)
    {
        var fields = new List<int> { StrandChunk.InvMass };
        if ((needs & ChunkFields.RestLength) != 0) fields.Add(StrandChunk.RestLength);
        if ((needs & ChunkFields.Shape) != 0) { fields.Add(StrandChunk.ShapePrev); fields.Add(StrandChunk.ShapeMid); fields.Add(StrandChunk.ShapeNext); }
        _fields = [.. fields];
    }

    /// <summary>The chunk fields kept here.</summary>
    public ReadOnlySpan<int> Fields => _fields;

    /// <summary>The blocks (for the prefetcher): the chunk from particle <c>first</c> keeps field k's rows at <c>Fields.Length · first + k · cells</c>.</summary>
    public float[] Blocks => _rows;

    /// <summary>Sizes the cache to the world, on the calling thread before the jobs (allocates only when the world's size changed).</summary>
    public void Fit(HairWorld w)
    {
        if (_madeAt.Length == w.StrandCount && _rows.Length == _fields.Length * w.ParticleCount) return;
        _rows = new float[_fields.Length * w.ParticleCount];
        _madeAt = new long[w.StrandCount]; _pinned = new ulong[w.StrandCount]; _owner = new int[w.StrandCount];
        Array.Fill(_owner, -1);
    }

    /// <summary>The lines of the per-chunk entries the next chunks will read (see <see cref="IStrandChunkSystem.PrefetchChunkState"/>).</summary>
    public void PrefetchState(int s0)
    {
        Prefetcher.First(_madeAt, s0); Prefetcher.First(_pinned, s0); Prefetcher.Ends(_owner, s0);
    }

    /// <summary>Whether the chunk from strand s0 (first particle <paramref name="first"/>) has its rows here, made since the world's last edit.</summary>
    public bool Holds(HairWorld w, int s0, int first, int height) =>
        _madeAt.Length == w.StrandCount && _madeAt[s0] == w.EditStamp + 1L && StrandChunk.OwnsBlock(_owner, s0)
        && (long)_fields.Length * (first + StrandChunk.Lanes * height) <= _rows.Length;

    /// <summary>
    /// The chunk's rows into the tile, as the transposes from the world put them: the rows of its own particles, and
    /// for capacities the 16 × 16 transposes round up to whole blocks, zeros in the rows past them (the transposes put
    /// the next strands' particles there; the chunk masks those rows either way). Returns the pinned-row mask kept with them.
    /// </summary>
    public ulong CopyTo(int s0, int first, int height, scoped StrandScratch tile)
    {
        int cells = StrandChunk.Lanes * height;
        int padded = Transpose.TakesShort(height) ? cells : (height + 15) / 16 * 16 * StrandChunk.Lanes;
        int at = _fields.Length * first;
        foreach (int f in _fields)
        {
            var rows = tile.Data.Slice(tile.Offset(f), padded);
            _rows.AsSpan(at, cells).CopyTo(rows);
            rows.Slice(cells).Clear();
            at += cells;
        }
        return _pinned[s0];
    }

    /// <summary>
    /// The chunk's rows transposed from the world's arrays into the tile (as every chunk loaded them before), and kept
    /// here as loaded (before the cut masks change the masses); valid once <see cref="KeepPinned"/> adds the mask.
    /// </summary>
    public void LoadAndKeep(HairWorld w, int s0, int first, int height, scoped StrandScratch tile)
    {
        foreach (int f in _fields) StrandChunkRunner.LoadRows(Source(w, f), first, height, ref tile.Data[tile.Offset(f)]);
        Keep(w, s0, first, height, tile);
    }

    /// <summary>The world's array behind a kept field.</summary>
    private static float[] Source(HairWorld w, int field) => field switch
    {
        StrandChunk.InvMass => w.InvMass,
        StrandChunk.RestLength => w.RestLength,
        StrandChunk.ShapePrev => w.ShapePrev,
        StrandChunk.ShapeMid => w.ShapeMid,
        StrandChunk.ShapeNext => w.ShapeNext,
        _ => throw new ArgumentOutOfRangeException(nameof(field)),
    };

    private void Keep(HairWorld w, int s0, int first, int height, scoped StrandScratch tile)
    {
        int cells = StrandChunk.Lanes * height;
        if (_madeAt.Length != w.StrandCount || (long)_fields.Length * (first + cells) > _rows.Length) return;
        int at = _fields.Length * first;
        foreach (int f in _fields)
        {
            tile.Data.Slice(tile.Offset(f), cells).CopyTo(_rows.AsSpan(at, cells));
            at += cells;
        }
        // Not yet valid: the mask comes after the cut masks (KeepPinned).
        _madeAt[s0] = 0;
        StrandChunk.ClaimBlock(_owner, s0);
    }

    /// <summary>The chunk's pinned-row mask (from the masked masses); the block is valid from here until the next edit.</summary>
    public void KeepPinned(HairWorld w, int s0, ulong pinned)
    {
        if (_madeAt.Length != w.StrandCount || _owner[s0] != s0) return;
        _pinned[s0] = pinned;
        _madeAt[s0] = w.EditStamp + 1L;
    }
}
