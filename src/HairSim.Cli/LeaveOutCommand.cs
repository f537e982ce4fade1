using System.CommandLine;
using System.Diagnostics;
using System.Globalization;
using System.Text;
using HairSim;
using HairSim.Measurement;

namespace HairSim.Cli;

/// <summary>
/// What leaving out saves: for each scene that needs less than the whole pipeline (LeaveOutCase), the frame time of
/// its lean pipeline against the same hair with every core system kept, all simulations timed in turn in one run.
/// </summary>
public static class LeaveOutCommand
{
    public const string Description = "What leaving unneeded systems out saves: six kinds of scene, the lean pipeline against every system kept, on 1 thread and on every core: a Markdown report with a chart.";

    public static Command Create()
    {
        var output = CliOptions.Text("--out", "the report to write (its chart goes to img/ beside it)", "out/leave-out.md", "file.md");
        var frames = CliOptions.Int("--frames", $"timed frames per simulation (stepped in blocks of {Block}; 120 keeps a burst of load on a shared machine out of the medians)", 120, Block, 10_000);
        var threads = CliOptions.Int("--threads", "the most threads to time with (1 and this many)", () => Environment.ProcessorCount, 1, 256);
        var command = new Command("leave-out", Description) { output, frames, threads };
        command.SetAction(p => Execute(CliOptions.CheckOutputFile(p.GetValue(output)!, "--out"), p.GetValue(frames), p.GetValue(threads)));
        return command;
    }

    private static readonly CultureInfo Inv = CultureInfo.InvariantCulture;
    private const int Block = 10;

    private sealed record Measured(LeaveOutCase Case, int Threads, string[] Lean, double LeanMs, double KeptMs, int Particles, int Substeps);

    public static int Execute(string output, int frames, int threads)
    {

        var results = new List<Measured>();
        var clock = Stopwatch.StartNew();
        foreach (int t in threads > 1 ? new[] { 1, threads } : [1])
        {
            using var dispatcher = new ParallelDispatcher(t);
            results.AddRange(Measure(dispatcher, t, frames));
        }
        foreach (var m in results)
            Console.WriteLine(string.Create(Inv, $"{m.Case.Name,-18} ×{m.Threads}  lean {m.LeanMs,7:F3} ms  kept {m.KeptMs,7:F3} ms  ({string.Join(", ", m.Lean)})"));
        Write(output, results, frames, clock.Elapsed.TotalSeconds);
        Console.WriteLine($"written {output}");
        return 0;
    }

    /// <summary>
    /// Every case's lean and kept simulations on the reference groom, stepped in turn in blocks of 10 frames (so drift
    /// on a shared machine hits all alike) after a common warm-up that lets the JIT reach its optimised code.
    /// </summary>
    private static List<Measured> Measure(IThreadDispatcher dispatcher, int threads, int frames)
    {
        var groom = GroomSettings.Reference();
        var settings = new SimulationSettings();
        var cases = LeaveOutCase.All;
        var sims = new List<(HairSimulation Sim, int Case, bool Kept)>();
        for (int c = 0; c < cases.Count; c++)
        {
            sims.Add((new HairSimulation(cases[c].BuildLean(groom, settings), dispatcher: dispatcher), c, false));
            sims.Add((new HairSimulation(cases[c].BuildKept(groom, settings), LeaveOutCase.KeepEverything(), dispatcher), c, true));
        }
        var progress = new Progress($"leave-out ×{threads}", frames / Block + 1);
        float dt = 1f / 60f;
        var frame = new int[sims.Count];
        var warm = Stopwatch.StartNew();
        while (warm.Elapsed.TotalSeconds < 1.5 || frame[^1] < 2 * Block)
            for (int s = 0; s < sims.Count; s++) Step(sims[s].Sim, ref frame[s], dt);
        progress.Report(1, "warm-up");

        var times = new double[sims.Count][];
        for (int s = 0; s < sims.Count; s++) times[s] = new double[frames / Block * Block];
        var sw = new Stopwatch();
        for (int b = 0; b < frames / Block; b++)
        {
            for (int s = 0; s < sims.Count; s++)
                for (int i = 0; i < Block; i++)
                {
                    sw.Restart();
                    Step(sims[s].Sim, ref frame[s], dt);
                    times[s][b * Block + i] = sw.Elapsed.TotalMilliseconds;
                }
            progress.Report(b + 2, $"block {b + 1}");
        }

        var list = new List<Measured>();
        for (int c = 0; c < cases.Count; c++)
        {
            int lean = 2 * c, kept = 2 * c + 1;
            var scene = sims[lean].Sim.Scene;
            if (scene.World.CountNonFinite() != 0) throw new InvalidDataException($"{cases[c].Name} produced non-finite values.");
            list.Add(new Measured(cases[c], threads, [.. sims[lean].Sim.Pipeline.SystemNames], Median(times[lean]), Median(times[kept]),
                scene.World.ParticleCount, scene.Settings.Substeps));
        }
        return list;
    }

    private static void Step(HairSimulation sim, ref int frame, float dt)
    {
        frame++;
        sim.Step(dt, HeadMotion.Shake(frame * dt));
    }

    private static double Median(double[] xs)
    {
        var s = (double[])xs.Clone();
        Array.Sort(s);
        return s[s.Length / 2];
    }

    private static void Write(string output, List<Measured> results, int frames, double seconds)
    {
        string dir = Path.GetDirectoryName(Path.GetFullPath(output))!;
        Directory.CreateDirectory(Path.Combine(dir, "img"));
        int maxThreads = results.Max(r => r.Threads);
        var top = results.FindAll(r => r.Threads == maxThreads);
        StabilityCommand.WriteFile(Path.Combine(dir, "img", "leave-out.svg"), SvgPlot.Bars(
            $"Frame time of the reference groom, lean pipeline vs every system kept ({maxThreads} thread{(maxThreads == 1 ? "" : "s")})",
            "ms per 60 Hz frame (4 substeps, 278,400 particles, head shaking)",
            top.ConvertAll(r => r.Case.Name), ["lean: only the systems the scene needs", "every core system kept"],
            [top.ConvertAll(r => r.LeanMs).ToArray(), top.ConvertAll(r => r.KeptMs).ToArray()]));

        var md = new StringBuilder();
        md.Append("# Leaving out what a scene does not need\n\n");
        md.Append(F($"Generated by `dotnet run -c Release --project src/HairSim.Cli -- leave-out --out {CliOptions.Shown(output)}` (fast path, {Environment.ProcessorCount} cores, {seconds:F0} s). Run times vary from machine to machine and run to run; compare rows of one run.\n\n"));
        md.Append(Method);
        md.Append("![leave-out](img/leave-out.svg)\n\n");
        md.Append("| scene | what it has | systems it runs | threads | ms/frame lean | ms/frame with every system kept | kept ÷ lean | lean vs game character | M particle-steps/s (lean) |\n");
        md.Append("|---|---|---|---:|---:|---:|---:|---:|---:|\n");
        foreach (var r in results)
        {
            var full = results.Find(x => x.Threads == r.Threads && x.Case == LeaveOutCase.All[0])!;
            md.Append(F($"| {r.Case.Name} | {r.Case.Has} | {string.Join(", ", r.Lean)} | {r.Threads} | {r.LeanMs:F3} | {r.KeptMs:F3} | {r.KeptMs / r.LeanMs:F2}× | {100 * (r.LeanMs / full.LeanMs - 1):+0;−0;0} % | {r.Particles * (double)r.Substeps / (r.LeanMs / 1000) / 1e6:F0} |\n"));
        }
        md.Append('\n');
        md.Append(Findings(results));
        StabilityCommand.WriteFile(output, md.ToString());
    }

    private static string Findings(List<Measured> results)
    {
        var sb = new StringBuilder("## Findings\n\n");
        foreach (int t in results.Select(r => r.Threads).Distinct())
        {
            var rows = results.FindAll(r => r.Threads == t && r.Case != LeaveOutCase.All[0]);
            sb.Append(F($"- {t} thread{(t == 1 ? "" : "s")}, time a kept pipeline spends on systems its scene does not need: "));
            sb.Append(string.Join("; ", rows.Select(r => F($"{r.Case.Name} {r.KeptMs - r.LeanMs:+0.00;−0.00} ms ({r.KeptMs / r.LeanMs:F2}×)"))));
            sb.Append(".\n");
        }
        sb.Append("""
            - Where the kept system has nothing to do it returns at once (the bend sweep under another bend model, the
              length pass when the bend sweep keeps lengths itself or with `LengthMode.None`, collide with no collider),
              so leaving it out saves only a pass over nothing, within the run-to-run noise of the machine; what such a scene saves is
              the work itself, in the column against the game character. Where the kept system would still work for
              nothing (render interpolation that nobody draws, the source's shape matching at α = 0), leaving it out
              saves that work outright.


            """);
        return sb.ToString();
    }

    private const string Method = """
        Each scene is the reference groom (435 sheets × 40 strands × 16 particles, default settings: the rest-shape bend
        model with its lengths kept in the same sweep, 4 substeps, 60 Hz) with the head shaking (±40° at 1.5 Hz), minus
        what its row takes away (the last row adds hair volume instead: its "lean vs game character" is what the volume
        system costs when a scene asks for it; every other lean pipeline leaves it out).
        It is simulated twice:
        - **lean**: the default pipeline builder, which keeps only the systems whose data the scene has
          (`PipelineBuilder`, listed by `HairPipeline.SystemNames`);
        - **every system kept**: the same hair with every core system in the pipeline anyway
          (`LeaveOutCase.KeepEverything`), and render strands computed that nothing reads. A kept system still does
          its work: the source's shape matching (α = 0 outside its own model) computes every goal and moves nothing;
          the bend sweep under another bend model, the length pass whose work the bend sweep already did, and the
          collide system with no collider return at once; interpolation fills render strands; the volume system builds
          its whole grid and every push with zero stiffness and friction, and changes nothing; the strand-contact system
          boxes every segment and files the boxes in its grid once per pass, and stops there (on a groom this dense the
          contacts themselves refuse to run: docs/volume.md).

        Both give the same particle bits (`LeaveOutCasesTests`, every case, both solver paths), so the difference in
        time is what leaving out saves, and nothing else changes. All simulations of one thread count are stepped in
        turn, 10 frames each, after a common warm-up of at least 1.5 s; medians are reported. "lean vs game
        character" compares with the first row, the scene that needs everything.


        """;

    private static string F(FormattableString s) => s.ToString(Inv);
}
