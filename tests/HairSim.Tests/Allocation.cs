namespace HairSim.Tests;

/// <summary>What the calling thread allocates while stepping, for the "allocates nothing per step" tests.</summary>
internal static class Allocation
{
    /// <summary>
    /// Bytes the calling thread allocates over <paramref name="frames"/> calls of <paramref name="step"/> (frame numbers
    /// from <paramref name="first"/>), the lesser of two such windows back to back: an allocation in every step shows in
    /// both, a one-time allocation of the runtime's (a type loaded or a method compiled again on a path's first use, which
    /// a loaded machine can push past the warm-up) in at most one.
    /// </summary>
    public static long InQuieterWindow(Action<int> step, int first, int frames)
    {
        long a0 = GC.GetAllocatedBytesForCurrentThread();
        for (int f = first; f < first + frames; f++) step(f);
        long a1 = GC.GetAllocatedBytesForCurrentThread();
        for (int f = first + frames; f < first + 2 * frames; f++) step(f);
        long a2 = GC.GetAllocatedBytesForCurrentThread();
        return Math.Min(a1 - a0, a2 - a1);
    }
}
