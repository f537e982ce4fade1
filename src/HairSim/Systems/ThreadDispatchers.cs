namespace HairSim;

/// <summary>Where the default dispatcher comes from (the optimised path supplies a parallel one).</summary>
public static partial class ThreadDispatchers
{
    /// <summary>A dispatcher using every core; the caller disposes it (no threads outlive it).</summary>
    public static IDisposableDispatcher CreateDefault()
    {
        IDisposableDispatcher? d = null;
        CreateParallel(ref d);
        return d ?? new DisposableSequential();
    }

    static partial void CreateParallel(ref IDisposableDispatcher? dispatcher);

    private sealed class DisposableSequential : IDisposableDispatcher
    {
        public int ThreadCount => 1;
        public void Run(int jobCount, Action<int> job) => SequentialDispatcher.Instance.Run(jobCount, job);
        public void Dispose() { }
    }
}

public interface IDisposableDispatcher : IThreadDispatcher, IDisposable { }
