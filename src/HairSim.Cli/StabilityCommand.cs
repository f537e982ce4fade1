using System.CommandLine;
using System.Globalization;
using System.Text;
using HairSim;
using HairSim.Measurement;

namespace HairSim.Cli;

/// <summary>
/// The stability map: stiff and extreme cases (α, time step, particles per strand, gravity, teleports, fast spins,
/// degenerate starting states) on a small groom; for each cell stable or not and the worst stretch seen.
/// </summary>
public static class StabilityCommand
{
    public const string Description = "The stability map: Sag, hair length, α, time step, particles per strand, gravity, teleports, fast spins and degenerate starts, stable or not and the worst stretch in each cell: a Markdown report with pictures.";

    public static Command Create()
    {
        var output = CliOptions.Text("--out", "the report to write (its pictures go to img/ beside it)", "out/stability.md", "file.md");
        var quick = CliOptions.Switch("--quick", "a short run: smaller grids");
        var path = CliOptions.SolverPathOption();
        var command = new Command("stability", Description) { output, quick, path };
        command.SetAction(p => Execute(CliOptions.CheckOutputFile(p.GetValue(output)!, "--out"), p.GetValue(quick), CliOptions.ToSolverPath(p.GetValue(path))));
        return command;
    }

    private const string Green = "#81c784", Orange = "#ffb74d", Red = "#e57373";

    /// <summary>One map: a grid of cells, each run with the settings the row and column give.</summary>
    private sealed record Grid(string Id, string Title, string RowAxis, string[] Rows, string ColumnAxis, string[] Columns, Func<int, int, StabilityResult> Cell);

    public static int Execute(string output, bool quick, SolverPath path)
    {

        var grids = Grids(quick, path);
        var results = new List<StabilityResult[,]>();
        long cells = 0, done = 0;
        foreach (var g in grids) cells += g.Rows.Length * g.Columns.Length;
        var progress = new Progress("stability", cells);
        var clock = System.Diagnostics.Stopwatch.StartNew();
        foreach (var g in grids)
        {
            var r = new StabilityResult[g.Rows.Length, g.Columns.Length];
            Parallel.For(0, g.Rows.Length * g.Columns.Length, new ParallelOptions { MaxDegreeOfParallelism = Environment.ProcessorCount }, k =>
            {
                int row = k / g.Columns.Length, col = k % g.Columns.Length;
                r[row, col] = g.Cell(row, col);
                lock (progress) progress.Report(++done, g.Id);
            });
            results.Add(r);
        }
        clock.Stop();
        Write(output, grids, results, quick, path, clock.Elapsed.TotalSeconds);
        int nonFinite = 0;
        foreach (var r in results) foreach (var c in r) if (!c.Finite) nonFinite++;
        Console.WriteLine($"{cells} cells in {clock.Elapsed.TotalSeconds:F0} s; cells with a non-finite value: {nonFinite}; written {output}");
        if (nonFinite > 0) Console.Error.WriteLine($"error: {nonFinite} cells of the map produced non-finite values");
        return nonFinite == 0 ? ExitCodes.Ok : ExitCodes.NonFinite;
    }

    private static SimulationSettings Defaults(SolverPath path) => new() { Path = path };

    /// <summary>The source's triple shape matching with the other defaults (the grids over α).</summary>
    private static SimulationSettings Source(SolverPath path) => new() { Path = path, Bend = BendModel.SourceTriples };

    private static readonly float[] Dts = [1 / 960f, 1 / 480f, 1 / 240f, 1 / 120f, 1 / 60f, 1 / 30f, 1 / 15f];

    private static List<Grid> Grids(bool quick, SolverPath path)
    {
        float[] dts = quick ? [1 / 240f, 1 / 60f, 1 / 15f] : Dts;
        string[] dtLabels = Array.ConvertAll(dts, d => $"1/{MathF.Round(1 / d):0} s");
        float[] alphas = quick ? [0f, 1f, 4f] : [0f, 0.5f, 1f, 1.5f, 2f, 3f, 4f];
        string[] alphaLabels = Array.ConvertAll(alphas, x => F($"α = {x:0.##}"));
        var grids = new List<Grid>();

        float[] sags = quick ? [0f, 0.01f, 1f] : [0f, 0.003f, 0.01f, 0.03f, 0.1f, 0.3f, 1f];
        grids.Add(new Grid("rest-sag-dt", "Defaults (rest-shape bend model, 4 substeps, guards on): Sag × frame time, head shake",
            "Sag", Array.ConvertAll(sags, x => F($"Sag = {x:0.###}")), "frame time dt", dtLabels, (r, c) =>
            {
                var s = Defaults(path); s.Sag = sags[r];
                return StabilityMap.Run(s, dts[c], 16, StabilityScenario.Shake);
            }));
        float[] scales = quick ? [0.04f, 1f, 40f] : [0.04f, 0.2f, 1f, 4f, 40f];
        grids.Add(new Grid("rest-scale-dt", "Defaults at every size: hair length (groom and head motion scaled, Froude) × frame time, head shake",
            "hair length", Array.ConvertAll(scales, x => F($"{25 * x:0.##} cm")), "frame time dt", dtLabels, (r, c) =>
                StabilityMap.Run(Defaults(path), dts[c], 16, StabilityScenario.Shake, scale: scales[r])));
        grids.Add(new Grid("muller-alpha-dt", "The source's triples with the other defaults (Müller, 4 substeps, follow-the-leader): α × frame time, head shake",
            "α", alphaLabels, "frame time dt", dtLabels, (r, c) =>
            {
                var s = Source(path); s.Alpha = alphas[r];
                return StabilityMap.Run(s, dts[c], 16, StabilityScenario.Shake);
            }));
        grids.Add(new Grid("source-alpha-dt", "The source's scheme, faithfully (Müller, 1 substep, no length pass, guards off): α × frame time, head shake",
            "α", alphaLabels, "frame time dt", dtLabels, (r, c) =>
            {
                var s = Source(path); s.Alpha = alphas[r]; s.Substeps = 1; s.Length = LengthMode.None; s.Guards = false;
                return StabilityMap.Run(s, dts[c], 16, StabilityScenario.Shake);
            }));
        grids.Add(new Grid("source-guarded-alpha-dt", "The source's scheme with the guards on (α clamped to 1, gravity's fall per substep ≤ 5 % of a segment, head travel ≤ 1.2 segments per substep)",
            "α", alphaLabels, "frame time dt", dtLabels, (r, c) =>
            {
                var s = Source(path); s.Alpha = alphas[r]; s.Substeps = 1; s.Length = LengthMode.None;
                return StabilityMap.Run(s, dts[c], 16, StabilityScenario.Shake);
            }));
        float[] rates = quick ? [10f, 1000f] : [1f, 10f, 100f, 1000f];
        grids.Add(new Grid("literal-alpha-dt", "The source's literal force, faithfully (1 substep, no length pass, guards off): α (1/s²) × frame time, head shake",
            "α (1/s²)", Array.ConvertAll(rates, x => F($"α = {x:0}")), "frame time dt", dtLabels, (r, c) =>
            {
                var s = Source(path); s.Mode = ShapeMatchMode.LiteralForce; s.Alpha = rates[r]; s.Substeps = 1; s.Length = LengthMode.None; s.Guards = false;
                return StabilityMap.Run(s, dts[c], 16, StabilityScenario.Shake);
            }));
        grids.Add(new Grid("literal-defaults-alpha-dt", "Literal force with the other defaults (4 substeps, follow-the-leader, guards on): α (1/s²) × frame time, head shake",
            "α (1/s²)", Array.ConvertAll(rates, x => F($"α = {x:0}")), "frame time dt", dtLabels, (r, c) =>
            {
                var s = Source(path); s.Mode = ShapeMatchMode.LiteralForce; s.Alpha = rates[r];
                return StabilityMap.Run(s, dts[c], 16, StabilityScenario.Shake);
            }));
        int[] particles = quick ? [2, 16, 512] : [2, 4, 8, 16, 32, 64, 128, 256, 512];
        float[] gravity = quick ? [1f, 100f] : [1f, 3f, 10f, 30f, 100f];
        grids.Add(new Grid("particles-gravity", "Defaults at 60 Hz: particles per strand × gravity, head shake",
            "particles", Array.ConvertAll(particles, p => p.ToString(CultureInfo.InvariantCulture)), "gravity", Array.ConvertAll(gravity, g => F($"× {g:0}")), (r, c) =>
            {
                var s = Defaults(path); s.Gravity *= gravity[c];
                return StabilityMap.Run(s, 1 / 60f, particles[r], StabilityScenario.Shake);
            }));
        var scenarios = Enum.GetValues<StabilityScenario>();
        var columns = new (string Label, Func<SimulationSettings> Make, float Dt)[]
        {
            ("defaults 60 Hz", () => Defaults(path), 1 / 60f),
            ("defaults 15 Hz", () => Defaults(path), 1 / 15f),
            ("guards off 60 Hz", () => { var s = Defaults(path); s.Guards = false; return s; }, 1 / 60f),
            ("guards off 15 Hz", () => { var s = Defaults(path); s.Guards = false; return s; }, 1 / 15f),
            ("gravity × 100", () => { var s = Defaults(path); s.Gravity *= 100f; return s; }, 1 / 60f),
            ("source, guards off", () => { var s = Source(path); s.Substeps = 1; s.Length = LengthMode.None; s.Guards = false; return s; }, 1 / 60f),
            ("literal α=1000", () => { var s = Source(path); s.Mode = ShapeMatchMode.LiteralForce; s.Alpha = 1000f; return s; }, 1 / 60f),
            ("Müller α = 4, guards off", () => { var s = Source(path); s.Alpha = 4f; s.Guards = false; return s; }, 1 / 60f),
        };
        grids.Add(new Grid("extreme", "Extreme cases × solver settings (16 particles per strand)",
            "case", Array.ConvertAll(scenarios, x => x.ToString()), "settings", Array.ConvertAll(columns, c => c.Label), (r, c) =>
                StabilityMap.Run(columns[c].Make(), columns[c].Dt, 16, scenarios[r])));
        return grids;
    }

    private static void Write(string output, List<Grid> grids, List<StabilityResult[,]> results, bool quick, SolverPath path, double seconds)
    {
        string dir = Path.GetDirectoryName(Path.GetFullPath(output))!;
        string imgDir = Path.Combine(dir, "img");
        Directory.CreateDirectory(imgDir);
        var md = new StringBuilder();
        md.Append("# Stability map\n\n");
        md.Append(F($"Generated by `dotnet run -c Release --project src/HairSim.Cli -- stability{(quick ? " --quick" : "")} --out {CliOptions.Shown(output)}` (solver path {path}; {seconds:F0} s on {Environment.ProcessorCount} cores).\n\n"));
        md.Append(Definition);
        int unstable = 0, nonFinite = 0, total = 0;
        foreach (var r in results) foreach (var c in r) { total++; if (!c.Stable) unstable++; if (!c.Finite) nonFinite++; }
        md.Append(F($"**Summary:** {total} cells, {total - unstable} stable, {unstable} not stable, {nonFinite} with a non-finite value.\n\n"));
        for (int g = 0; g < grids.Count; g++)
        {
            var grid = grids[g];
            var r = results[g];
            string svg = $"stability-{grid.Id}.svg";
            var cells = new SvgPlot.Cell[grid.Rows.Length, grid.Columns.Length];
            for (int i = 0; i < grid.Rows.Length; i++)
                for (int j = 0; j < grid.Columns.Length; j++)
                    cells[i, j] = new SvgPlot.Cell(Colour(r[i, j]), Short(r[i, j]), Detail(r[i, j]));
            WriteFile(Path.Combine(imgDir, svg), SvgPlot.HeatMap(grid.Title, grid.RowAxis, grid.Rows, grid.ColumnAxis, grid.Columns, cells,
                [(Green, "stable (worst edge elongation shown; ↓ = compression ≥ 50 %)"), (Orange, "finite, calm, outside the head, but stretched ≥ 50 %"), (Red, "unstable: non-finite, energy not dying down, or left inside the head")]));
            md.Append($"## {grid.Title}\n\n![{grid.Id}](img/{svg})\n\n");
            md.Append($"| {grid.RowAxis} \\ {grid.ColumnAxis} | {string.Join(" | ", grid.Columns)} |\n|---|{string.Concat(Enumerable.Repeat("---|", grid.Columns.Length))}\n");
            for (int i = 0; i < grid.Rows.Length; i++)
            {
                md.Append($"| {grid.Rows[i]} |");
                for (int j = 0; j < grid.Columns.Length; j++) md.Append($" {Mark(r[i, j])} {Short(r[i, j])} |");
                md.Append('\n');
            }
            md.Append('\n');
        }
        WriteFile(output, md.ToString());
    }

    private const string Definition = """
        Each cell runs a small groom (6 sheets × 2 strands, 0.25 m strands, draped) on the reference head ellipsoid with the
        default settings (the rest-shape bend model, docs/styles.md) except what the row and column change; the grids over α
        run the source's triple shape matching. The head moves (shake, teleport, spin) and then holds still for the last
        second; every value is measured after every frame. In the grid over hair length the groom, the head and the head's
        motion are scaled (lengths × k, times × √k: the same motion at another size) and the frame time is as given.

        Extreme cases: Shake (head shakes ±40° at 1.5 Hz, 2 s); Teleport (the head jumps 1 m and turns 120° in one
        frame: carried rigidly); NearTeleport (jumps 0.45 m and turns 55° in one frame, just under the teleport limits of
        0.47 m — twice the small groom's reach — and 60°); FastSpin (5 turns/s for 2 s, then stops dead); VeryFastSpin (20 turns/s: at 60 Hz that is 120°
        a frame, so every frame counts as a teleport and the hair turns rigidly); ZeroLengthEdges (every free particle
        starts on its root); CoincidentParticles (particles start in coincident pairs); StartInsideHead (free particles
        start scattered inside the head ellipsoid).

        **Stable** means all of:
        1. every position and velocity stays finite;
        2. no edge is ever stretched by 50 % or more (l / l0 − 1 < 0.5 after every frame). Compression is not counted
           (hair pushed against the head bunches up; it does not fly apart), but where an edge was compressed by 50 % or
           more the cell shows it as ↓ and the percentage;
        3. no free particle is inside a collider after any frame;
        4. the energy dies down once the head stops: the mean kinetic energy of the last 0.5 s is at most 0.9 × that of
           the 0.5 s before, or below 1e-4 J/kg (hair at rest; both scaled with the size in the grid over hair length).

        Guards (SimulationSettings.Guards, on by default; StabilityGuards.cs, applied in HairPipeline.Step to the copy of
        the settings every system reads, so the fast path inherits them):
        - **α clamp**: in Müller mode α above 1 is used as 1 (α = 2 reverses each particle's offset from its goal every
          substep; above 2 it grows). Without it: the source's scheme at α = 4 never calms down (✗ E↑ in the grid "The
          source's scheme, faithfully").
        - **Gravity's fall per substep ≤ MaxFallPerSubstep** (5 % of the groom's mean segment, h²·g ≤ 0.05·ℓ): a long frame,
          or small hair, gets more substeps (25 cm hair: substeps of at most 9.2 ms). This is the scale-free form of the
          former absolute limit of 1/60 s per substep (MaxSubstep, now off by default). Without a limit: the source's
          scheme at α = 0.5 and 1/30 s never calms down.
        - **Head travel ≤ MaxHeadTravel per substep** (1.2 mean segments: 2 cm on the reference groom, measured at the
          hair's reach): a head that jumps just under the teleport limits gets enough substeps that the collider does not
          sweep deep into the hair in one substep. Without it the source's scheme tears edges in NearTeleport (columns
          "guards off" of the extreme cases).
        - Already in the core and kept: the speed limit MaxSpeed (25 natural speeds √(g·L): 40 m/s for 25 cm hair), and the
          teleport handling (a jump over TeleportDistance, 2 × the hair's reach, or TeleportAngle carries the hair rigidly).
        Not changed by the guards, because it is the user's model and not a numerical failure: α = 0 with no length pass
        has nothing holding a strand together, so its free particles fall (at most at MaxSpeed) and never stop (✗ E↑).
        The source's scheme stays stretchy with the guards (orange): only a length pass holds length.
        The literal force is not guarded: it is not the default, Validate caps its α at 1000/s², and nowhere in the map
        did it blow up; its failure is softness (without a length pass it stretches many times over, and at α ≤ 10/s² its
        strands are still stretching when the run ends, which the energy test marks ✗).
        Known limitation, not counted as unstable: strands of 64 particles and more (edges of 4 mm and less) get edges
        compressed by 50–97 % where the head's radial push-out puts neighbouring particles on nearly the same surface
        point (↓ in the particles × gravity grid); the strand stays finite, outside the head and, up to 256 particles, calm.
        At 512 particles (1 mm edges) and gravity × 100 the compressed strands never quite settle: after the head stops
        they keep moving at a steady energy, on the reference path as on the fast one (seen in a longer run outside this
        map), so whether the energy test passes there depends on the last bits of the arithmetic (it passed before the
        bend sweep's fused roundings of the ninth performance pass, docs/performance.md).

        Cells show the worst edge elongation seen. ✓ stable, ~ only the stretch limit failed (finite and calm: the source's
        stretchy hair), ✗ unstable (non-finite, energy not dying down, or left inside the head; the reason is given).


        """;

    private static string Colour(StabilityResult r) => r.Stable ? Green : r.OnlyStretch ? Orange : Red;
    private static string Mark(StabilityResult r) => r.Stable ? "✓" : r.OnlyStretch ? "~" : "✗";

    private static string Short(StabilityResult r)
    {
        if (!r.Finite) return "NaN";
        double e = r.WorstElongation;
        string s = e >= 10 ? F($"{e * 100:0} %") : F($"{e * 100:0.#} %");
        if (r.WorstCompression >= StabilityResult.StretchLimit) s += F($" ↓{r.WorstCompression * 100:0}");
        if (r.MaxInside > 0) s += F($" in:{r.MaxInside}");
        if (!r.EnergyDecays) s += " E↑";
        return s;
    }

    private static string Detail(StabilityResult r) =>
        F($"non-finite {r.NonFinite}, worst stretch {r.WorstStretch * 100:0.###} % (elongation {r.WorstElongation * 100:0.###} %, compression {r.WorstCompression * 100:0.###} %), inside {r.MaxInside}, kinetic energy {r.EnergyBefore:0.####} → {r.EnergyAfter:0.####} J/kg");

    internal static void WriteFile(string path, string text)
    {
        string tmp = path + ".tmp";
        File.WriteAllText(tmp, text);
        File.Move(tmp, path, overwrite: true);
    }

    private static string F(FormattableString s) => s.ToString(CultureInfo.InvariantCulture);
}
