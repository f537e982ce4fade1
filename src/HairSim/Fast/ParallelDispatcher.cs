using System.Runtime.ExceptionServices;

namespace HairSim;

/// <summary>
/// A fork/join dispatcher with persistent worker threads (in the manner of bepuphysics2's ThreadDispatcher):
/// workers sleep on a semaphore, <see cref="Run"/> wakes them once, every thread (the caller included) takes jobs
/// from a shared counter, and the caller waits until all workers have checked in. Nothing is allocated per call.
/// Workers are background threads; <see cref="Dispose"/> wakes them to exit and joins them, so none outlive it
/// (Godot's editor reloads assemblies and must not find stray threads).
/// </summary>
public sealed class ParallelDispatcher : IDisposableDispatcher
{
    private readonly Thread[] _workers;
    private readonly SemaphoreSlim _start = new(0);
    // The caller waits for the workers on this monitor (allocated once; ManualResetEventSlim would allocate its
    // lock object the first time it has to block, i.e. inside some later step).
    private readonly object _doneGate = new();
    private readonly object _runLock = new();
    private Action<int>? _job;
    private int _jobCount;
    private int _nextJob;
    private int _pendingWorkers;
    private volatile bool _disposed;
    private ExceptionDispatchInfo? _failure;

    /// <param name="threadCount">Threads taking part, the calling thread included (1 … 256).</param>
    public ParallelDispatcher(int threadCount)
    {
        if (threadCount < 1 || threadCount > 256)
            throw new ArgumentOutOfRangeException(nameof(threadCount), threadCount, "Thread count must be in 1 … 256.");
        ThreadCount = threadCount;
        _workers = new Thread[threadCount - 1];
        for (int t = 0; t < _workers.Length; t++)
        {
            _workers[t] = new Thread(WorkerLoop) { IsBackground = true, Name = $"HairSim worker {t + 1}" };
            _workers[t].Start();
        }
    }

    public int ThreadCount { get; }

    /// <summary>The worker threads (for tests: after Dispose none is alive).</summary>
    public IReadOnlyList<Thread> Workers => _workers;

    public void Run(int jobCount, Action<int> job)
    {
        ArgumentNullException.ThrowIfNull(job);
        ObjectDisposedException.ThrowIf(_disposed, this);
        if (jobCount <= 0) return;
        if (_workers.Length == 0 || jobCount == 1)
        {
            for (int j = 0; j < jobCount; j++) job(j);
            return;
        }
        lock (_runLock)
        {
            _job = job;
            _jobCount = jobCount;
            _nextJob = -1;
            _failure = null;
            int helpers = Math.Min(_workers.Length, jobCount - 1);
            Volatile.Write(ref _pendingWorkers, helpers);
            _start.Release(helpers);
            Work();
            WaitForWorkers();
            _job = null;
            _failure?.Throw();
        }
    }

    private void Work()
    {
        var job = _job!;
        int count = _jobCount;
        try
        {
            for (int j = Interlocked.Increment(ref _nextJob); j < count; j = Interlocked.Increment(ref _nextJob)) job(j);
        }
        catch (Exception e)
        {
            // First failure wins; the others still finish their jobs so the join completes.
            Interlocked.CompareExchange(ref _failure, ExceptionDispatchInfo.Capture(e), null);
            Interlocked.Exchange(ref _nextJob, count);
        }
    }

    private void WaitForWorkers()
    {
        var spin = new SpinWait();
        for (int i = 0; i < 50 && Volatile.Read(ref _pendingWorkers) != 0; i++) spin.SpinOnce(sleep1Threshold: -1);
        if (Volatile.Read(ref _pendingWorkers) == 0) return;
        lock (_doneGate)
            while (Volatile.Read(ref _pendingWorkers) != 0) Monitor.Wait(_doneGate);
    }

    private void WorkerLoop()
    {
        while (true)
        {
            _start.Wait();
            if (_disposed) return;
            Work();
            if (Interlocked.Decrement(ref _pendingWorkers) == 0)
                lock (_doneGate) Monitor.PulseAll(_doneGate);
        }
    }

    public void Dispose()
    {
        if (_disposed) return;
        lock (_runLock)
        {
            _disposed = true;
            if (_workers.Length > 0) _start.Release(_workers.Length);
            foreach (var t in _workers) t.Join();
        }
        _start.Dispose();
    }
}
