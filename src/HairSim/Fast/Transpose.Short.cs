using System.Diagnostics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using System.Runtime.Intrinsics;
using System.Runtime.Intrinsics.X86;

namespace HairSim.Fast;

/// <summary>
/// Transposes for short strands (2 … <see cref="MaxShort"/> particles): 16 strands of h particles are 16·h
/// consecutive floats, h vectors, and row k (particle k of each) is picked out of them with two-source permutes
/// (lane l takes float l·h + k), about h² operations for h rows instead of a full 16 × 16 transpose of 16 rows of
/// which h are used. Stores go the other way and write the 16·h floats exactly, with no spill into the next strands.
/// Timed against the 16 × 16 transposes in one process: 3- and 4-particle frames faster; at 6 and 8 particles slower
/// (more permutes, and tables for those heights that crowd L1), hence the limit of 4. The sources stay in registers and
/// the tables are read without bounds checks: a loop over source pairs held in an inline array on the stack made 2- to
/// 4-particle frames clearly slower (interleaved).
/// </summary>
internal static partial class Transpose
{
    /// <summary>The longest strand the short transposes take: beyond this the 16 × 16 transpose needs fewer operations.</summary>
    public const int MaxShort = 4;

    public static bool ShortAvailable => Avx512F.IsSupported;

    /// <summary>Whether strands of <paramref name="height"/> particles load and store through the short transposes.</summary>
    public static bool TakesShort(int height) => height <= MaxShort && ShortAvailable;

    // Per height h, row k and source pair p (vectors 2p, 2p + 1): the permute's indices and the lanes it supplies.
    // Loads: lane l of row k takes float q = l·h + k, from pair q / 32 at index q mod 32.
    // Stores: float e of output vector j is particle k = (16j + e) mod h of strand l = (16j + e) / h, from pair k / 2.
    private static class ShortTables
    {
        public const int Slots = (MaxShort + 1) * MaxShort * (MaxShort / 2);
        public static readonly int[] LoadIndex = new int[Slots * 16], StoreIndex = new int[Slots * 16];
        public static readonly float[] LoadMask = new float[Slots * 16], StoreMask = new float[Slots * 16];
        public static readonly bool Built = Build();

        private static bool Build()
        {
            float all = BitConverter.Int32BitsToSingle(-1);
            for (int h = 2; h <= MaxShort; h++)
                for (int k = 0; k < h; k++)
                    for (int l = 0; l < 16; l++)
                    {
                        int q = l * h + k, at = Slot(h, k, q / 32) * 16 + l;
                        LoadIndex[at] = q % 32; LoadMask[at] = all;
                        // As a store: output vector k, float l.
                        int flat = 16 * k + l, row = flat % h, strand = flat / h;
                        int sat = Slot(h, k, row / 2) * 16 + l;
                        StoreIndex[sat] = (row % 2) * 16 + strand; StoreMask[sat] = all;
                    }
            return true;
        }
    }

    private static int Slot(int h, int k, int p) => (h * MaxShort + k) * (MaxShort / 2) + p;

    /// <summary>16 strands of <paramref name="h"/> particles (16·h floats from <paramref name="strands"/>) into rows 0 … h − 1 of 16 tile columns.</summary>
    [MethodImpl(MethodImplOptions.NoInlining | MethodImplOptions.AggressiveOptimization)]
    public static void InShort(ref float strands, int h, ref float tile, int lanes)
    {
        // Each row is picked from the first pair of sources and, for h > 2, blended with its pick from the second (a
        // zero vector stands in past the last source).
        Debug.Assert(h >= 2 && h <= MaxShort);
        var v0 = Ld16(ref strands, 0); var v1 = Ld16(ref strands, 16);
        var v2 = h > 2 ? Ld16(ref strands, 32) : Vector512<float>.Zero;
        var v3 = h > 3 ? Ld16(ref strands, 48) : Vector512<float>.Zero;
        ref int index = ref MemoryMarshal.GetArrayDataReference(ShortTables.LoadIndex);
        ref float mask = ref MemoryMarshal.GetArrayDataReference(ShortTables.LoadMask);
        for (int k = 0; k < h; k++)
            St16(ref tile, k * lanes, Pick2(v0, v1, v2, v3, h > 2, Slot(h, k, 0) * 16, ref index, ref mask));
    }

    /// <summary>The inverse of <see cref="InShort"/>: rows 0 … h − 1 of 16 tile columns back into 16·h consecutive floats.</summary>
    [MethodImpl(MethodImplOptions.NoInlining | MethodImplOptions.AggressiveOptimization)]
    public static void OutShort(ref float tile, int lanes, ref float strands, int h)
    {
        Debug.Assert(h >= 2 && h <= MaxShort);
        var v0 = Ld16(ref tile, 0); var v1 = Ld16(ref tile, lanes);
        var v2 = h > 2 ? Ld16(ref tile, 2 * lanes) : Vector512<float>.Zero;
        var v3 = h > 3 ? Ld16(ref tile, 3 * lanes) : Vector512<float>.Zero;
        ref int index = ref MemoryMarshal.GetArrayDataReference(ShortTables.StoreIndex);
        ref float mask = ref MemoryMarshal.GetArrayDataReference(ShortTables.StoreMask);
        for (int j = 0; j < h; j++)
            St16(ref strands, 16 * j, Pick2(v0, v1, v2, v3, h > 2, Slot(h, j, 0) * 16, ref index, ref mask));
    }

    /// <summary>One vector picked from the source pairs (v0, v1) and, where <paramref name="second"/>, (v2, v3).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static Vector512<float> Pick2(Vector512<float> v0, Vector512<float> v1, Vector512<float> v2, Vector512<float> v3, bool second, int slot,
        ref int index, ref float mask)
    {
        var picked = Avx512F.PermuteVar16x32x2(v0, Vector512.LoadUnsafe(ref index, (nuint)slot), v1);
        if (!second) return picked;
        var part = Avx512F.PermuteVar16x32x2(v2, Vector512.LoadUnsafe(ref index, (nuint)(slot + 16)), v3);
        return Vector512.ConditionalSelect(Vector512.LoadUnsafe(ref mask, (nuint)(slot + 16)), part, picked);
    }
}
