using System.Runtime.Loader;
using HairSim;

namespace HairSheet.Logic;

/// <summary>
/// Every worker-thread dispatcher the hair nodes hold, so none outlives the assembly. The editor unloads the
/// project's assembly on every C# rebuild without calling the nodes' _ExitTree (godot #78513), and live worker
/// threads then make the unload fail ("Failed to unload assemblies"). The registry disposes them all when the
/// assembly's load context starts unloading; a node disposes its own when it leaves the tree.
/// </summary>
public static class DispatcherRegistry
{
    private static readonly List<IDisposableDispatcher> Live = new();
    private static bool _hooked;

    /// <summary>A dispatcher on every core, registered until <see cref="Release"/> or the unload.</summary>
    public static IDisposableDispatcher Create()
    {
        var d = ThreadDispatchers.CreateDefault();
        lock (Live)
        {
            if (!_hooked)
            {
                // The context this library was loaded into (Godot loads the project's assemblies into a collectible one).
                var context = AssemblyLoadContext.GetLoadContext(typeof(DispatcherRegistry).Assembly);
                if (context != null) context.Unloading += _ => ReleaseAll();
                _hooked = true;
            }
            Live.Add(d);
        }
        return d;
    }

    /// <summary>Disposes one dispatcher and forgets it.</summary>
    public static void Release(IDisposableDispatcher? d)
    {
        if (d == null) return;
        lock (Live) Live.Remove(d);
        d.Dispose();
    }

    /// <summary>Disposes every registered dispatcher (its worker threads are joined).</summary>
    public static void ReleaseAll()
    {
        IDisposableDispatcher[] all;
        lock (Live) { all = Live.ToArray(); Live.Clear(); }
        foreach (var d in all) d.Dispose();
    }

    /// <summary>Dispatchers alive now.</summary>
    public static int Count { get { lock (Live) return Live.Count; } }
}
