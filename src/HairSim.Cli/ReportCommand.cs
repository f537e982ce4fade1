using System.CommandLine;
using System.Globalization;
using System.Text;
using HairSim;
using HairSim.Measurement;

namespace HairSim.Cli;

/// <summary>
/// Error against run time: every solver configuration through the canonical cases (hanging strand, catenary,
/// pendulum, collision sweep, shake, teleport, held shapes), a table and a plot with the Pareto front; then the
/// defaults' held shapes across scales, frame rates and substeps, and the same head shake at three sizes.
/// </summary>
public static class ReportCommand
{
    public const string Description = "Error against run time for every solver configuration (hanging strand, catenary, pendulum, collision sweep, head shake, teleport, held shapes), held shapes at every scale, frame rate and substep count, and the hair volume: a Markdown report with a plot.";

    public static Command Create()
    {
        var output = CliOptions.Text("--out", "the report to write (its plot goes to img/ beside it)", "out/error-vs-runtime.md", "file.md");
        var quick = CliOptions.Switch("--quick", "a short run: fewer configurations, scales and timing rounds");
        var path = CliOptions.SolverPathOption();
        var command = new Command("report", Description) { output, quick, path };
        command.SetAction(p => Execute(CliOptions.CheckOutputFile(p.GetValue(output)!, "--out"), p.GetValue(quick), CliOptions.ToSolverPath(p.GetValue(path))));
        return command;
    }

    public static int Execute(string output, bool quick, SolverPath path)
    {

        var configs = ErrorReport.Configurations(quick);
        var defaults = SolverConfiguration.FromSettings(new SimulationSettings());
        if (!configs.Contains(defaults)) configs.Add(defaults);
        using var dispatcher = ThreadDispatchers.CreateDefault();
        // Errors first, in parallel (deterministic); then run times one configuration at a time on a quiet machine.
        var rows = new ReportRow[configs.Count];
        var shakeCache = new System.Collections.Concurrent.ConcurrentDictionary<SolverConfiguration, double>();
        var progress = new Progress("measuring errors", configs.Count);
        int done = 0;
        Parallel.For(0, configs.Count, new ParallelOptions { MaxDegreeOfParallelism = Environment.ProcessorCount }, i =>
        {
            rows[i] = ErrorReport.MeasureErrors(configs[i], path, shakeCache);
            lock (progress) progress.Report(++done, configs[i].Label);
        });
        // Run times in rounds over all configurations. Round 0 is discarded: it lets the JIT reach its optimised tier
        // (timed first, the first configurations ran 3-10x slow on unoptimised code). Later rounds alternate the order
        // so drift on the machine hits every configuration alike; each keeps its fastest batch.
        int rounds = TimingRounds(quick);
        progress = new Progress("timing", configs.Count * (rounds + 1));
        var best = new Timing[configs.Count];
        for (int round = 0, step = 0; round <= rounds; round++)
            for (int k = 0; k < configs.Count; k++)
            {
                int i = round % 2 == 0 ? k : configs.Count - 1 - k;
                var t = ErrorReport.Time(configs[i], path, dispatcher, quick);
                if (round > 0 && (round == 1 || t.MicrosecondsPerFrame < best[i].MicrosecondsPerFrame)) best[i] = t;
                progress.Report(++step, round == 0 ? "warm-up " + configs[i].Label : configs[i].Label);
            }
        // Configurations that differ only in α run the same code on the same data (α is a multiplier), so they share
        // one run time: the fastest batch of any of them. Timed apart, this machine's noise alone decided which of
        // them looked faster, and so which of them the front kept.
        for (int i = 0; i < configs.Count; i++)
        {
            var shared = best[i];
            for (int j = 0; j < configs.Count; j++)
                if (SameCode(configs[i], configs[j]) && best[j].MicrosecondsPerFrame < shared.MicrosecondsPerFrame) shared = best[j];
            rows[i] = rows[i] with { Timing = shared };
        }
        var rowList = new List<ReportRow>(rows);
        var errors = rowList.ConvertAll(r => r.Error);
        var costs = rowList.ConvertAll(r => r.Timing.MicrosecondsPerFrame);
        var front = ParetoFront.Indices(costs, errors);
        int def = rowList.FindIndex(r => r.Config == defaults);

        Console.WriteLine(Legend);
        foreach (var r in rowList) Console.WriteLine(Line(r));
        bool onFront = Array.IndexOf(front, def) >= 0;
        Console.WriteLine($"default: {defaults.Label}; on the front: {onFront}; length error {Pct(rows[def].LengthError)}");
        Write(output, rowList, front, def, quick, path, dispatcher.ThreadCount);
        Console.WriteLine($"written {output}");
        if (!onFront || rows[def].LengthError >= 0.005)
        {
            Console.Error.WriteLine($"check failed: the defaults {(onFront ? "are on the Pareto front" : "are not on the Pareto front")}; their hanging-strand length error is {Pct(rows[def].LengthError)} (limit 0.5 %)");
            return ExitCodes.CheckFailed;
        }
        return ExitCodes.Ok;
    }

    private static int TimingRounds(bool quick) => quick ? 1 : 2;

    /// <summary>Whether two configurations run the same code per substep (they may differ in α only).</summary>
    private static bool SameCode(SolverConfiguration a, SolverConfiguration b) =>
        a.Bend == b.Bend && a.Mode == b.Mode && a.Substeps == b.Substeps && a.Length == b.Length
        && (a.Length != LengthMode.Pbd || a.LengthIterations == b.LengthIterations);

    private static void Write(string output, List<ReportRow> rows, int[] front, int def, bool quick, SolverPath path, int threads)
    {
        string dir = Path.GetDirectoryName(Path.GetFullPath(output))!;
        Directory.CreateDirectory(Path.Combine(dir, "img"));
        var points = rows.ConvertAll(r => new SvgPlot.Point(r.Timing.MicrosecondsPerFrame, r.Error, Group(r.Config), r.Config.Label));
        StabilityCommand.WriteFile(Path.Combine(dir, "img", "error-vs-runtime.svg"), SvgPlot.Scatter(
            "Error against run time (60 Hz, Pareto front dashed, defaults ringed)",
            "run time per frame of ~1000 strands × 16 particles (µs)", "error: worst relative error of the cases (1 = 100 %)", points, front, def));

        var md = new StringBuilder();
        md.Append("# Error against run time\n\n");
        md.Append(F($"Generated by `dotnet run -c Release --project src/HairSim.Cli -- report{(quick ? " --quick" : "")} --out {CliOptions.Shown(output)}` (solver path {path}, {threads} thread(s), {Environment.ProcessorCount} cores). Run times vary from machine to machine and run to run by a few per cent; the errors are deterministic.\n\n"));
        md.Append(Cases);
        var d = rows[def];
        md.Append(F($"**Defaults** ({d.Config.Label}, Sag {new SimulationSettings().Sag}, damping {new SimulationSettings().Damping} per natural time): on the Pareto front: **{(Array.IndexOf(front, def) >= 0 ? "yes" : "no")}**; hanging-strand length error **{Pct(d.LengthError)}** (limit 0.5 %); error {Pct(d.Error)}; {d.Timing.MicrosecondsPerFrame:F0} µs per frame ({d.Timing.ParticleStepsPerSecond / 1e6:F1} M particle-steps/s).\n\n"));
        Findings(md, rows, front, def);
        md.Append("![error vs run time](img/error-vs-runtime.svg)\n\n## Pareto front\n\n");
        Table(md, rows, front, def, front);
        md.Append("\n## All configurations\n\n");
        var all = new int[rows.Count];
        for (int i = 0; i < all.Length; i++) all[i] = i;
        Array.Sort(all, (x, y) => rows[x].Timing.MicrosecondsPerFrame.CompareTo(rows[y].Timing.MicrosecondsPerFrame));
        Table(md, rows, all, def, front);
        HeldShapeSweeps(md, quick);
        VolumeSection(md);
        MeshHeadReport.Append(md, quick);
        StabilityCommand.WriteFile(output, md.ToString());
    }

    /// <summary>
    /// Today's hair volume on the reference scene (there is no hair–hair interaction yet): the outer layer's mean height
    /// above the scalp as grown, settled, and after a head shake, the baseline a volume solver is measured against.
    /// </summary>
    private static void VolumeSection(StringBuilder md)
    {
        md.Append("\n## Hair volume\n\n");
        md.Append("The reference scene under three bend models, without and with hair volume (`VolumeSettings` defaults, docs/volume.md): the outer layer's mean height above the crown (`HairVolume.OuterLayerThickness` with directions more than 0.5 rad above the head's equator, binned 24 × 8; the farthest particle above the head ellipsoid in each bin, averaged). Without volume strands do not push on one another, so what keeps volume is only each strand's own shape: the default rest-shape model holds the groom's lift; the source's triples and limp hair sink towards the scalp.\n\n");
        md.Append("| bend model | volume | as grown (mm) | after 2 s still | after a 3 s head shake and 1 s still |\n|---|---|---:|---:|---:|\n");
        using var threads = ThreadDispatchers.CreateDefault();
        foreach (var bend in new[] { BendModel.RestShape, BendModel.SourceTriples, BendModel.Limp })
            foreach (bool volume in new[] { false, true })
            {
                var g = GroomSettings.Reference();
                var scene = GroomBuilder.BuildScene(g, new SimulationSettings { Bend = bend });
                if (volume) scene.SetComponent(new VolumeSettings());
                var sim = new HairSimulation(scene, dispatcher: threads);
                double Thickness() => HairVolume.OuterLayerThickness(scene.World, g.HeadCenter, g.HeadRadii, 0.5f);
                double grown = Thickness();
                for (int f = 0; f < 120; f++) sim.Step(1f / 60f);
                double settled = Thickness();
                for (int f = 1; f <= 180; f++) sim.Step(1f / 60f, HeadMotion.Shake(f / 60f));
                for (int f = 0; f < 60; f++) sim.Step(1f / 60f, RigidTransform.Identity);
                double shaken = Thickness();
                md.Append(F($"| {bend} | {(volume ? "on" : "off")} | {grown * 1000:F1} | {settled * 1000:F1} ({settled / grown * 100:F0} %) | {shaken * 1000:F1} ({shaken / grown * 100:F0} %) |\n"));
            }
        md.Append("\nTwo crossing sheets (`CrossingSheets`: 20 + 20 limp strands of 16 particles; sheet B falls from 12 % of the strand length onto sheet A lying on a floor, 3 natural seconds, Froude-scaled): wherever a strand of B crosses a strand of A seen from above (about 400 places as dropped), whether B ended at or below A (passed into or through A's layer), and B's mean height above A as a share of the strand length. Volume with the defaults (one pass per `MaxStep` = 1/8 natural time) and with `MaxStep` = 1/32 (the frame stepped in parts of at most 5 ms for 25 cm hair). Fast path.\n\n");
        md.Append("| strand length | frame rate | no volume: B at or below A | defaults: B at or below A | defaults: mean gap | MaxStep 1/32: B at or below A | MaxStep 1/32: mean gap |\n|---|---:|---:|---:|---:|---:|---:|\n");
        foreach (float scale in new[] { 0.04f, 1f, 40f })
            foreach (int hz in new[] { 30, 60, 240 })
            {
                var off = CrossingSheets.Run(null, SolverPath.Fast, hz, scale: scale, dispatcher: threads);
                var on = CrossingSheets.Run(new VolumeSettings(), SolverPath.Fast, hz, scale: scale, dispatcher: threads);
                var fine = CrossingSheets.Run(new VolumeSettings { MaxStep = 1f / 32 }, SolverPath.Fast, hz, scale: scale, dispatcher: threads);
                md.Append(F($"| {0.25 * scale * 100:0.##} cm | {hz} Hz | {off.Sunk} of {off.Crossings} | {on.Sunk} of {on.Crossings} | {Gap(on)} | {fine.Sunk} of {fine.Crossings} | {Gap(fine)} |\n"));
            }
        static string Gap(CrossingResult r) => double.IsNaN(r.MeanGap) ? "–" : F($"{r.MeanGap * 100:F1} %");
    }

    private static string Group(SolverConfiguration c) => c.Bend switch
    {
        BendModel.RestShape => "rest shape",
        BendModel.Limp => "limp",
        _ => $"{(c.Mode == ShapeMatchMode.Muller ? "Müller" : "literal")}, {c.LengthLabel}",
    };

    /// <summary>
    /// The defaults' held shapes over every scale, frame rate and substep count, on both paths; and the same head shake
    /// at 1 cm, 25 cm and 10 m (Froude-scaled) compared with the 25 cm run, for the defaults and the source's scheme.
    /// </summary>
    private static void HeldShapeSweeps(StringBuilder md, bool quick)
    {
        float[] lengths = quick ? [0.01f, 10f] : [0.01f, 0.25f, 10f];
        int[] rates = quick ? [30, 240] : [30, 60, 240];
        int[] substeps = quick ? [1, 16] : [1, 4, 16];
        var shapes = Enum.GetValues<HeldShape>();
        var paths = new[] { SolverPath.Reference, SolverPath.Fast };
        var cases = new List<(HeldShape Shape, float Length, int Hz, int Substeps, SolverPath Path)>();
        foreach (var shape in shapes) foreach (float l in lengths) foreach (int hz in rates) foreach (int n in substeps) foreach (var p in paths) cases.Add((shape, l, hz, n, p));
        var results = new HeldShapeResult[cases.Count];
        var progress = new Progress("held shapes", cases.Count);
        int done = 0;
        Parallel.For(0, cases.Count, i =>
        {
            var c = cases[i];
            results[i] = HeldShapeCases.Run(c.Shape, c.Length, 16, c.Hz, new SimulationSettings { Path = c.Path, Substeps = c.Substeps });
            lock (progress) progress.Report(++done, c.Shape.ToString());
        });
        md.Append("\n## Held shapes at every scale and frame rate\n\n");
        md.Append(F($"A strand of 16 particles grown in a rest shape — straight and horizontal (cantilever), a quarter arc rising from horizontal to vertical, a hanging curl of two turns — released under 1 g with the head still and the **default settings** (only the substep count varied; guards on). Run for 3 s × √(L / 0.25 m) (the same motion at every size under Froude scaling), measured over the last tenth of the frames: the farthest particle from its rest place and the tip, as shares of the strand length; the largest speed left in the velocity buffers, in units of √(g·L); the worst length drift. {cases.Count} runs.\n\n"));
        md.Append("| shape | path | worst particle, min … max | tip, max | spread across scales and rates | largest speed at rest (√(g·L)) | length drift |\n|---|---|---:|---:|---:|---:|---:|\n");
        foreach (var shape in shapes)
            foreach (var p in paths)
            {
                double lo = double.MaxValue, hi = 0, tip = 0, speed = 0, drift = 0;
                for (int i = 0; i < cases.Count; i++)
                {
                    if (cases[i].Shape != shape || cases[i].Path != p) continue;
                    var r = results[i];
                    lo = Math.Min(lo, r.WorstError); hi = Math.Max(hi, r.WorstError); tip = Math.Max(tip, r.TipError);
                    speed = Math.Max(speed, r.MaxSpeedAtRest); drift = Math.Max(drift, r.LengthError);
                }
                md.Append(F($"| {shape} | {p} | {Pct(lo)} … {Pct(hi)} | {Pct(tip)} | {Pct(hi - lo)} | {speed:0.0e0} | {drift:0.0e0} |\n"));
            }
        md.Append("\nTarget: within 2 % of the length (tip and worst particle), varying by less than 1 % of the length across scales and rates. Per scale and rate (fast path, worst particle over the three shapes, substeps 1 / 4 / 16):\n\n");
        md.Append("| hair length | " + string.Join(" | ", Array.ConvertAll(rates, r => r + " Hz")) + " |\n|---|" + string.Concat(Enumerable.Repeat("---:|", rates.Length)) + "\n");
        foreach (float l in lengths)
        {
            md.Append(l >= 1f ? F($"| {l:0.##} m |") : F($"| {l * 100:0.##} cm |"));
            foreach (int hz in rates)
            {
                var cells = new List<string>();
                foreach (int n in substeps)
                {
                    double worst = 0;
                    for (int i = 0; i < cases.Count; i++)
                        if (cases[i].Length == l && cases[i].Hz == hz && cases[i].Substeps == n && cases[i].Path == SolverPath.Fast) worst = Math.Max(worst, results[i].WorstError);
                    cells.Add(Pct(worst));
                }
                md.Append(" " + string.Join(" / ", cells) + " |");
            }
            md.Append('\n');
        }

        // What each Sag looks like.
        md.Append("\n## What Sag looks like\n\n");
        md.Append("Each shape at 25 cm and 60 Hz (any other length or rate gives the same shares, see above) with Sag varied, everything else default. Cantilever: tip drop below its rest place; arc and curl: farthest particle from its rest place; shares of the length.\n\n");
        md.Append("| Sag | cantilever tip drop | upward arc | curl | looks like |\n|---:|---:|---:|---:|---|\n");
        foreach (var (sag, look) in new (float, string)[] { (0f, "rigid: wire"), (0.003f, "lacquered"), (0.01f, "styled, holds (default)"), (0.03f, "styled, gives a little"), (0.1f, "soft, droops"), (0.3f, "very soft"), (1f, "nearly limp") })
        {
            var st = new SimulationSettings { Sag = sag };
            var c = HeldShapeCases.Run(HeldShape.Cantilever, 0.25f, 16, 60, st);
            var arc = HeldShapeCases.Run(HeldShape.UpwardArc, 0.25f, 16, 60, st);
            var curl = HeldShapeCases.Run(HeldShape.Curl, 0.25f, 16, 60, st);
            md.Append(F($"| {sag} | {Pct(c.TipError)} | {Pct(arc.WorstError)} | {Pct(curl.WorstError)} | {look} |\n"));
        }

        // The same shake at three sizes.
        md.Append("\n## The same head shake on a doll, a person and a giant\n\n");
        md.Append("The canonical small groom (24 strands of 25 cm on the reference head, draped) and the head shake, scaled to 1 cm hair (× 0.04) and to 10 m hair (× 40) in length and by √ of that in time (Froude scaling), compared with the 25 cm run after 2 s × √scale: every particle's position divided by the scale; the largest difference as a share of the strand length. **Same motion**: the frame rate scaled too (60 Hz × 1/√scale: 300 Hz for the doll, 9.5 Hz for the giant), so every size takes the same steps in its own time: what is left is what the model does differently at another size. **Same frame rate**: every size at 60 Hz, so the doll takes 5 times coarser steps in its own time and the giant 6 times finer: the shake's contact-rich motion then differs as it does between frame rates.\n\n");
        md.Append("| model | same motion: 1 cm vs 25 cm | same motion: 10 m vs 25 cm | 60 Hz: 1 cm vs 25 cm | 60 Hz: 10 m vs 25 cm |\n|---|---:|---:|---:|---:|\n");
        var models = new (string Name, SimulationSettings Settings)[]
        {
            ("defaults (rest shape)", new SimulationSettings()),
            ("the source's triples (α = 1, follow-the-leader)", new SimulationSettings { Bend = BendModel.SourceTriples }),
        };
        foreach (var (name, st) in models)
        {
            var person = HeldShapeCases.ScaledShake(1f, 60, st);
            double Froude(float k) => HeldShapeCases.ShapeDifference(HeldShapeCases.ScaledShake(k, 60 / Math.Sqrt(k), st), person);
            double Fixed(float k) => HeldShapeCases.ShapeDifference(HeldShapeCases.ScaledShake(k, 60, st), person);
            md.Append(F($"| {name} | {Pct(Froude(0.04f))} | {Pct(Froude(40f))} | {Pct(Fixed(0.04f))} | {Pct(Fixed(40f))} |\n"));
        }
        md.Append("\n");
    }

    /// <summary>What the rows say about the source's stretch and the choice of defaults (numbers from this run).</summary>
    private static void Findings(StringBuilder md, List<ReportRow> rows, int[] front, int def)
    {
        ReportRow? Find(float alpha, int substeps, LengthMode length) =>
            rows.Find(r => r.Config.Bend == BendModel.SourceTriples && r.Config.Mode == ShapeMatchMode.Muller && r.Config.Alpha == alpha && r.Config.Substeps == substeps && r.Config.Length == length);
        var one = Find(1f, 1, LengthMode.None);
        var four = Find(1f, 4, LengthMode.None);
        var sixteen = Find(1f, 16, LengthMode.None);
        var source4 = Find(1f, 4, LengthMode.FollowTheLeader);
        var d = rows[def];
        md.Append("## Findings\n\n");
        if (one != null && four != null && sixteen != null)
            md.Append(F($"- **The source's stretch.** Müller α = 1 without a length pass, hanging strand at 60 Hz: it settles at {1 + one.Hanging.LengthError:0.00}× its rest length with one substep, {1 + four.Hanging.LengthError:0.000}× with 4 and {1 + sixteen.Hanging.LengthError:0.000}× with 16 (an independent measurement of the source's scheme: 2.3×, 1.08×, 1.005×; same trend, our goal averaging and settling run differ). Substeps alone need 16 to come near 0.5 % and still stretch {Pct(sixteen.Shake.PeakStretch)} while the head shakes.\n"));
        var pbd8 = rows.Find(r => r.Config.Bend == BendModel.SourceTriples && r.Config.Mode == ShapeMatchMode.Muller && r.Config.Alpha == 1f && r.Config.Substeps == 8 && r.Config.Length == LengthMode.Pbd && r.Config.LengthIterations == 4);
        var ftl16 = Find(1f, 16, LengthMode.FollowTheLeader);
        if (four != null)
            md.Append(F($"- **Follow-the-leader** (the source's scheme) holds the hanging length exactly ({Pct(source4?.LengthError ?? double.NaN)}) at any substep count; at 4 substeps it costs {(source4?.Timing.MicrosecondsPerFrame ?? double.NaN) / four.Timing.MicrosecondsPerFrame:0.00}× the time of no length pass."));
        if (pbd8 != null)
            md.Append(F($" PBD with 4 iterations needs 8 substeps to come under 0.5 % (length error {Pct(pbd8.LengthError)}); it costs {pbd8.Timing.MicrosecondsPerFrame / d.Timing.MicrosecondsPerFrame:0.0}× the defaults and stretches {Pct(pbd8.Shake.PeakStretch)} in the shake."));
        md.Append("\n");
        var rest1 = rows.Find(r => r.Config.Bend == BendModel.RestShape && r.Config.Substeps == 1);
        var limp4 = rows.Find(r => r.Config.Bend == BendModel.Limp && r.Config.Substeps == 4);
        md.Append(F($"- **Defaults** (the rest-shape bend model, Sag 0.01, 4 substeps): on the front{(Array.IndexOf(front, def) >= 0 ? "" : " — NOT on the front in this run")}, held shapes {Pct(d.Held.WorstError)} of the length (worst particle; Sag 0.01 asks for a 1 % tip sag of a horizontal strand), hanging length error {Pct(d.LengthError)}, shake peak stretch {Pct(d.Shake.PeakStretch)}, teleport {Pct(d.Teleport.PeakStretch)}."));
        if (rest1 != null)
            md.Append(F($" With one substep ({rest1.Timing.MicrosecondsPerFrame:F0} against {d.Timing.MicrosecondsPerFrame:F0} µs, guards off as in every row here) the held shapes come out at {Pct(rest1.Held.WorstError)} and the shake stretches {Pct(rest1.Shake.PeakStretch)}: the fall per substep is then 16 % of a segment, past the 5 % the guards keep to."));
        if (source4 != null)
            md.Append(F($" The source's scheme at the same substeps (Müller α = 1 ×4 FTL, {source4.Timing.MicrosecondsPerFrame:F0} µs) cannot hold a style: its held shapes end {Pct(source4.Held.WorstError)} of the length from their rest places"));
        if (limp4 != null) md.Append(F($", as far as limp hair ({Pct(limp4.Held.WorstError)})"));
        md.Append(". The default model costs more per frame on this small groom; docs/performance.md times the reference scene.\n");
        if (pbd8 != null)
            md.Append(F($"\n- **Catenary.** With both ends pinned, follow-the-leader leaves the last edge to take all the slack (shape error {Pct(d.Catenary.ShapeError)} of L with the defaults); PBD settles on the analytic chain ({Pct(pbd8.Catenary.ShapeError)} with {pbd8.Config.LengthLabel} at 8 substeps). Hair has no second pin, so this does not rank, but a tool that pins tips should use PBD.\n"));
        int leftInside = rows.FindAll(r => r.Collision.MaxInside > 0).Count, nonFinite = rows.FindAll(r => r.NonFinite > 0).Count;
        md.Append(F($"- **Collision and finiteness.** Configurations that left a particle inside the head after a frame: {leftInside} of {rows.Count} (the push-out runs last in every substep); configurations with a non-finite value: {nonFinite}.\n\n"));
    }

    private static void Table(StringBuilder md, List<ReportRow> rows, int[] order, int def, int[] front)
    {
        md.Append("| configuration | µs / frame | M particle-steps/s | error | held shape (worst particle) | hanging length | straightness | catenary shape | catenary length | pendulum period | pendulum energy lost | penetration (mm) / inside | shake peak stretch | shake tip drop vs converged (mm) | teleport peak stretch | non-finite |\n");
        md.Append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
        foreach (int i in order)
        {
            var r = rows[i];
            string name = (i == def ? "**" + r.Config.Label + "** (defaults)" : r.Config.Label) + (Array.IndexOf(front, i) >= 0 ? " ◆" : "");
            string conv = r.ShakeConverged.LastChange < 1e-3
                ? F($"{r.ShakeConverged.Error * 1000:F1} (ref ×{r.ShakeConverged.ReferenceSubsteps})")
                : F($"{r.ShakeConverged.Error * 1000:F1} (no limit: Δ {r.ShakeConverged.LastChange * 1000:F1} at ×{r.ShakeConverged.ReferenceSubsteps})");
            md.Append(F($"| {name} | {r.Timing.MicrosecondsPerFrame:F0} | {r.Timing.ParticleStepsPerSecond / 1e6:F1} | {Pct(r.Error)} | {Pct(r.Held.WorstError)} | {Pct(r.Hanging.LengthError)} | {Pct(r.Hanging.Straightness)} | {Pct(r.Catenary.ShapeError)} | {Pct(r.Catenary.LengthError)} | {(r.Pendulum.Defined ? Pct(r.Pendulum.PeriodError) : r.Config.Bend == BendModel.RestShape ? "held root" : "no rod")} | {(r.Pendulum.Defined ? Pct(1 - r.Pendulum.EnergyRatio) : "—")} | {r.Collision.MaxPenetration * 1000:F2} / {r.Collision.MaxInside} | {Pct(r.Shake.PeakStretch)} | {conv} | {Pct(r.Teleport.PeakStretch)} | {r.NonFinite} |\n"));
        }
    }

    private const string Cases = """
        Every configuration runs the same canonical cases at 60 Hz, with the default settings apart from what the
        configuration names (bend model, α, shape-matching mode, substeps, length pass), and **with the stability guards off**, so
        each row measures exactly that configuration (the guards would raise 1 or 2 substeps to 4 at 60 Hz; with the
        defaults at 60 Hz they change nothing in these cases). Strands are 0.25 m, 16 particles.

        | case | what is measured | against |
        |---|---|---|
        | hanging strand | released horizontal, measured after 5 s: length error \|Σl / L − 1\|, straightness = largest horizontal distance of a particle from the vertical through the root / L | analytic: a vertical line of length L |
        | catenary | chain pinned at both ends 0.2 m apart (tip pinned with InvMass = 0), rest shape = the answer, starts with half the sag; after 5 s the largest particle distance to the answer / L, and the length error | analytic: the equilibrium of 15 equal links with equal joint weights (slope of link j ∝ j − 7), which converges to y = a·cosh(x/a) as links are added (unit-tested) |
        | pendulum | 2-particle strand (pivot → mass L = 0.25 m), released at 0.1 rad, damping off; period from 8 upward zero crossings, energy lost between the first and last | analytic: T = 2π / (√(g/L) / (1 + θ0²/16)) = 1.0036 s; no energy loss. Without a length pass nothing holds the mass (“no rod”) |
        | collision sweep | 24 strands on the head ellipsoid; the head sweeps ±8 cm and nods ±30° at 1 Hz for 3 s; after every frame the deepest penetration and free particles inside | analytic: 0 |
        | head shake | same groom, head shakes ±40° at 1.5 Hz and bobs 3 cm for 2 s: peak edge stretch of any frame; mean tip drop below the root (time average) | stretch: 0; tip drop: the same case converged — substeps doubled until it changes by < 1 mm, at most 256 |
        | teleport | settles 0.5 s, the head jumps 1 m and turns 120° in one frame, then 1 s still: peak stretch, non-finite values | 0 |
        | held shapes | one strand each grown straight and horizontal, as a quarter arc rising to vertical, and as a hanging two-turn curl, released with the head still for 3 s: the farthest particle from its rest place / L over the last tenth of the frames (worst of the three) | the rest shape; the rest-shape model's own answer is a sag of Sag × L for the horizontal strand |

        Under the default bend model the strands hang as grown (draped) and a hanging strand's rest pose is vertical;
        the pendulum is no free pendulum there (its root holds the strand's direction: “held root”).

        **Error** (the plot's y axis and the front) is the error of hair with free tips: the worst of the hanging
        length error, straightness, shake and teleport peak stretch, pendulum period error (where there is a rod) and
        the held shapes.
        Listed beside it but not ranked:
        - the catenary: a second pin, which hair does not have (the case pins the tip through InvMass = 0).
          Follow-the-leader cannot hold it: its root-to-tip sweep never pulls towards the far pin, so the last edge
          takes all the slack; PBD can;
        - the pendulum's energy loss over 8 s with damping off: every position-based length pass removes energy; with
          the default damping (0.32 per natural time, 2/s on these 25 cm strands) the hair loses 1 − e^(−2·8) ≈ 100 % of its energy in the same time anyway;
        - the shake against its converged run: Müller's α acts per substep, so halving the step makes the hair stiffer
          and the shake has no step-independent limit (the tip drop keeps moving by about 1–5 cm per halving even at
          256 substeps); only the literal force, whose α is a rate in 1/s², converges (without a length pass).

        **Run time** is the time per frame of ~1000 strands × 16 particles on the head (collision on) during the shake,
        Release build, one configuration at a time after all errors were measured. Configurations are timed in rounds
        over the whole list: a first round is thrown away (it lets the JIT reach its optimised code; without it the
        first configurations timed came out 3–10× slow), then 2 rounds in alternating order; in each, a configuration
        gets 10 warm-up frames and 3 batches of 20 frames, and its fastest batch of all counts (other work on the
        machine only slows a batch down). Configurations that differ only in α run the same code (α is a multiplier)
        and share one run time, the fastest batch of any of them; among them only the error decides.
        `--quick`: one timed round, batches of 10 frames.
        ◆ marks the Pareto front: no other configuration is both faster and more accurate.


        """;

    private static string F(FormattableString s) => s.ToString(CultureInfo.InvariantCulture);

    /// <summary>What the columns of <see cref="Line"/> are.</summary>
    private const string Legend =
        "columns: configuration; run time per frame (µs); err = worst error of all cases; held = held-shape error; len / straight = hanging strand's length error and straightness; " +
        "cat / catlen = catenary's shape and length errors; T / E = pendulum's period and energy errors; pen … in = collision sweep's deepest penetration (mm) and most particles inside; " +
        "shake = peak stretch in the head shake; conv = distance from the converged shake (mm) @ its substeps, d = last change (mm); tele = peak stretch after a teleport; nf = non-finite values";

    private static string Line(ReportRow r) => string.Create(CultureInfo.InvariantCulture,
        $"{r.Config.Label,-26} {r.Timing.MicrosecondsPerFrame,9:F0} µs  err {Pct(r.Error),8}  held {Pct(r.Held.WorstError),8}  len {Pct(r.Hanging.LengthError),8} straight {Pct(r.Hanging.Straightness),8} cat {Pct(r.Catenary.ShapeError),8} catlen {Pct(r.Catenary.LengthError),8} T {Pct(r.Pendulum.PeriodError),8} E {Pct(r.Pendulum.EnergyError),8} pen {r.Collision.MaxPenetration * 1000,6:F2}mm in {r.Collision.MaxInside,3} shake {Pct(r.Shake.PeakStretch),8} conv {r.ShakeConverged.Error * 1000,7:F2}mm@{r.ShakeConverged.ReferenceSubsteps} d{r.ShakeConverged.LastChange*1000:F2} tele {Pct(r.Teleport.PeakStretch),8} nf {r.NonFinite}");

    internal static string Pct(double v) => !double.IsFinite(v) ? "—"
        : v >= 1 ? string.Create(CultureInfo.InvariantCulture, $"{v * 100:0} %")
        : v >= 0.1 ? string.Create(CultureInfo.InvariantCulture, $"{v * 100:0.#} %")
        : string.Create(CultureInfo.InvariantCulture, $"{v * 100:0.###} %");
}
