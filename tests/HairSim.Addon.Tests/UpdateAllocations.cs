namespace HairSheet.Addon.Tests;

/// <summary>
/// The bytes a run of updates allocates on the test thread, update by update. One-time set-up (a type or static first
/// used there, or not, depending on which test of the run got there first: 248 bytes, seen on the first update and,
/// rarely, on a later one) allocates in one update; a cost per update allocates in every one.
/// </summary>
internal struct UpdateAllocations
{
    private long _before;
    private int _updates, _allocating;
    private long _bytes;

    public void Begin() => _before = GC.GetAllocatedBytesForCurrentThread();

    public void End()
    {
        long bytes = GC.GetAllocatedBytesForCurrentThread() - _before;
        _updates++;
        if (bytes != 0) { _allocating++; _bytes += bytes; }
    }

    /// <summary>No update allocated but (at most) the one that ran the one-time set-up.</summary>
    public readonly void AssertNonePerUpdate() =>
        Assert.True(_allocating <= 1, $"{_allocating} of {_updates} updates allocated ({_bytes} bytes in all)");
}
