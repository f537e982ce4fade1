using BenchmarkDotNet.Attributes;
using BenchmarkDotNet.Jobs;

namespace HairSim.Benchmarks;

/// <summary>
/// One whole frame (4 substeps, 60 Hz, shaking head) for the reference scene (17,400 strands) and the scaling
/// series, reference path vs fast path (1 thread and all cores) in the same run. Short job: few iterations, so
/// the suite finishes in minutes on 2 cores.
/// </summary>
[MemoryDiagnoser]
[SimpleJob(RuntimeMoniker.Net10_0, launchCount: 1, warmupCount: 3, iterationCount: 5)]
public class FrameBenchmarks
{
    [Params(1_000, 4_000, 17_400, 50_000, 100_000)]
    public int Strands;

    [Params("reference", "fast-1", "fast-all")]
    public string Solver = "fast-all";

    private HairSimulation _sim = null!;
    private IDisposableDispatcher? _dispatcher;
    private int _frame;

    [GlobalSetup]
    public void Setup()
    {
        var scene = BenchScenes.Build(Strands, Solver == "reference" ? SolverPath.Reference : SolverPath.Fast);
        _dispatcher = Solver == "fast-all" ? ThreadDispatchers.CreateDefault() : null;
        _sim = new HairSimulation(scene, dispatcher: _dispatcher);
        for (_frame = 0; _frame < 10; _frame++) _sim.Step(1f / 60f, BenchScenes.Shake((_frame + 1) / 60f));
    }

    [GlobalCleanup]
    public void Cleanup() => _dispatcher?.Dispose();

    [Benchmark]
    public void Frame()
    {
        _frame++;
        _sim.Step(1f / 60f, BenchScenes.Shake(_frame / 60f));
    }
}
