using HairSim;

namespace HairSim.Tests.Fast;

[CollectionDefinition(nameof(AllocationCollection), DisableParallelization = true)]
public class AllocationCollection { }

/// <summary>
/// A fast step allocates nothing once warm: measured on the calling thread for the sequential dispatcher and
/// process-wide (GC.GetTotalAllocatedBytes, precise) for the parallel one, whose workers are other threads.
/// Runs alone (no other test allocating at the same time).
/// </summary>
[Collection(nameof(AllocationCollection))]
public class FastAllocationTests
{
    [Theory]
    [InlineData("straight")]
    [InlineData("cut")]
    [InlineData("bent")]
    [InlineData("odd-lengths")]
    [InlineData("pbd")]
    [InlineData("all-colliders")]
    public void SequentialStepAllocatesNothing(string scene)
    {
        var s = FastPathScenes.Build(scene, SolverPath.Fast);
        var sim = new HairSimulation(s);
        for (int f = 1; f <= 40; f++) sim.Step(1f / 60f, FastPathScenes.HeadAt(f));
        long before = GC.GetAllocatedBytesForCurrentThread();
        for (int f = 41; f <= 60; f++) sim.Step(1f / 60f, FastPathScenes.HeadAt(f));
        Assert.Equal(0, GC.GetAllocatedBytesForCurrentThread() - before);
    }

    [Theory]
    [InlineData("straight")]
    [InlineData("cut")]
    [InlineData("bent")]
    public void ParallelStepAllocatesNothingOnAnyThread(string scene)
    {
        var s = FastPathScenes.Build(scene, SolverPath.Fast);
        using var dispatcher = new ParallelDispatcher(2);
        var sim = new HairSimulation(s, dispatcher: dispatcher);
        for (int f = 1; f <= 60; f++) sim.Step(1f / 60f, FastPathScenes.HeadAt(f));
        long best = long.MaxValue;
        // Background runtime work (tiered JIT) may allocate a little on its own; take the best of a few tries.
        for (int attempt = 0; attempt < 3 && best != 0; attempt++)
        {
            long before = GC.GetTotalAllocatedBytes(true);
            for (int f = 61; f <= 80; f++) sim.Step(1f / 60f, FastPathScenes.HeadAt(f));
            best = Math.Min(best, GC.GetTotalAllocatedBytes(true) - before);
        }
        Assert.True(best == 0, $"{best} bytes allocated over 20 frames");
    }
}
