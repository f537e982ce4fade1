using System.Numerics;
using System.Runtime.Intrinsics;
using System.Runtime.Intrinsics.X86;
using HairSim.Fast;

namespace HairSim.Tests.Fast;

/// <summary>
/// Shape matching's reciprocal root (Simd.InvSqrt14 and its 16-lane twin): the two widths give the same bits in every
/// lane (the 8- and 16-lane paths are tested bit for bit against each other on top of this), and both stay within a few
/// ulps of the exact 1/√x over the range hair lengths take, as accurate as the AVX-estimate form it replaced.
/// </summary>
public class InvSqrtTests
{
    private static float[] Samples()
    {
        // Squared triple spans from 10 µm to 100 m, log-spaced with jitter, and the ends of that range.
        var rng = new Random(7);
        var xs = new float[4096];
        for (int i = 0; i < xs.Length; i++) xs[i] = MathF.Pow(10f, -10f + 14f * (float)rng.NextDouble());
        xs[0] = 1e-10f; xs[1] = 1f; xs[2] = 1e4f; xs[3] = MathF.BitIncrement(1f);
        return xs;
    }

    [Fact]
    public void TheEightAndSixteenLaneFormsGiveTheSameBits()
    {
        if (!Vector512.IsHardwareAccelerated || !Avx512F.IsSupported || Vector<float>.Count != 8) return; // the 16-lane form needs AVX-512
        var xs = Samples();
        for (int i = 0; i < xs.Length; i += 16)
        {
            var wide = Simd.InvSqrt14x16(Vector512.Create(xs.AsSpan(i, 16)));
            for (int h = 0; h < 16; h += 8)
            {
                var narrow = Simd.InvSqrt14(new Vector<float>(xs.AsSpan(i + h, 8)));
                for (int l = 0; l < 8; l++)
                    Assert.Equal(BitConverter.SingleToInt32Bits(wide.GetElement(h + l)), BitConverter.SingleToInt32Bits(narrow[l]));
            }
        }
    }

    [Fact]
    public void BothFormsStayWithinAFewUlpsOfTheExactRoot()
    {
        var xs = Samples();
        double worst = 0, worstAvx = 0;
        for (int i = 0; i < xs.Length; i += Vector<float>.Count)
        {
            var v = new Vector<float>(xs.AsSpan(i, Vector<float>.Count));
            var y = Simd.InvSqrt14(v); var yAvx = Simd.InvSqrt(v);
            for (int l = 0; l < Vector<float>.Count; l++)
            {
                double exact = 1.0 / Math.Sqrt(xs[i + l]);
                worst = Math.Max(worst, Math.Abs(y[l] - exact) / exact);
                worstAvx = Math.Max(worstAvx, Math.Abs(yAvx[l] - exact) / exact);
            }
        }
        // 2⁻²³ ≈ 1.19e-7 is an ulp near 1: within 3 ulps, and no worse than the AVX estimate's form.
        Assert.True(worst < 3.6e-7, $"worst relative error {worst:E3}");
        Assert.True(worst <= worstAvx, $"worst relative error {worst:E3} against {worstAvx:E3} with the AVX estimate");
    }
}
