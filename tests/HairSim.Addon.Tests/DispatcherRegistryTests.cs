using HairSheet.Logic;

namespace HairSheet.Addon.Tests;

/// <summary>
/// The hair nodes' worker threads must not outlive the assembly (Godot's editor unloads it on every C# rebuild
/// without calling _ExitTree): the registry disposes every dispatcher it handed out, as the unload hook does.
/// </summary>
[Collection("DispatcherRegistry")]
public class DispatcherRegistryTests
{
    [Fact]
    public void ReleaseAllDisposesEveryDispatcherHandedOut()
    {
        DispatcherRegistry.ReleaseAll();
        var a = DispatcherRegistry.Create();
        var b = DispatcherRegistry.Create();
        Assert.Equal(2, DispatcherRegistry.Count);
        int ran = 0;
        a.Run(4, _ => Interlocked.Increment(ref ran));
        Assert.Equal(4, ran);
        DispatcherRegistry.Release(b);
        Assert.Equal(1, DispatcherRegistry.Count);
        DispatcherRegistry.ReleaseAll();
        Assert.Equal(0, DispatcherRegistry.Count);
        // A parallel dispatcher refuses work once disposed (its workers are joined); the sequential one has none.
        if (a.ThreadCount > 1) Assert.Throws<ObjectDisposedException>(() => a.Run(2, _ => { }));
        if (b.ThreadCount > 1) Assert.Throws<ObjectDisposedException>(() => b.Run(2, _ => { }));
    }
}
