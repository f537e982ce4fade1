using System.Numerics;
using BenchmarkDotNet.Attributes;

namespace HairSim.Editing.Benchmarks;

/// <summary>
/// Editing on the reference scene (435 × 40 × 16), hair settled for half a second: a chin-height stroke across
/// the whole front view (every hanging strand crosses it), on one core.
/// </summary>
[MemoryDiagnoser]
public class CutBenchmarks
{
    private HairScene _scene = null!;
    private Stroke _stroke = null!;
    private StrandSelection _fringe = null!;
    private Stroke _curl = null!;
    private readonly CutOptions _all = new() { Reach = CutReach.AllThrough };
    private readonly CutOptions _visible = new() { Reach = CutReach.VisibleOnly };
    private readonly EditHistory _history = new();

    [GlobalSetup]
    public void Setup()
    {
        _scene = GroomBuilder.BuildScene(GroomSettings.Reference());
        var sim = new HairSimulation(_scene);
        for (int f = 0; f < 30; f++) sim.Step(1f / 60f);
        var front = StrokeCamera.LookAtOrthographic(new Vector3(0, -0.1f, 2f), new Vector3(0, -0.1f, 0), Vector3.UnitY, 0.7f, new Vector2(800, 800));
        front.Project(new Vector3(0, -0.1f, 0), out var chin, out _);
        _stroke = new Stroke([new Vector2(5, chin.Y), new Vector2(795, chin.Y)], front);
        var side = StrokeCamera.LookAtOrthographic(new Vector3(-2f, -0.05f, 0), new Vector3(0, -0.05f, 0), Vector3.UnitY, 0.5f, new Vector2(800, 800));
        side.Project(new Vector3(0, 0.075f, 0.055f), out var a, out _);
        side.Project(new Vector3(0, 0.02f, 0.12f), out var b, out _);
        _fringe = HairEditor.Select(_scene, side, SelectionArea.Rectangle(a, b), new SelectionOptions { RootsOnly = true });
        var pts = new List<Vector2>();
        for (int k = 0; k <= 120; k++)
        {
            float t = 3 * MathF.PI * k / 120;
            side.Project(new Vector3(0, 0.03f * MathF.Cos(t), 0.1f + 0.03f * MathF.Sin(t)), out var p, out _);
            pts.Add(p);
        }
        _curl = new Stroke(pts, side);
    }

    /// <summary>Finding every crossing (all layers): the grid search plus lifting each crossing to 3D.</summary>
    [Benchmark]
    public int PlanCutAllThrough() => HairEditor.Cut(_scene, _stroke, _all).Strands.Count;

    /// <summary>The same, with a ray cast against the head per crossing to keep only visible strands.</summary>
    [Benchmark]
    public int PlanCutVisibleOnly() => HairEditor.Cut(_scene, _stroke, _visible).Strands.Count;

    /// <summary>Plan, apply (with both undo snapshots) and undo: the world ends as it began.</summary>
    [Benchmark]
    public long CutApplyUndo()
    {
        _history.Do(HairEditor.Cut(_scene, _stroke, _all));
        long bytes = _history.MemoryBytes;
        _history.Undo();
        _history.Clear();
        return bytes;
    }

    /// <summary>Planning a fit of the fringe (≈1,000 strands) to a curl stroke.</summary>
    [Benchmark]
    public int PlanFitFringe() => HairEditor.Fit(_scene, _fringe, _curl).Strands.Count;
}
