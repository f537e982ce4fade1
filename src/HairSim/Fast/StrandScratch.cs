using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;

namespace HairSim.Fast;

/// <summary>
/// Scratch for per-strand kernels and length tiles: a number of slices (fields, see <see cref="Size"/>) of <see cref="Stride"/> floats.
/// Field f starts at <see cref="Offset"/>(f); indices −Width … −1 of each slice are valid too, so kernels can read
/// one particle before the root without a branch. Callers put it on the stack (stackalloc, up to
/// <see cref="StackFloats"/>), so a step allocates nothing on any thread, ever; only scratch for very long strands
/// falls back to a per-thread heap buffer, allocated once per thread.
/// </summary>
internal readonly ref struct StrandScratch
{
    /// <summary>Scratch up to this size (64 KB) goes on the stack: strands up to ~90 particles for length tiles, ~600 for shape matching.</summary>
    public const int StackFloats = 16 * 1024;

    [ThreadStatic] private static float[]? _heap;

    public readonly Span<float> Data;
    public readonly int Stride;

    public StrandScratch(Span<float> data, int capacity)
    {
        // Every field starts on a 64-byte cache line, so no 16-lane load or store of a row splits a line. (A heap
        // buffer the GC later moves only loses the alignment, not the layout.)
        Data = data.Slice(ToLine(ref MemoryMarshal.GetReference(data)));
        Stride = Lined(capacity + 3 * Vector<float>.Count);
    }

    /// <summary>Floats in a 64-byte cache line.</summary>
    public const int LineFloats = 16;

    /// <summary>Floats from <paramref name="first"/> to the next start of a 64-byte line (0 … 15): where pinned or stack buffers begin their lined data.</summary>
    public static unsafe int ToLine(ref float first) =>
        (int)((LineFloats - (((nint)Unsafe.AsPointer(ref first) >> 2) & (LineFloats - 1))) & (LineFloats - 1));
    private static int Lined(int n) => (n + LineFloats - 1) / LineFloats * LineFloats;

    /// <summary>Floats needed for <paramref name="fields"/> slices of <paramref name="capacity"/> elements.</summary>
    public static int Size(int capacity, int fields) => Lined(capacity + 3 * Vector<float>.Count) * fields + LineFloats;

    /// <summary>Where field <paramref name="field"/>'s element 0 is: a line in, so the Width elements before it are in the slice too.</summary>
    public int Offset(int field) => field * Stride + LineFloats;

    /// <summary>The per-thread heap buffer for scratch too large for the stack.</summary>
    public static Span<float> Heap(int size)
    {
        var h = _heap;
        if (h == null || h.Length < size) _heap = h = new float[size];
        return h.AsSpan(0, size);
    }
}
