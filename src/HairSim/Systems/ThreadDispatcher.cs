namespace HairSim;

/// <summary>Runs jobCount jobs, possibly in parallel, and returns when all are done (one fork/join).</summary>
public interface IThreadDispatcher
{
    int ThreadCount { get; }
    void Run(int jobCount, Action<int> job);
}

/// <summary>Runs jobs one after another on the calling thread.</summary>
public sealed class SequentialDispatcher : IThreadDispatcher
{
    public static readonly SequentialDispatcher Instance = new();
    public int ThreadCount => 1;
    public void Run(int jobCount, Action<int> job)
    {
        for (int j = 0; j < jobCount; j++) job(j);
    }
}
