using HairSim.Fast;

namespace HairSim.Tests.Fast;

/// <summary>The length pass's transposes against their definition: tile[k·lanes + l] = strand l's particle k.</summary>
public class TransposeTests
{
    private const int Lanes = 32;

    private static float[] Strands()
    {
        var s = new float[16 * 16 + 16];
        for (int i = 0; i < s.Length; i++) s[i] = i * 1.5f - 7f;
        return s;
    }

    [Fact]
    public void In16MovesParticleKOfStrandLToRowKColumnL()
    {
        if (!Transpose.Available) { Assert.False(new FastLengthSystem(16).UsesWide); return; } // the scalar copy is used instead
        var s = Strands();
        var tile = new float[16 * Lanes];
        Transpose.In16(ref s[0], ref tile[16], Lanes);
        for (int l = 0; l < 16; l++)
            for (int k = 0; k < 16; k++)
                Assert.Equal(s[l * 16 + k], tile[k * Lanes + 16 + l]);
        Assert.All(Enumerable.Range(0, 16), k => Assert.Equal(0f, tile[k * Lanes])); // other columns untouched
    }

    [Fact]
    public void In16WideGivesTheTileOfIn16()
    {
        if (!FastPathInfo.Avx512) { Assert.False(new FastLengthSystem(16).UsesWide); return; } // only 32-lane tiles use it
        var s = Strands();
        var a = new float[16 * Lanes]; var b = new float[16 * Lanes];
        Transpose.In16(ref s[0], ref a[16], Lanes);
        Transpose.In16Wide(ref s[0], ref b[16], Lanes);
        Assert.Equal(a, b);
        Assert.Contains(a, v => v != 0f);
    }

    [Theory]
    [InlineData(false)]
    [InlineData(true)]
    public void Out16WideInvertsIn16WideAndAddsWhenAsked(bool add)
    {
        if (!FastPathInfo.Avx512) { Assert.False(new FastLengthSystem(16).UsesWide); return; } // only 32-lane tiles use it
        var s = Strands();
        var tile = new float[16 * Lanes];
        Transpose.In16Wide(ref s[0], ref tile[16], Lanes);
        var back = new float[16 * 16 + 16];
        for (int i = 0; i < back.Length; i++) back[i] = 100f + i;
        var before = (float[])back.Clone();
        Transpose.Out16Wide(ref tile[16], Lanes, ref back[0], add);
        for (int i = 0; i < 256; i++) Assert.Equal(add ? before[i] + s[i] : s[i], back[i]);
        for (int i = 256; i < back.Length; i++) Assert.Equal(before[i], back[i]); // nothing written past the 16 strands
    }

    // The non-finite values by their bits (NaN and −NaN would print alike, and the runner would skip one as a duplicate).
    [Theory]
    [InlineData(0x7FC00000u)] // NaN
    [InlineData(0x7F800000u)] // +∞
    [InlineData(0xFF800000u)] // −∞
    [InlineData(0xFFC00000u)] // −NaN
    [InlineData(0x7F800001u)] // a signalling NaN
    public void Out16WideProbedStoresAsOut16WideAndFindsANonFiniteValueWherever(uint badBits)
    {
        float bad = BitConverter.UInt32BitsToSingle(badBits);
        if (!FastPathInfo.Avx512) { Assert.False(new FastLengthSystem(16).UsesWide); return; } // only 32-lane tiles use it
        var s = Strands();
        // The finite extremes must not count: the largest and smallest magnitudes, both signs, zeros.
        s[3] = float.MaxValue; s[7] = -float.MaxValue; s[11] = float.Epsilon; s[13] = -0f; s[17] = -float.Epsilon;
        var tile = new float[16 * Lanes];
        Transpose.In16Wide(ref s[0], ref tile[16], Lanes);
        var expected = new float[256]; var probed = new float[256];
        Transpose.Out16Wide(ref tile[16], Lanes, ref expected[0], add: false);
        Assert.True(Simd.AllFinite(Transpose.Out16WideProbed(ref tile[16], Lanes, ref probed[0])));
        Assert.Equal(expected, probed);
        for (int k = 0; k < 16; k++)
            for (int l = 0; l < 16; l++)
            {
                var t = (float[])tile.Clone();
                t[k * Lanes + 16 + l] = bad;
                Assert.False(Simd.AllFinite(Transpose.Out16WideProbed(ref t[16], Lanes, ref probed[0])), $"row {k}, lane {l}");
            }
    }

    [Theory]
    [InlineData(2, 16)]
    [InlineData(3, 16)]
    [InlineData(3, 11)]
    [InlineData(12, 15)]
    public void StridedTransposesMoveShortStrandsAndWriteNothingPastThem(int stride, int whole)
    {
        if (!FastPathInfo.Avx512) return; // only strand chunks (AVX-512) use them
        // 16 strands of `stride` particles, then guard values that a store must not touch.
        var src = new float[16 * stride + 16];
        for (int i = 0; i < src.Length; i++) src[i] = i * 0.75f + 1f;
        var tile = new float[16 * Lanes];
        Transpose.In16Strided(ref src[0], stride, ref tile[0], Lanes);
        for (int l = 0; l < 16; l++)
            for (int k = 0; k < stride; k++)
                Assert.Equal(src[l * stride + k], tile[k * Lanes + l]);
        var dst = new float[src.Length];
        Array.Fill(dst, -1f);
        // Strands past `whole` are written element by element, so the guard past the 16th strand stays put.
        Transpose.Out16Strided(ref tile[0], Lanes, ref dst[0], stride, whole, stride);
        for (int i = 0; i < 16 * stride; i++) Assert.Equal(src[i], dst[i]);
        if (15 * stride + 16 > 16 * stride && whole < 16)
            for (int i = 16 * stride; i < dst.Length; i++) Assert.Equal(-1f, dst[i]);
    }

    [Theory]
    [InlineData(2)] [InlineData(3)] [InlineData(4)]
    public void ShortTransposesMoveParticleKOfStrandLToRowKColumnLAndBack(int h)
    {
        if (!Transpose.ShortAvailable) return; // AVX-512 only; chunks (their only user) need it too
        // 16 strands of h particles with a guard float on either side, which neither transpose may touch.
        var s = new float[16 * h + 2];
        for (int i = 0; i < s.Length; i++) s[i] = i * 1.25f - 3f;
        var tile = new float[(h + 1) * Lanes];
        Array.Fill(tile, -99f);
        Transpose.InShort(ref s[1], h, ref tile[16], Lanes);
        for (int l = 0; l < 16; l++)
            for (int k = 0; k < h; k++)
                Assert.Equal(s[1 + l * h + k], tile[k * Lanes + 16 + l]);
        for (int k = 0; k < h; k++)
            for (int l = 0; l < 16; l++) Assert.Equal(-99f, tile[k * Lanes + l]); // other columns untouched
        Assert.All(tile.AsSpan(h * Lanes).ToArray(), v => Assert.Equal(-99f, v)); // rows past the strands untouched

        var back = new float[16 * h + 2];
        back[0] = 42f; back[^1] = 43f;
        Transpose.OutShort(ref tile[16], Lanes, ref back[1], h);
        Assert.Equal(s.AsSpan(1, 16 * h).ToArray(), back.AsSpan(1, 16 * h).ToArray());
        Assert.Equal(42f, back[0]); Assert.Equal(43f, back[^1]);
    }
}
