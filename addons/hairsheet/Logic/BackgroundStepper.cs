using System.Diagnostics;
using System.Runtime.ExceptionServices;
using HairSim;

namespace HairSheet.Logic;

/// <summary>
/// Steps a simulation on a worker thread while the caller's frame goes on (the engine renders), one frame of
/// latency: each physics frame the node waits for the previous step, draws its render output (the renderer copies
/// it into its own buffers), and starts the next. So the render data is double-buffered by the renderer's copy, and
/// the hair's cost leaves the main thread. One dedicated thread and two semaphores: nothing is allocated per frame.
/// The scene must not be touched (edits, reads) between <see cref="Start"/> and <see cref="Wait"/>.
/// </summary>
public sealed class BackgroundStepper : IDisposable
{
    private readonly HairSimulation _simulation;
    private readonly Thread _thread;
    private readonly SemaphoreSlim _go = new(0), _done = new(0);
    private readonly Stopwatch _timer = new();
    private float _dt;
    private int _steps;
    private RigidTransform _head;
    private bool _running, _disposed, _quit;
    private Exception? _error;

    public BackgroundStepper(HairSimulation simulation)
    {
        _simulation = simulation ?? throw new ArgumentNullException(nameof(simulation));
        _thread = new Thread(Loop) { IsBackground = true, Name = "HairSheet background step" };
        _thread.Start();
    }

    /// <summary>A step is under way (started and not yet waited for).</summary>
    public bool Running => _running;

    /// <summary>Wall time the worker spent on the last finished step, in milliseconds.</summary>
    public double LastStepMilliseconds { get; private set; }

    /// <summary>Bytes the worker thread allocated during the last finished step (0 once the scene runs; helper threads of a parallel dispatcher are not counted).</summary>
    public long LastStepAllocatedBytes { get; private set; }

    /// <summary>Starts <paramref name="steps"/> steps of <paramref name="dt"/> toward <paramref name="head"/> on the worker.</summary>
    public void Start(float dt, int steps, RigidTransform head)
    {
        ObjectDisposedException.ThrowIf(_disposed, this);
        if (_running) throw new InvalidOperationException("A background step is already running: Wait for it first.");
        if (steps < 0) throw new ArgumentOutOfRangeException(nameof(steps), steps, "Steps must be zero or more.");
        _dt = dt; _steps = steps; _head = head;
        _running = true;
        _go.Release();
    }

    /// <summary>Waits for the step under way, if any; an exception the step threw is rethrown here, once.</summary>
    public void Wait()
    {
        if (!_running) return;
        _done.Wait();
        _running = false;
        var e = _error;
        _error = null;
        if (e != null) ExceptionDispatchInfo.Capture(e).Throw();
    }

    private void Loop()
    {
        while (true)
        {
            _go.Wait();
            if (_quit) return;
            _timer.Restart();
            long allocated = GC.GetAllocatedBytesForCurrentThread();
            try
            {
                for (int i = 0; i < _steps; i++) _simulation.Step(_dt, _head);
            }
            catch (Exception e)
            {
                _error = e;
            }
            LastStepMilliseconds = _timer.Elapsed.TotalMilliseconds;
            LastStepAllocatedBytes = GC.GetAllocatedBytesForCurrentThread() - allocated;
            _done.Release();
        }
    }

    /// <summary>Waits for the step under way (its exception is dropped) and joins the worker.</summary>
    public void Dispose()
    {
        if (_disposed) return;
        if (_running) { _done.Wait(); _running = false; _error = null; }
        _disposed = true;
        _quit = true;
        _go.Release();
        _thread.Join();
        _go.Dispose(); _done.Dispose();
    }
}
