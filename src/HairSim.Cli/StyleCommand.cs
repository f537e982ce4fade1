using System.CommandLine;
using System.Diagnostics;
using System.Globalization;
using System.Numerics;
using HairSim;
using HairSim.Editing;
using HairSim.IO;

namespace HairSim.Cli;

/// <summary>
/// A scripted styling session on the reference scene: settle, cut a chin-length bob (front view), select the
/// fringe and fit a curl to it (side view), simulate on while the head shakes, then export .hair / .obj / .usda,
/// save the hairstyle and draw before/after pictures. --bench times a full-scene cut instead.
/// </summary>
public static class StyleCommand
{
    public const string Description = "A scripted styling session on the reference scene (or on a mesh head with --head): settle, cut at chin height (front view), fit a curl to the fringe (side view), then a head shake; writes .hairstyle, .hair, .obj, .usda and before/after SVG pictures. --bench times a full-scene cut instead.";

    public static Command Create()
    {
        var output = CliOptions.Text("--out", "folder for the haircut files and pictures", "out", "folder");
        var settle = CliOptions.Double("--settle", "seconds the hair settles under gravity before it is styled", 1, v => v >= 0 && v <= 60, "in 0 … 60 seconds", "seconds");
        var after = CliOptions.Double("--after", "seconds of head shake after styling", 10, v => v >= 0 && v <= 60, "in 0 … 60 seconds", "seconds");
        var stiffness = CliOptions.Double("--stiffness", "global pull of every particle towards its rest pose (0 = none: the bend model holds the style by itself)", 0, v => v >= 0 && v <= 1, "in 0 … 1", "0…1");
        var groom = new GroomOptions();
        var bench = CliOptions.Switch("--bench", "time a full-scene cut (median of --runs) instead of the styling session");
        var runs = CliOptions.Int("--runs", "timed cuts with --bench", 30, 1, 10_000);
        var head = CliOptions.Text("--head", "style hair grown on this mesh (.glb, .gltf or .obj; its vertex colours' red marks the scalp) and colliding with it; 'procedural' is the project's own head", null, "file|procedural");
        var cell = CliOptions.Double("--sdf-cell", "cell size of the --head mesh's distance field, metres", 0.0025, v => v > 0 && v <= 1, "more than 0 and at most 1 metre", "metres");
        var command = new Command("style", Description) { output, settle, after, stiffness, bench, runs, head, cell };
        groom.AddTo(command);
        command.SetAction(p =>
        {
            if (p.Given(runs) && !p.GetValue(bench)) throw new UsageException("--runs applies only with --bench");
            if (p.GetValue(head) == null && p.Given(cell)) throw new UsageException("--sdf-cell applies only with --head");
            var g = groom.Read(p);
            string outDir = p.GetValue(bench) ? p.GetValue(output)! : CliOptions.CheckOutputFolder(p.GetValue(output)!, "--out");
            return Execute(outDir, p.GetValue(settle), p.GetValue(after), (float)p.GetValue(stiffness), g, p.GetValue(bench), p.GetValue(runs),
                p.GetValue(head), (float)p.GetValue(cell));
        });
        return command;
    }

    private static readonly CultureInfo Ci = CultureInfo.InvariantCulture;

    public static int Execute(string outDir, double settle, double after, float stiffness, GroomSettings groom, bool bench, int runs,
        string? headMesh = null, float sdfCell = 0.0025f)
    {
        var settings = new SimulationSettings { Path = SolverPath.Fast };
        // On a mesh head the script's strokes stay where they are on the reference head (chin height, fringe): a head of
        // the reference proportions, such as the project's procedural one, is styled the same way.
        var scene = headMesh == null ? GroomBuilder.BuildScene(groom, settings) : RunCommand.GrowOnMesh(headMesh, sdfCell, groom, settings);
        settings = scene.Settings;
        var w = scene.World;
        using var dispatcher = ThreadDispatchers.CreateDefault();
        var sim = new HairSimulation(scene, dispatcher: dispatcher);
        var script = new Script(groom);
        Console.WriteLine($"scene: {w.SheetCount} sheets × {groom.StrandsPerSheet} strands × {groom.ParticlesPerStrand} particles = {w.StrandCount:N0} strands; bend model {settings.Bend}, Sag {settings.Sag.ToString(Ci)}; global shape stiffness {stiffness.ToString(Ci)}");
        Simulate(sim, settle, "settling");
        var history = new EditHistory();
        scene.SetComponent(history);
        // The settled hair becomes the rest pose: what the user sees is what the bend model holds.
        history.Do(HairEditor.BakeRestPose(scene));
        settings.GlobalShapeStiffness = stiffness;
        scene.SettingsChanged();

        if (bench) return Bench(scene, history, script.CutStroke, script.CutOptions, runs);

        Directory.CreateDirectory(outDir);
        var fringe = script.Fringe(scene);
        var mask = fringe.Mask.ToArray();
        Svg(outDir, "before", scene, mask);

        var sw = Stopwatch.StartNew();
        var cut = HairEditor.Cut(scene, script.CutStroke, script.CutOptions);
        double cutMs = sw.Elapsed.TotalMilliseconds;
        history.Do(cut);
        Console.WriteLine(string.Create(Ci, $"cut: {cut.Strands.Count:N0} strands cut at chin height (plan {cutMs:F1} ms, undo memory {cut.MemoryBytes / 1e6:F1} MB)"));
        if (cut.Strands.Count == 0)
        {
            Console.Error.WriteLine(string.Create(Ci, $"check failed: the chin-height cut crossed no strand: no hair reaches below the chin after {settle:0.##} s of settling"));
            return ExitCodes.CheckFailed;
        }

        var key = KeyCurve.FromStrands(w, fringe.Strands);
        sw.Restart();
        var fit = script.Fit(scene, fringe);
        double fitMs = sw.Elapsed.TotalMilliseconds;
        history.Do(fit);
        Console.WriteLine(string.Create(Ci, $"fit: {fringe.Count:N0} fringe strands fitted to a curl stroke (plan {fitMs:F1} ms, key curve {key.Length * 100:F1} cm, stroke {fit.StrokeLength * 100:F1} cm{(fit.Extended ? ", extended straight" : "")})"));

        double fitted = Curliness(w, fringe);
        double during = Simulate(sim, after, "head shaking", shake: true, fringe);
        Simulate(sim, 1, "head still");
        var m = WorldMetrics.Measure(scene);
        Console.WriteLine(string.Create(Ci, $"after {after:F1} s of head shake and 1 s still: non-finite {m.NonFinite}, max edge stretch {m.MaxEdgeStretch * 100:F3} %, fringe tip–root / length {fitted:F3} fitted → {Curliness(w, fringe):F3} (1 = hanging straight); fringe's farthest particle from its fitted place {FromStyle(w, fringe) * 100:F2} % of its length now, {during * 100:F1} % at most while shaking"));

        var curves = StrandCurves.FromWorld(w);
        var files = new (string Name, Action<string> Write)[]
        {
            ("hairstyle.hair", p => CurveExport.WriteCyHair(p, curves)),
            ("hairstyle.obj", p => CurveExport.WriteObj(p, curves)),
            ("hairstyle.usda", p => CurveExport.WriteUsda(p, curves)),
            ("hairstyle.hairstyle", p => HairstyleFile.Save(scene, p)),
        };
        foreach (var (name, write) in files)
        {
            var path = Path.Combine(outDir, name);
            write(path);
            Console.WriteLine(string.Create(Ci, $"wrote {path} ({new FileInfo(path).Length / 1024.0:F0} KiB)"));
        }
        var reloaded = HairstyleFile.Load(Path.Combine(outDir, "hairstyle.hairstyle"));
        Console.WriteLine($"hairstyle file reloads bit-exact: {reloaded.World.BitEquals(w)}");
        Svg(outDir, "after", scene, mask);
        if (m.NonFinite != 0)
        {
            Console.Error.WriteLine($"error: the simulation produced {m.NonFinite} non-finite values");
            return ExitCodes.NonFinite;
        }
        if (!reloaded.World.BitEquals(w))
        {
            Console.Error.WriteLine("check failed: the saved hairstyle does not reload bit-exact");
            return ExitCodes.CheckFailed;
        }
        return ExitCodes.Ok;
    }

    /// <summary>
    /// The scripted style on a groom of the reference head's proportions: a chin-height cut through every layer (front
    /// view) and a curl fitted to the fringe (side view). The bench styles the reference scene with it too.
    /// </summary>
    public sealed class Script
    {
        private readonly StrokeCamera _front, _side;

        public Script(GroomSettings groom)
        {
            _front = StrokeCamera.LookAtOrthographic(new Vector3(0, -0.1f, 2f), new Vector3(0, -0.1f, 0), Vector3.UnitY, 0.7f, new Vector2(800, 800));
            _side = StrokeCamera.LookAtOrthographic(new Vector3(-2f, -0.05f, 0), new Vector3(0, -0.05f, 0), Vector3.UnitY, 0.5f, new Vector2(800, 800));
            // A bob: a horizontal stroke across the whole picture at chin height (bottom of the head ellipsoid), through all layers.
            var chin = ScreenOf(_front, new Vector3(0, groom.HeadCenter.Y - groom.HeadRadii.Y, 0));
            CutStroke = new Stroke([new Vector2(5, chin.Y), new Vector2(795, chin.Y)], _front);
        }

        public Stroke CutStroke { get; }
        public CutOptions CutOptions { get; } = new() { Reach = CutReach.AllThrough, MinRemainingLength = 0.02f };

        /// <summary>The fringe: roots in a box over the forehead, seen from the side.</summary>
        public StrandSelection Fringe(HairScene scene)
        {
            var area = SelectionArea.Rectangle(ScreenOf(_side, new Vector3(0, 0.075f, 0.055f)), ScreenOf(_side, new Vector3(0, 0.02f, 0.12f)));
            var fringe = HairEditor.Select(scene, _side, area, new SelectionOptions { RootsOnly = true });
            if (fringe.Count == 0) throw new UsageException("no strand is rooted over the forehead, where the scripted fit selects the fringe: use more --sheets or --strands");
            return fringe;
        }

        /// <summary>A curl in the side view: forward and down from the hairline, then a 2.5 cm loop turned 1.5 times.</summary>
        public FitCommand Fit(HairScene scene, StrandSelection fringe)
        {
            var root = KeyCurve.FromStrands(scene.World, fringe.Strands).Root;
            var curl = new List<Vector2> { ScreenOf(_side, root) };
            var centre = root + new Vector3(0, -0.02f, 0.03f) + new Vector3(0, -0.025f, 0);
            for (int k = 0; k <= 120; k++)
            {
                float t = 1.5f * 2 * MathF.PI * k / 120;
                curl.Add(ScreenOf(_side, centre + 0.025f * new Vector3(0, MathF.Cos(t), MathF.Sin(t))));
            }
            return HairEditor.Fit(scene, fringe, new Stroke(curl, _side));
        }

        /// <summary>Settle (1 s), bake the rest pose, cut and fit: the styled reference scene of the bench.</summary>
        public void StyleAll(HairSimulation sim)
        {
            for (int f = 0; f < 60; f++) sim.Step(1f / 60f);
            var scene = sim.Scene;
            HairEditor.BakeRestPose(scene).Apply();
            HairEditor.Cut(scene, CutStroke, CutOptions).Apply();
            Fit(scene, Fringe(scene)).Apply();
        }
    }

    private static Vector2 ScreenOf(StrokeCamera cam, Vector3 p)
    {
        if (!cam.Project(p, out var s, out _)) throw new ArgumentException("Scripted point is behind the camera.");
        return Vector2.Clamp(s, Vector2.Zero, cam.ViewportSize);
    }

    /// <summary>Simulates at 60 Hz, the head still or shaking; returns the fringe's worst distance from its style (share of length) seen, if asked.</summary>
    private static double Simulate(HairSimulation sim, double seconds, string label, bool shake = false, StrandSelection? watch = null)
    {
        int frames = (int)Math.Round(seconds * 60);
        if (frames == 0) return 0;
        var progress = new Progress(label, frames);
        double worst = 0;
        for (int f = 0; f < frames; f++)
        {
            if (shake) sim.Step(1f / 60f, Measurement.HeadMotion.Shake((f + 1) / 60f)); else sim.Step(1f / 60f, RigidTransform.Identity);
            if (watch != null && f % 6 == 0) worst = Math.Max(worst, FromStyle(sim.World, watch));
            progress.Report(f + 1);
        }
        return worst;
    }

    /// <summary>Farthest particle of the selected strands from its rest place on the head, as a share of its strand's length.</summary>
    private static double FromStyle(HairWorld w, StrandSelection sel)
    {
        double worst = 0;
        foreach (int s in sel.Strands)
        {
            double length = 0, d = 0;
            int first = w.StrandFirst[s];
            for (int k = 0; k < w.StrandParticleCount[s]; k++)
            {
                if (k > 0) length += w.RestLength[first + k];
                d = Math.Max(d, Vector3.Distance(w.GetPosition(first + k), w.Head.TransformPoint(w.GetRest(first + k))));
            }
            worst = Math.Max(worst, d / length);
        }
        return worst;
    }

    private static double Curliness(HairWorld w, StrandSelection sel)
    {
        double sum = 0;
        foreach (int s in sel.Strands)
        {
            double len = 0;
            for (int k = 1; k < w.StrandParticleCount[s]; k++) len += w.RestLength[w.StrandFirst[s] + k];
            sum += Vector3.Distance(w.GetPosition(w.RootIndex(s)), w.GetPosition(w.TipIndex(s))) / len;
        }
        return sum / sel.Count;
    }

    private static void Svg(string dir, string stage, HairScene scene, bool[] mask)
    {
        foreach (var view in new[] { SvgExport.View.Front, SvgExport.View.Side })
        {
            var path = Path.Combine(dir, $"{stage}-{view.ToString().ToLowerInvariant()}.svg");
            SvgExport.Write(path, scene, view, 0.6f, 600, mask, $"{stage}, {view.ToString().ToLowerInvariant()} view (fringe in red, every 10th other strand)", every: 10);
            Console.WriteLine(string.Create(Ci, $"wrote {path} ({new FileInfo(path).Length / 1024.0:F0} KiB)"));
        }
    }

    /// <summary>Times the full-scene cut: planning alone, and plan + apply + undo (which leaves the world as it was).</summary>
    private static int Bench(HairScene scene, EditHistory history, Stroke stroke, CutOptions options, int runs)
    {
        int strands = HairEditor.Cut(scene, stroke, options).Strands.Count;
        if (strands == 0)
        {
            Console.Error.WriteLine("check failed: the chin-height cut crosses no strand, so there is nothing to time");
            return ExitCodes.CheckFailed;
        }
        for (int k = 0; k < 5; k++) { history.Do(HairEditor.Cut(scene, stroke, options)); history.Undo(); } // warm-up (JIT, caches)
        var plan = new double[runs];
        var full = new double[runs];
        var sw = new Stopwatch();
        for (int r = 0; r < runs; r++)
        {
            sw.Restart();
            var cmd = HairEditor.Cut(scene, stroke, options);
            plan[r] = sw.Elapsed.TotalMilliseconds;
            history.Do(cmd);
            history.Undo();
            full[r] = sw.Elapsed.TotalMilliseconds;
        }
        Array.Sort(plan); Array.Sort(full);
        Console.WriteLine(string.Create(Ci, $"full-scene cut ({scene.World.StrandCount:N0} strands, {scene.World.ParticleCount:N0} particles, stroke of {stroke.Count} points, {strands:N0} strands cut), one core, {runs} runs after 5 warm-up:"));
        Console.WriteLine(string.Create(Ci, $"  plan (find crossings):     median {plan[runs / 2]:F2} ms, min {plan[0]:F2} ms, max {plan[^1]:F2} ms"));
        Console.WriteLine(string.Create(Ci, $"  plan + apply + undo:       median {full[runs / 2]:F2} ms, min {full[0]:F2} ms, max {full[^1]:F2} ms"));
        return 0;
    }
}
