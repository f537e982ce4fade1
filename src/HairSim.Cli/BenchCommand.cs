using System.CommandLine;
using System.Diagnostics;
using System.Globalization;
using System.Runtime.InteropServices;
using System.Text;
using HairSim;
using HairSim.Fast;

namespace HairSim.Cli;

/// <summary>
/// Speed of the solver paths: the reference scene (435 × 40 × 16) and a scaling series of strand counts, each
/// timed for the reference path (scalar double, 1 thread), the fast path on 1 thread and the fast path on every
/// core, in the same run. Warm-up frames first, then repeated timed frames; the median is reported. Per-system
/// rows time one system alone (a pipeline holding only that system) from the same warm state.
/// </summary>
public static partial class BenchCommand
{
    public const string Description = "Speed of the reference and fast paths, 1 thread and every core: the reference scene, styled hair, 1k … 100k strands, 3 … 64 particles per strand, each system alone; ms per frame, particle-steps/s, speed-up, bytes allocated per step.";

    public static Command Create()
    {
        var frames = CliOptions.Int("--frames", "timed frames per row (the median is reported)", 60, 3, 100_000);
        var warmup = CliOptions.Int("--warmup", "untimed frames before each row", 20, 1, 100_000);
        var threads = CliOptions.Int("--threads", "threads of the multi-threaded rows", () => Environment.ProcessorCount, 1, 256);
        var scales = CliOptions.IntList("--scales", "strand counts of the scaling series (17400 is the reference scene)", [1000, 4000, 17400, 50000, 100000], 40, 400_000, "strand counts");
        var rounds = CliOptions.Int("--rounds", "rounds for the largest scene's multi-threaded row (the frame-budget target)", 5, 1, 100);
        var lengths = CliOptions.IntList("--lengths", "particles per strand of the strand-length series", [3, 8, 12, 16, 17, 32, 64], 2, 256, "particles per strand");
        var noSystems = CliOptions.Switch("--no-systems", "leave out the rows that time each system alone");
        var output = CliOptions.Text("--out", "also write the tables into this Markdown file, keeping its hand-written part after the BENCH:END marker", null, "file.md");
        var command = new Command("bench", Description) { frames, warmup, threads, scales, rounds, lengths, noSystems, output };
        command.SetAction(p => Execute(p.GetValue(frames), p.GetValue(warmup), p.GetValue(threads), p.GetValue(scales)!, !p.GetValue(noSystems),
            p.GetValue(rounds), p.GetValue(lengths)!, p.GetValue(output) is { } o ? CliOptions.CheckOutputFile(o, "--out") : null));
        return command;
    }

    private static readonly CultureInfo Inv = CultureInfo.InvariantCulture;

    internal sealed record Row(string Scene, string Part, string Path, int Threads, int Strands, int Particles, int Frames,
        double MedianMs, double MinMs, double BytesPerStep, double Substeps)
    {
        /// <summary>Median of each round, when the row was timed in several rounds.</summary>
        public double[] RoundMedians { get; init; } = [];
        /// <summary>After each round of a multi-threaded row: arithmetic on every thread against one (<see cref="MachineCheck.QuickGain"/>).</summary>
        public double[] RoundChecks { get; init; } = [];
        public double MsPerStep => MedianMs / Substeps;
        public double ParticleStepsPerSecond => Particles * (double)Substeps / (MedianMs / 1000.0);
    }

    public static int Execute(int frames, int warmup, int threads, int[] scales, bool systems, int rounds, int[] lengths, string? outPath)
    {

        var command = "dotnet run -c Release --project src/HairSim.Cli -- bench" + (Environment.GetCommandLineArgs().Length > 2
            ? " " + string.Join(' ', Environment.GetCommandLineArgs().Skip(2)) : "");
        var rows = new List<Row>();
        var chunkPairs = new List<(Row On, Row Off)>();
        var total = Stopwatch.StartNew();
        using var parallel = new ParallelDispatcher(threads);
        // After a pause: right at start-up the build that `dotnet run` just did, or the runtime's own start-up work, can
        // still hold a core, and a check then reads about one core's work on two threads whatever the host does.
        Thread.Sleep(3000);
        var checkBefore = MachineCheck.Measure(threads);
        Console.Error.WriteLine($"machine check before the rows: {MachineCheck.Describe(checkBefore)}");

        // Whole frames: the reference scene first, then the scaling series.
        var scenes = new List<(string Name, GroomSettings Groom)> { ("reference 435×40×16", GroomSettings.Reference()) };
        foreach (int n in scales)
        {
            if (n == 17_400) continue; // that is the reference scene
            var g = GroomSettings.Reference();
            g.SheetCount = Math.Max(1, n / g.StrandsPerSheet);
            scenes.Add(($"{g.SheetCount * g.StrandsPerSheet:N0} strands", g));
        }
        long maxParticles = scenes.Max(x => x.Groom.TotalParticles);
        // The smallest groom of the scaling series, if it is smaller than the reference scene (else −1).
        long smallest = scenes.Count > 1 ? scenes.Skip(1).Min(x => x.Groom.TotalParticles) : -1;
        if (smallest >= scenes[0].Groom.TotalParticles) smallest = -1;
        foreach (var (name, groom) in scenes)
        {
            long particles = groom.TotalParticles;
            // The reference path is ~10–30× slower: time it on fewer frames (ratios are per step, so that is fair).
            int refFrames = Math.Max(3, (int)Math.Min(frames, frames * 278_400L / Math.Max(1, particles)));
            int refWarm = Math.Max(1, Math.Min(warmup, refFrames / 2));
            rows.Add(Frame(name, groom, SolverPath.Reference, SequentialDispatcher.Instance, 1, refWarm, refFrames));
            bool reference = name.StartsWith("reference", StringComparison.Ordinal);
            // The smallest groom (about a game character's) also at one substep per frame, side by side with its 4-substep
            // frame on 1 thread: the one-substep ratio of a groom whose chunks stay in the caches between frames.
            if (!reference && particles == smallest)
                rows.AddRange(Interleaved([new(name, "fast", groom), new(name + ", 1 substep", "fast", groom, Tune: OneSubstep)],
                    SequentialDispatcher.Instance, 1, warmup, frames));
            else if (!reference) rows.Add(Frame(name, groom, SolverPath.Fast, SequentialDispatcher.Instance, 1, warmup, frames));
            else
            {
                // Styled hair (the style command's cut, fitted fringe and baked rest pose) against the uncut groom, the
                // source's triples (the former default) on both, the default with one substep per frame and the source's
                // scheme alone (as a hand-vectorised native kernel runs it) with 4 and 1 substeps: the cost of styles, of
                // holding them and of a frame's fixed work, timed side by side (interleaved) on 1 thread and on every thread.
                // Guards off for one substep: with them on, gravity's limit per substep raises this scene to 2 at 60 Hz.
                rows.Add(Frame(name, groom, SolverPath.Reference, SequentialDispatcher.Instance, 1, refWarm, refFrames, styled: true));
                foreach (var (dispatcher, n) in threads > 1 ? new[] { ((IThreadDispatcher)SequentialDispatcher.Instance, 1), (parallel, threads) } : [(SequentialDispatcher.Instance, 1)])
                    rows.AddRange(Interleaved(
                    [
                        new(name, "fast", groom), new(name + ", styled", "fast", groom, Styled: true),
                        new(name, "fast, source's triples", groom, BendModel.SourceTriples),
                        new(name + ", styled", "fast, source's triples", groom, BendModel.SourceTriples, Styled: true),
                        new(name + ", 1 substep", "fast", groom, Tune: OneSubstep),
                        new(name + ", scheme only, 4 substeps", "fast", groom, Tune: SchemeOnly(4)),
                        new(name + ", scheme only, 1 substep", "fast", groom, Tune: SchemeOnly(1)),
                    ], dispatcher, n, warmup, frames));
            }
            // The largest scene's multi-threaded row is the frame-budget target: timed in several rounds, since run time on
            // a shared machine drifts from second to second.
            if (threads > 1 && !reference) rows.Add(Frame(name, groom, SolverPath.Fast, parallel, threads, warmup, frames, rounds: groom.TotalParticles == maxParticles ? rounds : 1));
            // Before/after in one run: the same fast path kept to its 8-lane (AVX) code, on the reference scene and the largest.
            if (FastPathInfo.Avx512 && (name.StartsWith("reference", StringComparison.Ordinal) || groom.TotalParticles == maxParticles))
            {
                rows.Add(Frame(name, groom, SolverPath.Fast, SequentialDispatcher.Instance, 1, warmup, frames, allowAvx512: false));
                if (threads > 1) rows.Add(Frame(name, groom, SolverPath.Fast, parallel, threads, warmup, frames, allowAvx512: false));
                // And with strand chunks off (every system over the world in turn, each substep: the path before chunks),
                // interleaved with chunks on in one simulation, so drift on a shared machine hits both alike.
                chunkPairs.Add(ChunksOnOff(name, groom, SequentialDispatcher.Instance, 1, warmup, frames));
                if (threads > 1) chunkPairs.Add(ChunksOnOff(name, groom, parallel, threads, warmup, frames));
                rows.Add(chunkPairs[threads > 1 ? ^2 : ^1].Off);
                if (threads > 1) rows.Add(chunkPairs[^1].Off);
            }
        }

        // Mesh head against the ellipsoid head, interleaved (docs/meshes.md).
        var meshPairs = MeshHeadBench.Pairs(threads > 1 ? parallel : null, threads, warmup, frames);
        foreach (var (m, e) in meshPairs) { rows.Add(m); rows.Add(e); }

        // Particles per strand: the reference scene's strand count at other strand lengths, on every core, so the cost
        // per particle-step of each length can be set against the best one (the fast path should not be tuned to one length).
        // Interleaved, so the ratios to the best length are taken in one window of time.
        var byLength = new List<Contender>();
        foreach (int n in lengths)
        {
            var g = GroomSettings.Reference();
            g.ParticlesPerStrand = n;
            g.PinnedPerStrand = Math.Min(g.PinnedPerStrand, n - 1);
            byLength.Add(new(LengthScene(n), "fast", g));
        }
        if (byLength.Count > 0) rows.AddRange(Interleaved(byLength, threads > 1 ? parallel : SequentialDispatcher.Instance, threads, warmup, frames));

        if (systems)
        {
            var groom = GroomSettings.Reference();
            foreach (var system in new[] { HeadFollowSystem.SystemName, ShapeMatchSystem.SystemName, IntegrateSystem.SystemName, BendSystem.SystemName, LengthSystem.SystemName, CollideSystem.SystemName, InterpolateSystem.SystemName })
            {
                rows.Add(OneSystem(groom, system, SolverPath.Reference, SequentialDispatcher.Instance, 1, Math.Max(3, frames / 4)));
                rows.Add(OneSystem(groom, system, SolverPath.Fast, SequentialDispatcher.Instance, 1, frames));
                if (threads > 1) rows.Add(OneSystem(groom, system, SolverPath.Fast, parallel, threads, frames));
                if (FastPathInfo.Avx512 && system is ShapeMatchSystem.SystemName or IntegrateSystem.SystemName or BendSystem.SystemName or LengthSystem.SystemName or CollideSystem.SystemName)
                    rows.Add(OneSystem(groom, system, SolverPath.Fast, SequentialDispatcher.Instance, 1, frames, allowAvx512: false));
            }
        }
        var checkAfter = MachineCheck.Measure(threads);
        Console.Error.WriteLine($"machine check after the rows: {MachineCheck.Describe(checkAfter)}");
        total.Stop();

        var table = Table(rows);
        Console.WriteLine();
        Console.WriteLine(table);
        Console.WriteLine($"bench took {total.Elapsed.TotalSeconds:F0} s");
        foreach (var line in MeshHeadBench.Lines(meshPairs)) Console.WriteLine(line);
        if (outPath != null) WriteDoc(outPath, table, command, rows, chunkPairs, threads, frames, warmup, rounds, meshPairs, (checkBefore, checkAfter));
        return 0;
    }

    private static string LengthScene(int particles) => $"17,400 strands × {particles} particles";

    private static HairScene Scene(GroomSettings groom, SolverPath path, BendModel bend = BendModel.RestShape, Action<SimulationSettings>? tune = null)
    {
        var settings = new SimulationSettings { Path = path, Bend = bend };
        tune?.Invoke(settings);
        return GroomBuilder.BuildScene(groom, settings);
    }

    /// <summary>
    /// The source's scheme alone, as a hand-vectorised native kernel runs it: triple shape matching (α 0.5),
    /// goal force, symplectic Euler and ellipsoid collision; no length pass, no guards, no speed limit.
    /// </summary>
    private static Action<SimulationSettings> SchemeOnly(int substeps) => st =>
    {
        st.Bend = BendModel.SourceTriples; st.Alpha = 0.5f; st.Length = LengthMode.None;
        st.Guards = false; st.MaxSpeed = 0f; st.Substeps = substeps;
    };

    /// <summary>One substep per frame, really: the guards would raise it (gravity may move a particle 5 % of a segment per substep).</summary>
    private static void OneSubstep(SimulationSettings st) { st.Substeps = 1; st.Guards = false; }

    /// <param name="styled">Style the scene first as the style command does (settle, bake the rest pose, chin-height cut, fitted fringe curl).</param>
    private static Row Frame(string name, GroomSettings groom, SolverPath path, IThreadDispatcher dispatcher, int threads, int warmup, int frames,
        bool allowAvx512 = true, int rounds = 1, bool styled = false)
    {
        var scene = Scene(groom, path);
        var sim = new HairSimulation(scene, PipelineBuilder.CreateDefault(allowAvx512), dispatcher);
        if (styled) new StyleCommand.Script(groom).StyleAll(sim);
        float dt = 1f / 60f;
        int f = 0;
        // At least `warmup` frames and, for the fast path, 1.5 s: the JIT recompiles hot methods with full optimisation
        // only after they have run a while (tiered compilation), and a short warm-up would time the first tiers.
        var warm = Stopwatch.StartNew();
        for (; f < warmup || (path == SolverPath.Fast && warm.Elapsed.TotalSeconds < 1.5); f++)
            sim.Step(dt, HairSim.Measurement.HeadMotion.Shake((f + 1) * dt));
        var times = new double[frames * rounds];
        var roundMedians = new double[rounds];
        var roundChecks = new double[rounds];
        var sw = new Stopwatch();
        long substeps = 0, bytes = 0;
        for (int r = 0, i = 0; r < rounds; r++)
        {
            long before = GC.GetTotalAllocatedBytes(true);
            for (int k = 0; k < frames; k++, i++, f++)
            {
                var head = HairSim.Measurement.HeadMotion.Shake((f + 1) * dt);
                sw.Restart();
                sim.Step(dt, head);
                times[i] = sw.Elapsed.TotalMilliseconds;
                substeps += sim.Pipeline.LastFrameSubsteps;
            }
            bytes += GC.GetTotalAllocatedBytes(true) - before;
            // Between the rounds of a multi-threaded row: what the machine gives every thread at that moment (issue 13's
            // two levels: a round that is slow on 2 threads, next to a check that reads about one core's arithmetic).
            if (rounds > 1 && threads > 1) roundChecks[r] = MachineCheck.QuickGain(threads);
        }
        for (int r = 0; r < rounds; r++)
        {
            var round = times.AsSpan(r * frames, frames).ToArray();
            Array.Sort(round);
            roundMedians[r] = round[frames / 2];
        }
        if (scene.World.CountNonFinite() != 0) throw new InvalidDataException($"{name} ({path}) produced non-finite values.");
        var row = Summarise(styled ? name + ", styled" : name, "frame", path, threads, scene, times, bytes, times.Length, (double)substeps / times.Length) with { RoundMedians = rounds > 1 ? roundMedians : [], RoundChecks = rounds > 1 && threads > 1 ? roundChecks : [] };
        if (!allowAvx512) row = row with { Path = "fast, 8-lane" };
        Console.Error.WriteLine($"{name,-22} {Label(row),-18} {row.MedianMs,9:F3} ms/frame");
        return row;
    }

    /// <summary>Chunks on and off in one simulation, alternating blocks of 10 frames: (on, off) rows.</summary>
    private static (Row On, Row Off) ChunksOnOff(string name, GroomSettings groom, IThreadDispatcher dispatcher, int threads, int warmup, int frames)
    {
        var scene = Scene(groom, SolverPath.Fast);
        var sim = new HairSimulation(scene, dispatcher: dispatcher);
        float dt = 1f / 60f;
        int f = 0;
        var warm = Stopwatch.StartNew();
        for (; f < warmup || warm.Elapsed.TotalSeconds < 1.5; f++)
        {
            sim.Pipeline.UseStrandChunks = f % 2 == 0; // both paths reach the JIT's optimised tier
            sim.Step(dt, HairSim.Measurement.HeadMotion.Shake((f + 1) * dt));
        }
        const int Block = 10;
        int blocks = Math.Max(1, (frames + Block - 1) / Block);
        var on = new double[blocks * Block];
        var off = new double[blocks * Block];
        var sw = new Stopwatch();
        for (int b = 0; b < blocks; b++)
            for (int pass = 0; pass < 2; pass++)
            {
                sim.Pipeline.UseStrandChunks = pass == 0;
                var times = pass == 0 ? on : off;
                for (int i = 0; i < Block; i++, f++)
                {
                    var head = HairSim.Measurement.HeadMotion.Shake((f + 1) * dt);
                    sw.Restart();
                    sim.Step(dt, head);
                    times[b * Block + i] = sw.Elapsed.TotalMilliseconds;
                }
            }
        if (scene.World.CountNonFinite() != 0) throw new InvalidDataException($"{name} produced non-finite values.");
        var rowOn = Summarise(name, "frame", SolverPath.Fast, threads, scene, on, 0, on.Length);
        var rowOff = Summarise(name, "frame", SolverPath.Fast, threads, scene, off, 0, off.Length) with { Path = "fast, no chunks" };
        Console.Error.WriteLine($"{name,-22} {Label(rowOff),-18} {rowOff.MedianMs,9:F3} ms/frame (chunks on, interleaved: {rowOn.MedianMs:F3})");
        return (rowOn, rowOff);
    }

    private static Row OneSystem(GroomSettings groom, string system, SolverPath path, IThreadDispatcher dispatcher, int threads, int frames,
        bool allowAvx512 = true)
    {
        // Shape matching and the separate length pass belong to the source's scheme (the default bend sweep has the length fused in).
        var scene = Scene(groom, path, system is ShapeMatchSystem.SystemName or LengthSystem.SystemName ? BendModel.SourceTriples : BendModel.RestShape);
        if (system == InterpolateSystem.SystemName) scene.Render = new RenderSettings(); // one render strand per gap, the default
        // A moving state: one second of the full simulation with a shaking head, then the system alone from there.
        var warm = new HairSimulation(scene, dispatcher: dispatcher);
        float dt = 1f / 60f;
        for (int f = 0; f < 60; f++) warm.Step(dt, HairSim.Measurement.HeadMotion.Shake((f + 1) * dt));
        var snapshot = scene.World.Clone();
        var only = new PipelineBuilder();
        foreach (var fac in PipelineBuilder.CreateDefault(allowAvx512).Factories) if (fac.Name == system) only.Add(fac);
        var pipeline = only.Build(scene, dispatcher);
        pipeline.UseStrandChunks = false; // the system's own pass over the world (chunks are timed in whole frames)
        var head = HairSim.Measurement.HeadMotion.Shake(61 * dt);
        // Each frame restarts from the snapshot's motion only (not an edit: caches of pins and rest data stay valid).
        for (int i = 0; i < 3; i++) { snapshot.CopyMotionTo(scene.World); pipeline.Step(dt, head); }
        var times = new double[frames];
        var sw = new Stopwatch();
        long bytes = 0;
        for (int i = 0; i < frames; i++)
        {
            snapshot.CopyMotionTo(scene.World);
            long b0 = GC.GetTotalAllocatedBytes(true);
            sw.Restart();
            pipeline.Step(dt, head);
            times[i] = sw.Elapsed.TotalMilliseconds;
            bytes += GC.GetTotalAllocatedBytes(true) - b0;
        }
        // Interpolate runs once per frame, so its "step" is the frame and its particles are each processed once.
        var row = Summarise("reference 435×40×16", system, path, threads, scene, times, bytes, frames,
            system == InterpolateSystem.SystemName ? 1 : null);
        if (!allowAvx512) row = row with { Path = "fast, 8-lane" };
        Console.Error.WriteLine($"{system,-22} {Label(row),-18} {row.MedianMs,9:F3} ms/frame");
        return row;
    }

    /// <param name="passesPerFrame">Steps per frame the row's per-step figures divide by: the substeps actually stepped (the guards may add some), on average; the requested substeps if not given.</param>
    internal static Row Summarise(string name, string part, SolverPath path, int threads, HairScene scene, double[] times, long bytes, int frames, double? passesPerFrame = null)
    {
        var sorted = (double[])times.Clone();
        Array.Sort(sorted);
        double substeps = passesPerFrame ?? scene.Settings.Substeps;
        return new Row(name, part, path == SolverPath.Fast ? "fast" : "reference", threads, scene.World.StrandCount, scene.World.ParticleCount,
            frames, sorted[sorted.Length / 2], sorted[0], bytes / (double)(frames * substeps), substeps);
    }

    private static string Label(Row r) => $"{r.Path} ×{r.Threads}";

    private static string Table(List<Row> rows)
    {
        var sb = new StringBuilder();
        sb.AppendLine("| scene | part | path | threads | particles | frames timed | ms/frame (median) | steps/frame | ms/step | particle-steps/s | speed-up vs reference | bytes allocated/step |");
        sb.AppendLine("| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
        foreach (var r in rows)
        {
            var reference = rows.Find(x => x.Scene == r.Scene && x.Part == r.Part && x.Path == "reference");
            string speedup = reference == null ? "–" : (reference.MsPerStep / r.MsPerStep).ToString("F1", Inv) + "×";
            sb.AppendLine(string.Create(Inv,
                $"| {r.Scene} | {r.Part} | {r.Path} | {r.Threads} | {r.Particles:N0} | {r.Frames} | {r.MedianMs:F3} | {r.Substeps:0.##} | {r.MsPerStep:F3} | {r.ParticleStepsPerSecond / 1e6:F1} M | {speedup} | {r.BytesPerStep:F0} |"));
        }
        return sb.ToString();
    }

    private static void WriteDoc(string path, string table, string command, List<Row> rows, List<(Row On, Row Off)> chunkPairs, int threads, int frames, int warmup, int rounds,
        List<(Row Mesh, Row Ellipsoid)> meshPairs, (MachineCheck.Result Before, MachineCheck.Result After) check)
    {
        var sb = new StringBuilder();
        sb.AppendLine("# Performance");
        sb.AppendLine();
        sb.AppendLine("<!-- The section between the BENCH markers is generated by the bench command; the design section below it is hand-written. -->");
        sb.AppendLine("<!-- BENCH:BEGIN -->");
        sb.AppendLine("## Measured");
        sb.AppendLine();
        sb.AppendLine($"Command: `{command}`");
        sb.AppendLine();
        sb.AppendLine(string.Create(Inv, $"- Machine: {CpuModel()}, {Environment.ProcessorCount} logical cores, {RuntimeInformation.OSDescription}"));
        sb.AppendLine($"- Machine check (`MachineCheck`, no HairSim code: eight independent FMA chains per thread, and sums over a 64 MB array), before the rows: {MachineCheck.Describe(check.Before)}; after them: {MachineCheck.Describe(check.After)}. On a shared virtual machine these move from run to run, and the rows with them.");
        sb.AppendLine($"- Runtime: {RuntimeInformation.FrameworkDescription}, SIMD width {System.Numerics.Vector<float>.Count} floats (Vector<float>), hardware acceleration {System.Numerics.Vector.IsHardwareAccelerated}");
        sb.AppendLine($"- Date: {DateTime.UtcNow:yyyy-MM-dd HH:mm} UTC");
        sb.AppendLine($"- Method: {warmup} warm-up frames (fast path: at least 1.5 s of them, so the JIT's optimised tier is what gets timed), then {frames} timed frames (fewer for the reference path on large scenes: it is timed on ⌈{frames}·278,400/particles⌉ frames, at least 3); median reported. 60 Hz frames, 4 substeps, head shaking (±40° at 1.5 Hz) so collisions happen. Steps/frame: the substeps whole-frame rows actually stepped, on average (the stability guards add some where the head moves far against a segment's length: the 64-particle strands' 4 mm segments), and ms/step = ms/frame ÷ steps/frame. Speed-up = reference ms/step ÷ this row's ms/step, both from this run. Bytes allocated/step = GC.GetTotalAllocatedBytes(precise) over the timed frames (all threads) ÷ steps. The largest scene's multi-threaded row is timed in {rounds} rounds of {frames} frames back to back; its median is over all of them, and the round medians are listed under Target 2. Rows marked \"fast, 8-lane\" run the same fast path with its AVX-512 code turned off (`PipelineBuilder.CreateDefault(allowAvx512: false)`), rows marked \"fast, no chunks\" with strand chunks turned off (`HairPipeline.UseStrandChunks = false`: each system over the world in turn), timed in the same simulation as chunks on, alternating blocks of 10 frames: before/after in one run.");
        sb.AppendLine("- Rows \"…, styled\": the reference scene styled as the style command does (1 s settle, rest pose baked, chin-height cut through every layer, a curl fitted to the 1,035-strand fringe), timed from there. Rows \"fast, source's triples\": the same hair with the source's triple shape matching and a separate follow-the-leader pass (BendModel.SourceTriples, the default before the rest-shape model). Interleaved: the reference scene's fast rows on each thread count (default, styled, source's triples uncut and styled, one substep, the source's scheme alone with 4 and 1 substeps) are stepped in turn, in one process, and so are the smallest scene's 4-substep and one-substep rows on 1 thread and the rows of the particles-per-strand series (blocks of about equal time: 10 frames of the group's slowest scene and up to 80 of a faster one); their ratios are taken in one window of time.");
        sb.AppendLine("- Per-system rows: one system alone (a pipeline holding only it, strand chunks off, so the row times the system's own pass over the world; ShapeMatch and Length on the source's scheme, whose systems they are), each frame starting from the same warm state (1 s of shaking), on the reference scene. Interpolate is the render interpolation, once per frame (the scene gets default render settings: one render strand between neighbours, 549,840 render points); the whole-frame rows have no render strands (docs/leave-out.md times frames with them).");
        sb.AppendLine("- All rows come from one run on a shared machine (other builds may run at the same time): compare rows within the table, and rerun for absolute numbers.");
        sb.AppendLine();
        sb.Append(table);
        sb.AppendLine();
        var refFast = rows.Find(r => r.Scene == "reference 435×40×16" && r.Part == "frame" && r.Path == "fast" && r.Threads == threads);
        var big = rows.FindAll(r => r.Part == "frame" && r.Path == "fast" && r.Threads == threads).OrderByDescending(r => r.Particles).FirstOrDefault();
        if (refFast != null)
            sb.AppendLine(string.Create(Inv, $"Target 1 — reference scene well under 1 ms per step on {threads} threads: **{refFast.MsPerStep:F3} ms/step** ({refFast.MedianMs:F2} ms per 4-substep frame)."));
        if (big != null)
            sb.AppendLine(string.Create(Inv, $"Target 2 — 100,000 strands × 16 particles, 4 substeps, within a 60 Hz frame (16.7 ms) on {threads} threads: largest scene in this run ({big.Strands:N0} strands): **{big.MedianMs:F2} ms/frame** (median of {big.Frames} frames{(big.RoundMedians.Length > 1 ? $" in {big.RoundMedians.Length} rounds; round medians {string.Join(", ", big.RoundMedians.Select(m => m.ToString("F2", Inv)))} ms{(big.RoundChecks.Length == big.RoundMedians.Length ? $"; arithmetic on {threads} threads against one, checked right after each round: {string.Join(", ", big.RoundChecks.Select(m => m.ToString("F2", Inv) + "×"))}" : "")}" : "")}; slowest round {(big.RoundMedians.Length > 1 ? big.RoundMedians.Max() : big.MedianMs).ToString("F2", Inv)} ms)."));
        foreach (var narrow in rows.FindAll(r => r.Path == "fast, 8-lane"))
        {
            var wide = rows.Find(r => r.Scene == narrow.Scene && r.Part == narrow.Part && r.Path == "fast" && r.Threads == narrow.Threads);
            if (wide != null)
                sb.AppendLine(string.Create(Inv, $"16-lane (AVX-512) paths vs the same fast path kept to 8 lanes, {(narrow.Part == "frame" ? narrow.Scene : $"{narrow.Part} alone")}, {narrow.Threads} thread{(narrow.Threads == 1 ? "" : "s")}: {narrow.MedianMs:F2} → {wide.MedianMs:F2} ms/frame (**{narrow.MedianMs / wide.MedianMs:F2}×**)."));
        }
        foreach (int n in threads > 1 ? new[] { 1, threads } : [1])
        {
            Row? Find(string scene, string p) => rows.Find(r => r.Scene == scene && r.Part == "frame" && r.Path == p && r.Threads == n);
            const string Ref = "reference 435×40×16";
            var plain = Find(Ref, "fast"); var styledRow = Find(Ref + ", styled", "fast");
            var source = Find(Ref, "fast, source's triples"); var sourceStyled = Find(Ref + ", styled", "fast, source's triples");
            if (plain != null && styledRow != null && source != null && sourceStyled != null)
                sb.AppendLine(string.Create(Inv, $"Styled vs uncut, {n} thread{(n == 1 ? "" : "s")}: the default bend model {plain.MedianMs:F2} → {styledRow.MedianMs:F2} ms/frame styled (**{styledRow.MedianMs / plain.MedianMs:F2}×**); the source's triples (the former default) {source.MedianMs:F2} → {sourceStyled.MedianMs:F2} ms/frame (**{sourceStyled.MedianMs / source.MedianMs:F2}×**). The default model against the former default on the uncut groom: **{plain.MedianMs / source.MedianMs:F2}×**, styled: **{styledRow.MedianMs / source.MedianMs:F2}×** (target for styled and uncut: at most 1.3× the former default uncut)."));
        }
        foreach (int n in threads > 1 ? new[] { 1, threads } : [1])
        {
            Row? Find(string scene) => rows.Find(r => r.Scene == scene && r.Part == "frame" && r.Path == "fast" && r.Threads == n);
            const string Ref = "reference 435×40×16";
            var four = Find(Ref); var one = Find(Ref + ", 1 substep");
            var s4 = Find(Ref + ", scheme only, 4 substeps"); var s1 = Find(Ref + ", scheme only, 1 substep");
            // A hand-vectorised C kernel of the source's step, measured separately on the 2-core AMD EPYC virtual machine, ms per step.
            double native = n == 1 ? 0.354 : n == 2 ? 0.193 : double.NaN;
            if (four != null && one != null)
                sb.AppendLine(string.Create(Inv, $"One substep per frame (guards off, which would make it 2), default model, {n} thread{(n == 1 ? "" : "s")}: {one.MedianMs:F3} ms per frame against {four.MsPerStep:F3} ms per substep at 4 substeps (**{one.MedianMs / four.MsPerStep:F2}×**; target: at most 1.3×)."));
            foreach (var small in rows.FindAll(r => r.Threads == n && r.Part == "frame" && r.Path == "fast" && !r.Scene.StartsWith(Ref, StringComparison.Ordinal)
                && r.Scene.EndsWith(", 1 substep", StringComparison.Ordinal)))
            {
                var smallFour = Find(small.Scene[..^", 1 substep".Length]);
                if (smallFour != null)
                    sb.AppendLine(string.Create(Inv, $"One substep per frame, {smallFour.Scene} (a small groom, whose chunks stay in the caches), {n} thread{(n == 1 ? "" : "s")}: {small.MedianMs:F3} ms per frame against {smallFour.MsPerStep:F3} ms per substep at 4 substeps (**{small.MedianMs / smallFour.MsPerStep:F2}×**)."));
            }
            if (s4 != null && s1 != null)
                sb.AppendLine(string.Create(Inv, $"The source's scheme alone (triples at α 0.5, no length pass, guards and speed limit off), {n} thread{(n == 1 ? "" : "s")}: {s4.MsPerStep:F3} ms per substep at 4 substeps, {s1.MedianMs:F3} ms per frame at 1 substep{(double.IsFinite(native) ? $"; against a hand-vectorised native C kernel of the same scheme ({native:F3} ms per step on the same machine, measured separately; the kernel is not in the project): **{s4.MsPerStep / native:F2}×** and **{s1.MedianMs / native:F2}×**" : "")}."));
        }
        var byLength = rows.FindAll(r => r.Scene.StartsWith("17,400 strands × ", StringComparison.Ordinal) && r.Path == "fast");
        if (byLength.Count > 1)
        {
            double best = byLength.Min(r => r.MedianMs / (r.Particles * (double)r.Substeps));
            var parts = byLength.Select(r => string.Create(Inv, $"{r.Particles / 17_400} → {1e6 * r.MedianMs / (r.Particles * (double)r.Substeps):F2} ns ({r.MedianMs / (r.Particles * (double)r.Substeps) / best:F2}×{(r.Substeps > 4.005 ? $", {r.Substeps:F1} substeps per frame: the guards add some while the head shakes" : "")})"));
            double worst = byLength.Max(r => r.MedianMs / (r.Particles * (double)r.Substeps)) / best;
            sb.AppendLine(string.Create(Inv, $"Particles per strand, 17,400 strands, default model, {byLength[0].Threads} thread{(byLength[0].Threads == 1 ? "" : "s")}: cost per particle-step (and against the best length) {string.Join("; ", parts)}. Worst against best: **{worst:F2}×** (target: within 1.3×)."));
        }
        foreach (var (on, off) in chunkPairs)
            sb.AppendLine(string.Create(Inv, $"Strand chunks vs the same fast path system by system, {off.Scene}, {off.Threads} thread{(off.Threads == 1 ? "" : "s")}, interleaved in one simulation (blocks of 10 frames, {off.Frames} each): {off.MedianMs:F2} → {on.MedianMs:F2} ms/frame (**{off.MedianMs / on.MedianMs:F2}×**)."));
        foreach (var line in MeshHeadBench.Lines(meshPairs)) sb.AppendLine(line);
        sb.AppendLine("<!-- BENCH:END -->");
        string generated = sb.ToString();

        // Keep the hand-written part of an existing document.
        string hand = DesignSection;
        if (File.Exists(path))
        {
            string old = File.ReadAllText(path);
            int end = old.IndexOf("<!-- BENCH:END -->", StringComparison.Ordinal);
            if (end >= 0) hand = old[(end + "<!-- BENCH:END -->".Length)..].TrimStart('\n', '\r');
        }
        string full = generated + "\n" + hand;
        string? dir = Path.GetDirectoryName(Path.GetFullPath(path));
        if (dir != null) Directory.CreateDirectory(dir);
        string tmp = path + ".tmp";
        File.WriteAllText(tmp, full);
        File.Move(tmp, path, overwrite: true);
        Console.WriteLine($"wrote {path}");
    }

    private static string CpuModel()
    {
        try
        {
            if (File.Exists("/proc/cpuinfo"))
                foreach (var line in File.ReadLines("/proc/cpuinfo"))
                    if (line.StartsWith("model name", StringComparison.Ordinal)) return line[(line.IndexOf(':') + 1)..].Trim();
        }
        catch (IOException) { }
        return RuntimeInformation.ProcessArchitecture.ToString();
    }

    private const string DesignSection = "## Design\n\n(See the repository's docs/performance.md for the design notes.)\n";
}
