using HairSim;

namespace HairSim.Tests.Fast;

[CollectionDefinition(nameof(AllocationCollection), DisableParallelization = true)]
public class AllocationCollection { }

/// <summary>
/// A fast step allocates nothing once warm: measured on the calling thread for the sequential dispatcher, and on
/// every thread of the parallel dispatcher (the caller and its workers) for the parallel one. (Process-wide
/// counts, GC.GetTotalAllocatedBytes, also see the test runner's own threads, so they are not used here.)
/// </summary>
[Collection(nameof(AllocationCollection))]
public class FastAllocationTests
{
    /// <summary>Hair volume once per frame, or with frames stepped in parts (MaxStep 1/32: four per 60 Hz frame here).</summary>
    private static void AddVolume(HairScene s, string? volume)
    {
        if (volume == "volume") s.SetComponent(new VolumeSettings());
        else if (volume == "volume in parts") s.SetComponent(new VolumeSettings { MaxStep = 1f / 32 });
    }

    [Theory]
    [InlineData("straight")]
    [InlineData("cut")]
    [InlineData("bent")]
    [InlineData("odd-lengths")]
    [InlineData("pbd")]
    [InlineData("all-colliders")]
    [InlineData("cut", true)]
    [InlineData("rest")]
    [InlineData("rest-cut")]
    [InlineData("rest-odd-lengths")]
    [InlineData("rest-planes")]
    [InlineData("rest", false, "volume")]
    [InlineData("rest-cut", false, "volume")]
    [InlineData("rest", false, "volume in parts")]
    public void SequentialStepAllocatesNothing(string scene, bool render = false, string? volume = null)
    {
        var s = FastPathScenes.Build(scene, SolverPath.Fast);
        if (render) s.Render = new RenderSettings { StrandsPerGap = 2 };
        AddVolume(s, volume);
        var sim = new HairSimulation(s);
        for (int f = 1; f <= 40; f++) sim.Step(1f / 60f, FastPathScenes.HeadAt(f));
        Action<int> step = f => sim.Step(1f / 60f, FastPathScenes.HeadAt(f));
        Assert.Equal(0, Allocation.InQuieterWindow(step, 41, 20));
    }

    [Theory]
    [InlineData("straight")]
    [InlineData("cut")]
    [InlineData("rest")]
    [InlineData("rest-cut")]
    [InlineData("all-colliders")]
    public void TheReferencePathAllocatesNothingPerStepEither(string scene)
    {
        // The reference path is the oracle, not what a game runs; still, a frame of it allocates nothing once it runs
        // (the bench counts every thread's allocations, the runtime's one-time ones included, over a short warm-up).
        var s = FastPathScenes.Build(scene, SolverPath.Reference);
        var sim = new HairSimulation(s);
        for (int f = 1; f <= 10; f++) sim.Step(1f / 60f, FastPathScenes.HeadAt(f));
        Action<int> step = f => sim.Step(1f / 60f, FastPathScenes.HeadAt(f));
        Assert.Equal(0, Allocation.InQuieterWindow(step, 11, 5));
    }

    [Theory]
    [InlineData("straight", false)]
    [InlineData("cut", false)]
    [InlineData("bent", false)]
    [InlineData("cut", true)]
    [InlineData("rest", false)]
    [InlineData("rest-bent", true)]
    [InlineData("rest", false, "volume")]
    [InlineData("rest-cut", true, "volume in parts")]
    public void ParallelStepAllocatesNothingOnAnyThread(string scene, bool render, string? volume = null)
    {
        var s = FastPathScenes.Build(scene, SolverPath.Fast);
        if (render) s.Render = new RenderSettings { StrandsPerGap = 2 }; // render interpolation at each frame's end
        AddVolume(s, volume);
        const int threads = 2;
        using var dispatcher = new ParallelDispatcher(threads);
        var sim = new HairSimulation(s, dispatcher: dispatcher);
        for (int f = 1; f <= 60; f++) sim.Step(1f / 60f, FastPathScenes.HeadAt(f));
        var probe = new PerThreadAllocations(threads);
        var before = new long[threads];
        var ids = new int[threads];
        probe.Take(dispatcher);
        // Copies into arrays allocated beforehand: the caller thread allocates nothing between the two readings.
        Array.Copy(probe.Bytes, before, threads);
        Array.Copy(probe.ThreadIds, ids, threads);
        for (int f = 61; f <= 80; f++) sim.Step(1f / 60f, FastPathScenes.HeadAt(f));
        probe.Take(dispatcher);
        Assert.Equal(threads, ids.Distinct().Count());
        for (int t = 0; t < threads; t++)
        {
            int j = Array.IndexOf(probe.ThreadIds, ids[t]);
            Assert.True(j >= 0, "the same threads took part");
            Assert.True(probe.Bytes[j] - before[t] == 0, $"thread {ids[t]} (caller {Environment.CurrentManagedThreadId}) allocated {probe.Bytes[j] - before[t]} bytes over 20 frames");
        }
    }

    /// <summary>
    /// Reads GC.GetAllocatedBytesForCurrentThread on every thread of a dispatcher: one job per thread, each job
    /// waiting until all have started, so no thread can take two. Reading allocates nothing.
    /// </summary>
    private sealed class PerThreadAllocations
    {
        public readonly long[] Bytes;
        public readonly int[] ThreadIds;
        private readonly Action<int> _job;
        private int _started;

        public PerThreadAllocations(int threads)
        {
            Bytes = new long[threads];
            ThreadIds = new int[threads];
            _job = Read;
        }

        public void Take(IThreadDispatcher d)
        {
            _started = 0;
            d.Run(Bytes.Length, _job);
        }

        private void Read(int j)
        {
            Interlocked.Increment(ref _started);
            long deadline = Environment.TickCount64 + 5000;
            while (Volatile.Read(ref _started) < Bytes.Length && Environment.TickCount64 < deadline) Thread.SpinWait(50);
            ThreadIds[j] = Environment.CurrentManagedThreadId;
            Bytes[j] = GC.GetAllocatedBytesForCurrentThread();
        }
    }
}
