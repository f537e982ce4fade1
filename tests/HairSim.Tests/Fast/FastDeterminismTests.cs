using HairSim;

namespace HairSim.Tests.Fast;

/// <summary>
/// Strands are independent, so however the frame is cut into jobs and threads, the fast path must give the
/// same bits. (Each strand's arithmetic is the same whichever block or SIMD group it lands in: lanes never mix.)
/// </summary>
public class FastDeterminismTests
{
    [Theory]
    [InlineData("straight", 2)]
    [InlineData("straight", 3)]
    [InlineData("cut", 2)]
    [InlineData("bent", 3)]
    [InlineData("odd-lengths", 2)]
    [InlineData("pbd", 2)]
    [InlineData("all-colliders", 4)]
    [InlineData("rest", 2)]
    [InlineData("rest-cut", 3)]
    [InlineData("rest-odd-lengths", 2)]
    public void ParallelGivesTheSameBitsAsSequential(string scene, int threads)
    {
        var sequential = FastPathScenes.Build(scene, SolverPath.Fast);
        var parallel = FastPathScenes.Build(scene, SolverPath.Fast);
        using var dispatcher = new ParallelDispatcher(threads);
        var simS = new HairSimulation(sequential);
        var simP = new HairSimulation(parallel, dispatcher: dispatcher);
        for (int f = 1; f <= 20; f++)
        {
            simS.Step(1f / 60f, FastPathScenes.HeadAt(f));
            simP.Step(1f / 60f, FastPathScenes.HeadAt(f));
        }
        Assert.True(sequential.World.BitEquals(parallel.World));
        // And the hair did move (the comparison is not of two untouched worlds).
        Assert.False(FastPathScenes.Build(scene, SolverPath.Fast).World.BitEquals(parallel.World));
    }
}
