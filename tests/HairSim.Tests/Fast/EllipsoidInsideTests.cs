using System.Numerics;
using System.Runtime.Intrinsics;

namespace HairSim.Tests.Fast;

/// <summary>
/// The fast ellipsoid kernel decides a hit on the squared radius s (s &lt; 1), where it used to compare the root
/// √s &lt; 1, so its branch does not wait for the root. The two agree on every float: checked here exhaustively over
/// [1/4, 4), where the boundary lies (the rounded root is monotonic, so outside that range both tests are settled by
/// its ends), with the hardware's 16- and 8-lane roots the kernels use, and on the special values.
/// </summary>
public class EllipsoidInsideTests
{
    [Fact]
    public void TheSquaredRadiusDecidesAsTheRootDoesOnEveryFloatNearTheSurface()
    {
        int from = BitConverter.SingleToInt32Bits(0.25f), to = BitConverter.SingleToInt32Bits(4f);
        int disagree = 0, inside = 0;
        var lanes = new float[16];
        for (int bits = from; bits < to; bits += 16)
        {
            for (int l = 0; l < 16; l++) lanes[l] = BitConverter.Int32BitsToSingle(bits + l);
            var s = Vector512.Create(lanes);
            var byRoot = Vector512.LessThan(Vector512.Sqrt(s), Vector512<float>.One);
            var bySquare = Vector512.LessThan(s, Vector512<float>.One);
            if (byRoot.AsUInt32() != bySquare.AsUInt32()) disagree++; // masks as bits: set lanes are NaNs as floats
            var s8 = Vector256.Create(lanes.AsSpan(0, 8));
            if (Vector256.LessThan(Vector256.Sqrt(s8), Vector256<float>.One).AsUInt32() != Vector256.LessThan(s8, Vector256<float>.One).AsUInt32()) disagree++;
            inside += BitOperations.PopCount(bySquare.ExtractMostSignificantBits());
        }
        Assert.Equal(0, disagree);
        // The range really straddles the surface: the floats in [1/4, 1) are inside, the rest not.
        Assert.Equal(BitConverter.SingleToInt32Bits(1f) - from, inside);
        // The float just below 1 is inside by both tests (its root rounds below 1), and 1 itself by neither.
        float below = MathF.BitDecrement(1f);
        Assert.True(MathF.Sqrt(below) < 1f);
        Assert.False(MathF.Sqrt(1f) < 1f);
    }

    [Theory]
    [InlineData(0f)]
    [InlineData(float.Epsilon)]
    [InlineData(float.MaxValue)]
    [InlineData(float.PositiveInfinity)]
    [InlineData(float.NaN)]
    public void SpecialValuesDecideAsTheRootDoes(float s)
    {
        var v = Vector512.Create(s);
        Assert.Equal(Vector512.LessThan(Vector512.Sqrt(v), Vector512<float>.One).AsUInt32(), Vector512.LessThan(v, Vector512<float>.One).AsUInt32());
    }
}
