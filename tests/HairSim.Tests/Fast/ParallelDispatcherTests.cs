using HairSim;

namespace HairSim.Tests.Fast;

public class ParallelDispatcherTests
{
    [Theory]
    [InlineData(1, 1)]
    [InlineData(2, 1)]
    [InlineData(2, 7)]
    [InlineData(3, 1000)]
    [InlineData(4, 3)]
    public void RunsEveryJobExactlyOnce(int threads, int jobs)
    {
        using var d = new ParallelDispatcher(threads);
        var hits = new int[jobs];
        for (int round = 0; round < 20; round++)
        {
            Array.Clear(hits);
            d.Run(jobs, j => Interlocked.Increment(ref hits[j]));
            Assert.All(hits, h => Assert.Equal(1, h));
        }
        Assert.Equal(threads, d.ThreadCount);
    }

    [Fact]
    public void UsesMoreThanOneThreadWhenThereIsWork()
    {
        using var d = new ParallelDispatcher(2);
        var ids = new int[64];
        // Each job waits for the other thread to have started one, so a single thread could never finish.
        int started = 0;
        d.Run(2, j =>
        {
            Interlocked.Increment(ref started);
            var sw = System.Diagnostics.Stopwatch.StartNew();
            while (Volatile.Read(ref started) < 2 && sw.ElapsedMilliseconds < 5000) Thread.SpinWait(100);
            ids[j] = Environment.CurrentManagedThreadId;
        });
        Assert.Equal(2, started);
        Assert.NotEqual(ids[0], ids[1]);
    }

    [Fact]
    public void JobExceptionReachesTheCallerAndTheDispatcherStaysUsable()
    {
        using var d = new ParallelDispatcher(2);
        var e = Assert.Throws<InvalidOperationException>(() => d.Run(16, j => { if (j == 5) throw new InvalidOperationException("job 5"); }));
        Assert.Equal("job 5", e.Message);
        int count = 0;
        d.Run(16, _ => Interlocked.Increment(ref count));
        Assert.Equal(16, count);
    }

    [Fact]
    public void DisposeLeavesNoLiveThreads()
    {
        var d = new ParallelDispatcher(4);
        d.Run(100, _ => { });
        var workers = d.Workers.ToArray();
        Assert.Equal(3, workers.Length);
        Assert.All(workers, t => Assert.True(t.IsAlive && t.IsBackground));
        d.Dispose();
        Assert.All(workers, t => Assert.False(t.IsAlive));
        Assert.Throws<ObjectDisposedException>(() => d.Run(2, _ => { }));
        d.Dispose(); // twice is harmless
    }

    [Fact]
    public void DefaultDispatcherUsesEveryCoreAndDisposesCleanly()
    {
        var d = ThreadDispatchers.CreateDefault();
        Assert.Equal(Environment.ProcessorCount, d.ThreadCount);
        var p = Assert.IsType<ParallelDispatcher>(d);
        var workers = p.Workers.ToArray();
        d.Dispose();
        Assert.All(workers, t => Assert.False(t.IsAlive));
    }

    [Theory]
    [InlineData(0)]
    [InlineData(257)]
    public void RejectsAbsurdThreadCounts(int threads) =>
        Assert.Throws<ArgumentOutOfRangeException>(() => new ParallelDispatcher(threads));
}
