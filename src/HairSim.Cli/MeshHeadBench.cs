using System.Diagnostics;
using System.Globalization;
using HairSim;
using HairSim.Meshes;

namespace HairSim.Cli;

/// <summary>
/// Bench rows for mesh heads (docs/meshes.md): the reference groom (435 × 40 × 16) grown on the project's head
/// (<see cref="ProceduralHead"/>, 2.5 mm field) against the same groom on the ellipsoid head, both on the fast path
/// with a shaking head, stepped in alternating blocks of 10 frames in one process so drift on a shared machine hits
/// both alike. The ratio of the medians is the issue's figure: at most 1.5.
/// </summary>
internal static class MeshHeadBench
{
    public const string MeshScene = "reference groom, mesh head", EllipsoidScene = "reference groom, ellipsoid head";
    private static readonly CultureInfo Inv = CultureInfo.InvariantCulture;

    /// <summary>(mesh, ellipsoid) rows on 1 thread and, when given, on the parallel dispatcher.</summary>
    public static List<(BenchCommand.Row Mesh, BenchCommand.Row Ellipsoid)> Pairs(IThreadDispatcher? parallel, int threads, int warmup, int frames)
    {
        var mesh = ProceduralHead.Create();
        var field = SignedDistanceField.Bake(mesh, 0.0025f);
        var groom = GroomSettings.Reference();
        var g = new MeshGroomSettings
        {
            SheetCount = groom.SheetCount, StrandsPerSheet = groom.StrandsPerSheet, ParticlesPerStrand = groom.ParticlesPerStrand,
            StrandLength = groom.StrandLength, ScalpMaskThreshold = 0.5f,
        };
        var pairs = new List<(BenchCommand.Row, BenchCommand.Row)>();
        foreach (var (dispatcher, n) in parallel != null ? new[] { ((IThreadDispatcher)SequentialDispatcher.Instance, 1), (parallel, threads) } : [(SequentialDispatcher.Instance, 1)])
        {
            var meshScene = MeshScalp.BuildScene(mesh, field, g, new SimulationSettings { Path = SolverPath.Fast });
            var ellipsoidScene = GroomBuilder.BuildScene(groom, new SimulationSettings { Path = SolverPath.Fast });
            // Four times the rows' frames (24 blocks of each head at the default 60): a ratio of two medians on a shared
            // machine needs more blocks than one row's median, or one disturbed block moves it by a few per cent.
            var pair = Interleaved(meshScene, ellipsoidScene, dispatcher, n, warmup, 4 * frames);
            pairs.Add(pair);
            Console.Error.WriteLine(string.Create(Inv,
                $"{"mesh head",-22} fast ×{n,-15} {pair.Mesh.MedianMs,9:F3} ms/frame (ellipsoid head, interleaved: {pair.Ellipsoid.MedianMs:F3}; {pair.Mesh.MedianMs / pair.Ellipsoid.MedianMs:F2}×)"));
        }
        return pairs;
    }

    private static (BenchCommand.Row Mesh, BenchCommand.Row Ellipsoid) Interleaved(HairScene meshScene, HairScene ellipsoidScene,
        IThreadDispatcher dispatcher, int threads, int warmup, int frames)
    {
        var sims = new[] { new HairSimulation(meshScene, dispatcher: dispatcher), new HairSimulation(ellipsoidScene, dispatcher: dispatcher) };
        float dt = 1f / 60f;
        var f = new int[2];
        void Step(int k) { f[k]++; sims[k].Step(dt, HairSim.Measurement.HeadMotion.Shake(f[k] * dt)); }
        // Warm-up: at least `warmup` frames each and 1.5 s, so the JIT's optimised tier is what gets timed.
        var warm = Stopwatch.StartNew();
        for (int i = 0; i < warmup || warm.Elapsed.TotalSeconds < 1.5; i++) { Step(0); Step(1); }
        const int Block = 10;
        int blocks = Math.Max(1, (frames + Block - 1) / Block);
        var times = new[] { new double[blocks * Block], new double[blocks * Block] };
        var sw = new Stopwatch();
        long bytes = GC.GetTotalAllocatedBytes(true); // over both simulations (each row shows the total)
        for (int b = 0; b < blocks; b++)
            for (int k = 0; k < 2; k++)
                for (int i = 0; i < Block; i++)
                {
                    sw.Restart();
                    Step(k);
                    times[k][b * Block + i] = sw.Elapsed.TotalMilliseconds;
                }
        bytes = GC.GetTotalAllocatedBytes(true) - bytes;
        foreach (var s in new[] { meshScene, ellipsoidScene })
            if (s.World.CountNonFinite() != 0) throw new InvalidDataException("The mesh-head bench produced non-finite values.");
        if (!sims[0].Pipeline.UsesStrandChunks && HairSim.Fast.FastPathInfo.Avx512)
            throw new InvalidOperationException("The mesh head left the strand-chunk path.");
        var mesh = BenchCommand.Summarise(MeshScene, "frame", SolverPath.Fast, threads, meshScene, times[0], bytes, times[0].Length);
        var ellipsoid = BenchCommand.Summarise(EllipsoidScene, "frame", SolverPath.Fast, threads, ellipsoidScene, times[1], bytes, times[1].Length);
        return (mesh, ellipsoid);
    }

    /// <summary>The doc's sentences for the pairs: the ratio against the issue's target.</summary>
    public static IEnumerable<string> Lines(List<(BenchCommand.Row Mesh, BenchCommand.Row Ellipsoid)> pairs)
    {
        foreach (var (m, e) in pairs)
            yield return string.Create(Inv,
                $"Mesh head vs ellipsoid head, reference groom, {m.Threads} thread{(m.Threads == 1 ? "" : "s")}, interleaved in one run (blocks of 10 frames, {m.Frames} each): {e.MedianMs:F2} → {m.MedianMs:F2} ms/frame (**{m.MedianMs / e.MedianMs:F2}×**; target: at most 1.5×), {m.ParticleStepsPerSecond / 1e6:F0} M particle-steps/s on the mesh head. ({m.Particles:N0} particles on the mesh head, {e.Particles:N0} on the ellipsoid).");
    }
}
