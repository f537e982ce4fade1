using BenchmarkDotNet.Attributes;
using BenchmarkDotNet.Jobs;

namespace HairSim.Benchmarks;

/// <summary>
/// One system alone (a pipeline holding only it) for one frame of 4 substeps on the reference scene, reference
/// vs fast path. The state is a warm one (1 s of shaking) and is restored before each iteration's invocations
/// only, so a run measures the system on a realistic, slowly evolving state.
/// </summary>
[MemoryDiagnoser]
[SimpleJob(RuntimeMoniker.Net10_0, launchCount: 1, warmupCount: 3, iterationCount: 5)]
public class SystemBenchmarks
{
    [Params("HeadFollow", "ShapeMatch", "Integrate", "Length", "Collide")]
    public string Pass = "ShapeMatch";

    [Params("reference", "fast-1", "fast-all")]
    public string Solver = "fast-1";

    private HairScene _scene = null!;
    private HairWorld _warm = null!;
    private HairPipeline _pipeline = null!;
    private IDisposableDispatcher? _dispatcher;
    private RigidTransform _head;

    [GlobalSetup]
    public void Setup()
    {
        _scene = BenchScenes.Build(17_400, Solver == "reference" ? SolverPath.Reference : SolverPath.Fast);
        _dispatcher = Solver == "fast-all" ? ThreadDispatchers.CreateDefault() : null;
        var sim = new HairSimulation(_scene, dispatcher: _dispatcher);
        for (int f = 0; f < 60; f++) sim.Step(1f / 60f, BenchScenes.Shake((f + 1) / 60f));
        _warm = _scene.World.Clone();
        var only = new PipelineBuilder();
        foreach (var factory in PipelineBuilder.CreateDefault().Factories) if (factory.Name == Pass) only.Add(factory);
        _pipeline = only.Build(_scene, _dispatcher);
        _head = BenchScenes.Shake(61 / 60f);
    }

    [IterationSetup]
    public void Restore() => _warm.CopyTo(_scene.World);

    [GlobalCleanup]
    public void Cleanup() => _dispatcher?.Dispose();

    [Benchmark]
    public void OneFrame() => _pipeline.Step(1f / 60f, _head);
}
