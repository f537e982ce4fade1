using System.Numerics;
using System.Runtime.Intrinsics;
using HairSim.Fast;

namespace HairSim.Tests.Fast;

/// <summary>
/// The speed checks' shortcut (Simd.AllWithin under Simd.SpeedBound): a velocity it passes can never be over the limit
/// by the exact test (both of the exact test's forms: the integration's sum of squares and the kick's fused one), so
/// skipping the squares leaves the bits of the exact test. NaN is never passed.
/// </summary>
public class SpeedBoundTests
{
    public static TheoryData<float> Limits() => new() { 1e-3f, 0.3f, 1f, 25f, 1e6f, 3e18f };

    /// <summary>The largest float the bound passes, and the next one up.</summary>
    private static (float Within, float Past) Edge(float maxSpeed)
    {
        uint probe = Simd.SpeedBound(maxSpeed);
        float within = BitConverter.UInt32BitsToSingle(probe >> 1);
        return (within, MathF.BitIncrement(within));
    }

    [Theory]
    [MemberData(nameof(Limits))]
    public void NoVelocityWithinTheBoundIsOverTheLimit(float maxSpeed)
    {
        float limitSq = maxSpeed * maxSpeed;
        var (within, past) = Edge(maxSpeed);
        // The worst case: every component at the bound, of either sign.
        foreach (var (x, y, z) in new[] { (within, within, within), (-within, within, -within), (within, 0f, -within) })
        {
            Assert.True(Passes(x, y, z, maxSpeed));
            float sum = x * x + y * y + z * z;
            float fused = MathF.FusedMultiplyAdd(z, z, MathF.FusedMultiplyAdd(y, y, x * x));
            Assert.False(sum > limitSq, $"sum of squares {sum} over {limitSq}");
            Assert.False(fused > limitSq, $"fused sum of squares {fused} over {limitSq}");
        }
        // One component past the bound in one lane: the exact test is taken.
        Assert.False(Passes(within, past, 0f, maxSpeed));
        Assert.False(Passes(0f, 0f, -past, maxSpeed));
        // The bound is not so low that ordinary speeds take the exact test: half the limit along an axis passes.
        Assert.True(Passes(0.5f * maxSpeed, 0f, 0f, maxSpeed));
    }

    [Fact]
    public void NaNIsNeverWithinAndInfinityOnlyWithoutALimit()
    {
        Assert.False(Passes(float.NaN, 0f, 0f, 25f));
        Assert.False(Passes(0f, 0f, float.NaN, float.PositiveInfinity));
        Assert.False(Passes(float.PositiveInfinity, 0f, 0f, 25f));
        // No limit (+∞): every finite or infinite velocity passes, as the exact test never finds one over +∞.
        Assert.True(Passes(float.MaxValue, -float.MaxValue, float.NegativeInfinity, float.PositiveInfinity));
    }

    /// <summary>The 8-lane and (where there is AVX-512) 16-lane forms, with the velocity in one lane and zeros elsewhere; they must agree.</summary>
    private static bool Passes(float x, float y, float z, float maxSpeed)
    {
        uint bound = Simd.SpeedBound(maxSpeed);
        int lane = Vector<float>.Count - 1;
        var narrow = Simd.AllWithin(InLane(x, lane), InLane(y, lane), InLane(z, lane), new Vector<uint>(bound));
        if (Vector512.IsHardwareAccelerated)
        {
            var wide = Simd.AllWithin(Vector512<float>.Zero.WithElement(9, x), Vector512<float>.Zero.WithElement(9, y),
                Vector512<float>.Zero.WithElement(9, z), Vector512.Create(bound));
            Assert.Equal(narrow, wide);
        }
        return narrow;
    }

    private static Vector<float> InLane(float v, int lane)
    {
        var a = new float[Vector<float>.Count];
        a[lane] = v;
        return new Vector<float>(a);
    }
}
