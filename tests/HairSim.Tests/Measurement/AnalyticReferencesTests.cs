using System.Numerics;
using HairSim.Measurement;

namespace HairSim.Tests.Measurement;

public class AnalyticReferencesTests
{
    [Theory]
    [InlineData(0.25, 0.2)]
    [InlineData(1.0, 0.1)]
    [InlineData(1.0, 0.999)]
    public void CatenaryParameterGivesTheChainLength(double length, double span)
    {
        double a = AnalyticReferences.CatenaryParameter(length, span);
        Assert.Equal(length, 2 * a * Math.Sinh(span / (2 * a)), 9);
    }

    [Fact]
    public void CatenaryRejectsAChainShorterThanItsSpan()
    {
        Assert.Throws<ArgumentOutOfRangeException>(() => AnalyticReferences.CatenaryParameter(0.1, 0.2));
        Assert.Throws<ArgumentOutOfRangeException>(() => AnalyticReferences.DiscreteCatenary(15, 0.1, 0.2));
    }

    [Fact]
    public void DiscreteCatenaryHasEqualLinksBetweenThePins()
    {
        var p = AnalyticReferences.DiscreteCatenary(15, 0.25, 0.2);
        Assert.Equal(16, p.Length);
        Assert.Equal(new Vector3(-0.1f, 0f, 0f), p[0]);
        Assert.Equal(new Vector3(0.1f, 0f, 0f), p[^1]);
        for (int j = 1; j < p.Length; j++) Assert.Equal(0.25 / 15, Vector3.Distance(p[j], p[j - 1]), 5);
    }

    [Fact]
    public void DiscreteCatenaryIsInForceBalance()
    {
        // Equal weights at the joints and constant horizontal tension: consecutive link slopes differ by the same amount.
        var p = AnalyticReferences.DiscreteCatenary(15, 0.25, 0.2);
        double Slope(int j) => (p[j + 1].Y - p[j].Y) / (double)(p[j + 1].X - p[j].X);
        double step = Slope(1) - Slope(0);
        Assert.True(step > 0);
        for (int j = 1; j < 14; j++) Assert.Equal(step, Slope(j + 1) - Slope(j), 3);
        Assert.Equal(-Slope(0), Slope(14), 4); // symmetric
    }

    [Fact]
    public void DiscreteCatenaryConvergesToTheContinuousOne()
    {
        double length = 0.25, span = 0.2, a = AnalyticReferences.CatenaryParameter(length, span);
        double Deviation(int links)
        {
            double worst = 0;
            foreach (var q in AnalyticReferences.DiscreteCatenary(links, length, span))
                worst = Math.Max(worst, Math.Abs(q.Y - AnalyticReferences.CatenaryHeight(a, span, q.X)));
            return worst;
        }
        double d16 = Deviation(16), d64 = Deviation(64), d256 = Deviation(256);
        Assert.True(d64 < d16 / 4 && d256 < d64 / 4, $"deviation {d16}, {d64}, {d256} does not fall like 1/N");
        Assert.True(d256 < 1e-4 * length);
    }

    [Fact]
    public void PendulumPeriodReducesToTheSmallAngleFormula()
    {
        Assert.Equal(2 * Math.PI * Math.Sqrt(0.25 / 9.81), AnalyticReferences.PendulumPeriod(0.25, 9.81, 0, 0), 12);
        // Larger swings and damping both lengthen the period.
        double t0 = AnalyticReferences.PendulumPeriod(0.25, 9.81, 0, 0);
        Assert.True(AnalyticReferences.PendulumPeriod(0.25, 9.81, 0.3, 0) > t0);
        Assert.True(AnalyticReferences.PendulumPeriod(0.25, 9.81, 0, 2) > t0);
        double w0 = Math.Sqrt(9.81 / 0.25);
        Assert.Throws<ArgumentOutOfRangeException>(() => AnalyticReferences.PendulumPeriod(0.25, 9.81, 0, 2.01 * w0));
    }

    [Fact]
    public void PendulumEnergyDecaysAtTheDampingRate() =>
        Assert.Equal(Math.Exp(-3.0), AnalyticReferences.PendulumEnergyRatio(2, 1.5), 12);
}
