namespace HairSim.Fast;

/// <summary>
/// Per-thread scratch for per-strand kernels: sized once for the longest strand (and grown only if a longer one
/// appears), so a step allocates nothing after the first frame on each worker thread.
/// Field f of the scratch is the slice starting at <see cref="Offset"/>(f); index −Width … −1 of each slice is
/// valid too, so kernels can read one particle before the root without a branch.
/// </summary>
internal sealed class StrandScratch
{
    [ThreadStatic] private static StrandScratch? _current;

    public readonly float[] Data;
    public readonly int Stride;
    public readonly int Capacity;
    public readonly int Fields;

    private StrandScratch(int capacity, int fields)
    {
        int width = System.Numerics.Vector<float>.Count;
        Capacity = capacity;
        Fields = fields;
        Stride = capacity + 3 * width;
        Data = new float[Stride * fields];
    }

    public int Offset(int field) => field * Stride + System.Numerics.Vector<float>.Count;

    public static StrandScratch For(int capacity, int fields)
    {
        var s = _current;
        if (s == null || s.Capacity < capacity || s.Fields < fields)
            _current = s = new StrandScratch(Math.Max(capacity, s?.Capacity ?? 0), Math.Max(fields, s?.Fields ?? 0));
        return s;
    }
}
