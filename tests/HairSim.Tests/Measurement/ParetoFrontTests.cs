using CsCheck;
using HairSim.Measurement;

namespace HairSim.Tests.Measurement;

public class ParetoFrontTests
{
    [Fact]
    public void KeepsOnlyPointsNothingBeatsOnBothAxes()
    {
        double[] cost = [1, 2, 3, 4, 2.5, 5];
        double[] error = [10, 5, 6, 1, 5, 1];
        // 2 is beaten by 1 (cheaper, more accurate); 4 by 1 (cheaper, equal error); 5 by 3 (cheaper, equal error).
        Assert.Equal([0, 1, 3], ParetoFront.Indices(cost, error));
    }

    [Fact]
    public void LeavesOutNonFinitePointsAndKeepsTies()
    {
        double[] cost = [1, 1, double.NaN, 0.5];
        double[] error = [2, 2, 0.1, double.PositiveInfinity];
        Assert.Equal([0, 1], ParetoFront.Indices(cost, error));
    }

    [Fact]
    public void RejectsListsOfDifferentLength() =>
        Assert.Throws<ArgumentException>(() => ParetoFront.Indices([1.0], [1.0, 2.0]));

    [Fact]
    public void FrontIsNonDominatedAndDominatesEverythingElse()
    {
        Gen.Double[0, 10].Array[1, 40].Select(Gen.Double[0, 10].Array[40, 40]).Sample(t =>
        {
            var (cost, more) = t;
            var error = more[..cost.Length];
            var front = ParetoFront.Indices(cost, error);
            bool Dominates(int j, int i) => cost[j] <= cost[i] && error[j] <= error[i] && (cost[j] < cost[i] || error[j] < error[i]);
            for (int i = 0; i < cost.Length; i++)
            {
                bool dominated = false;
                for (int j = 0; j < cost.Length; j++) dominated |= Dominates(j, i);
                if (Array.IndexOf(front, i) >= 0 == dominated) return false;
            }
            for (int k = 1; k < front.Length; k++) if (cost[front[k]] < cost[front[k - 1]]) return false;
            return true;
        }, iter: 500);
    }
}
