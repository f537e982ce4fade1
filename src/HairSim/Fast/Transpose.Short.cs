using System.Runtime.CompilerServices;
using System.Runtime.Intrinsics;
using System.Runtime.Intrinsics.X86;

namespace HairSim.Fast;

/// <summary>
/// Transposes for short strands (2 … <see cref="MaxShort"/> particles): 16 strands of h particles are 16·h
/// consecutive floats, h vectors, and row k (particle k of each) is picked out of them with two-source permutes
/// (lane l takes float l·h + k), about h² operations for h rows instead of a full 16 × 16 transpose of 16 rows of
/// which h are used. Stores go the other way and write the 16·h floats exactly, with no spill into the next strands.
/// Timed against the 16 × 16 transposes in one process: 3- and 4-particle frames faster; at 6 and 8 particles slower
/// (more permutes, and tables for those heights that crowd L1), hence the limit of 4.
/// </summary>
internal static partial class Transpose
{
    /// <summary>The longest strand the short transposes take: beyond this the 16 × 16 transpose needs fewer operations.</summary>
    public const int MaxShort = 4;

    public static bool ShortAvailable => Avx512F.IsSupported;

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
    [MethodImpl(MethodImplOptions.NoInlining)]
    public static void InShort(ref float strands, int h, ref float tile, int lanes)
    {
        var v = new Sources();
        for (int i = 0; i < h; i++) v[i] = Ld16(ref strands, 16 * i);
        v[h] = Vector512<float>.Zero;
        int pairs = (h + 1) / 2;
        for (int k = 0; k < h; k++)
            St16(ref tile, k * lanes, Pick(in v, pairs, Slot(h, k, 0) * 16, ShortTables.LoadIndex, ShortTables.LoadMask));
    }

    /// <summary>The inverse of <see cref="InShort"/>: rows 0 … h − 1 of 16 tile columns back into 16·h consecutive floats.</summary>
    [MethodImpl(MethodImplOptions.NoInlining)]
    public static void OutShort(ref float tile, int lanes, ref float strands, int h)
    {
        var v = new Sources();
        for (int k = 0; k < h; k++) v[k] = Ld16(ref tile, k * lanes);
        v[h] = Vector512<float>.Zero;
        int pairs = (h + 1) / 2;
        for (int j = 0; j < h; j++)
            St16(ref strands, 16 * j, Pick(in v, pairs, Slot(h, j, 0) * 16, ShortTables.StoreIndex, ShortTables.StoreMask));
    }

    /// <summary>One vector picked out of the sources, pair by pair, with the indices and lanes of the slots from <paramref name="slot"/>.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static Vector512<float> Pick(in Sources v, int pairs, int slot, int[] index, float[] mask)
    {
        var picked = Avx512F.PermuteVar16x32x2(v[0], Vector512.LoadUnsafe(ref index[slot]), v[1]);
        for (int p = 1; p < pairs; p++)
        {
            slot += 16;
            var part = Avx512F.PermuteVar16x32x2(v[2 * p], Vector512.LoadUnsafe(ref index[slot]), v[2 * p + 1]);
            picked = Vector512.ConditionalSelect(Vector512.LoadUnsafe(ref mask[slot]), part, picked);
        }
        return picked;
    }

    /// <summary>Up to MaxShort source vectors and a zero one past the last (the odd height's second source).</summary>
    [InlineArray(MaxShort + 1)]
    private struct Sources
    {
        private Vector512<float> _v;
    }
}
