using System.CommandLine;
using System.Diagnostics;
using System.Globalization;
using HairSim;
using HairSim.Measurement;

namespace HairSim.Cli;

/// <summary>The main job: build the reference scene, simulate it headless, report timings and error figures.</summary>
public static class RunCommand
{
    public const string Description = "The main job: simulate the reference scene (435 sheets × 40 strands × 16 particles) headless and report frame times and error figures.";

    /// <summary>What a run does, read from the command line.</summary>
    public sealed record Options(double Seconds, int Hz, GroomSettings Groom, int Substeps, SolverPath Path, bool Shake, bool Paced,
        string? Head, double SdfCell, string? Hairstyle, string? Export, bool Volume = false, BendModel? Bend = null);

    /// <summary>--bend's names for the bend models.</summary>
    private static readonly Dictionary<string, BendModel> BendNames = new()
    {
        ["rest"] = BendModel.RestShape, ["triples"] = BendModel.SourceTriples, ["limp"] = BendModel.Limp,
    };

    public static Command Create()
    {
        var seconds = CliOptions.Double("--seconds", "simulated time", 10, v => v > 0 && v <= 3600, "more than 0 and at most 3600 seconds", "seconds");
        var hz = CliOptions.Int("--hz", "frames per second (each frame steps 1/hz seconds)", 60, 1, 1000);
        var substeps = CliOptions.Int("--substeps", "substeps per frame", new SimulationSettings().Substeps, 1, 256);
        var path = CliOptions.SolverPathOption();
        var groom = new GroomOptions();
        var shake = CliOptions.Switch("--shake", "shake the head (\"no\", ±40° at 1.5 Hz, while bobbing 3 cm at 2 Hz) instead of holding it still");
        var paced = CliOptions.Switch("--paced", "start frames on the real-time clock and idle in between, as a game's 60 Hz loop");
        var volume = CliOptions.Switch("--volume", "hair volume: strands push apart and drag one another (VolumeSettings defaults, docs/volume.md)");
        var bend = CliOptions.Choice("--bend", "bend model: rest (keeps each strand's rest shape), triples (the source's shape matching) or limp (no bending); a --hairstyle keeps its own unless this is given",
            "rest", [.. BendNames.Keys]);
        var head = CliOptions.Text("--head", "grow the hair on this mesh (.glb, .gltf or .obj; its vertex colours' red marks the scalp) and collide with it; 'procedural' is the project's own head", null, "file|procedural");
        var cell = CliOptions.Double("--sdf-cell", "cell size of the --head mesh's distance field, metres", 0.0025, v => v > 0 && v <= 1, "more than 0 and at most 1 metre", "metres");
        var hairstyle = CliOptions.Text("--hairstyle", "run this saved haircut (.hairstyle, with its own settings; --substeps and --path still apply)", null, "file");
        var export = CliOptions.Text("--export", "after the run, write hair.hair, hair.obj, hair.usda, hair.hairstyle, front.svg and side.svg to this folder", null, "folder");
        var command = new Command("run", Description) { seconds, hz, substeps, path, shake, paced, volume, bend, head, cell, hairstyle, export };
        groom.AddTo(command);
        command.SetAction(p =>
        {
            string? hairstyleFile = p.GetValue(hairstyle), headFile = p.GetValue(head);
            if (hairstyleFile != null && headFile != null) throw new UsageException("--hairstyle and --head cannot be combined: a hairstyle file holds its own hair");
            if (hairstyleFile != null && groom.Given(p)) throw new UsageException("--sheets, --strands and --particles do not apply with --hairstyle: a hairstyle file holds its own hair");
            if (headFile == null && p.Given(cell)) throw new UsageException("--sdf-cell applies only with --head");
            var g = groom.Read(p);
            if (headFile != null && (long)g.SheetCount * g.StrandsPerSheet > 1_000_000)
                throw new UsageException("--sheets × --strands must be at most 1,000,000 strands on a mesh head");
            string? exportFolder = p.GetValue(export) is { } folder ? CliOptions.CheckOutputFolder(folder, "--export") : null;
            return Execute(new Options(p.GetValue(seconds), p.GetValue(hz), g, p.GetValue(substeps), CliOptions.ToSolverPath(p.GetValue(path)), p.GetValue(shake),
                p.GetValue(paced), headFile, p.GetValue(cell), hairstyleFile, exportFolder, p.GetValue(volume),
                hairstyleFile == null || p.Given(bend) ? BendNames[p.GetValue(bend)!] : null));
        });
        return command;
    }

    /// <summary>Hair grown on the file's mesh (all of it is scalp unless its vertex colours mark one in red), colliding with its distance field.</summary>
    internal static HairScene GrowOnMesh(string path, float cell, GroomSettings groom, SimulationSettings settings)
    {
        var load = Stopwatch.StartNew();
        var mesh = path == "procedural" ? HairSim.Meshes.ProceduralHead.Create() : HairSim.Meshes.MeshFile.Load(path);
        load.Stop();
        var field = HairSim.Meshes.SignedDistanceField.Bake(mesh, cell);
        var grow = Stopwatch.StartNew();
        var g = new HairSim.Meshes.MeshGroomSettings
        {
            SheetCount = groom.SheetCount, StrandsPerSheet = groom.StrandsPerSheet, ParticlesPerStrand = groom.ParticlesPerStrand,
            StrandLength = groom.StrandLength, PinnedPerStrand = groom.PinnedPerStrand, ScalpMaskThreshold = mesh.Colors != null ? 0.5f : 0f,
        };
        HairScene scene;
        try { scene = HairSim.Meshes.MeshScalp.BuildScene(mesh, field, g, settings); }
        catch (ArgumentException e) when (e is not ArgumentOutOfRangeException)
        {
            // The scalp cannot hold the groom asked for (too few roots fit, no triangle on the scalp).
            throw new UsageException($"--head {path}: {e.Message} (--sheets × --strands is {(long)g.SheetCount * g.StrandsPerSheet:N0} strands)");
        }
        grow.Stop();
        Console.WriteLine(string.Create(CultureInfo.InvariantCulture,
            $"head mesh {path}: {mesh.TriangleCount:N0} triangles (read in {load.Elapsed.TotalMilliseconds:F0} ms); distance field {field.Nx}×{field.Ny}×{field.Nz} cells of {cell * 1000:0.###} mm baked in {field.BakeTime.TotalMilliseconds:F0} ms; hair grown in {grow.Elapsed.TotalMilliseconds:F0} ms"));
        return scene;
    }

    public static int Execute(Options o)
    {
        double seconds = o.Seconds;
        int hz = o.Hz;
        var groom = o.Groom;
        var settings = new SimulationSettings { Substeps = o.Substeps, Path = o.Path, Bend = o.Bend ?? BendModel.RestShape };
        bool shake = o.Shake, paced = o.Paced;
        string? headFile = o.Head, hairstyleFile = o.Hairstyle, exportFolder = o.Export;
        double cell = o.SdfCell;
        var build = Stopwatch.StartNew();
        var scene = hairstyleFile != null ? LoadHairstyle(hairstyleFile, settings, o.Bend)
            : headFile == null ? GroomBuilder.BuildScene(groom, settings) : GrowOnMesh(headFile, (float)cell, groom, settings);
        if (o.Volume) scene.SetComponent(new VolumeSettings());
        build.Stop();
        settings = scene.Settings;
        var w = scene.World;
        using var dispatcher = ThreadDispatchers.CreateDefault();
        var sim = new HairSimulation(scene, dispatcher: dispatcher);
        var reference = GroomSettings.Reference();
        string what = hairstyleFile != null ? $"haircut {Path.GetFileName(hairstyleFile)}"
            : headFile != null ? "groom on the mesh head"
            : groom.SheetCount == reference.SheetCount && groom.StrandsPerSheet == reference.StrandsPerSheet && groom.ParticlesPerStrand == reference.ParticlesPerStrand
                ? "HairSheet reference scene" : "groom on the reference head";
        Console.WriteLine(hairstyleFile != null
            ? $"{what}: {w.SheetCount} sheets, {w.StrandCount:N0} strands, {w.ParticleCount:N0} particles (loaded in {build.Elapsed.TotalMilliseconds:F0} ms)"
            : $"{what}: {w.SheetCount} sheets × {groom.StrandsPerSheet} strands × {groom.ParticlesPerStrand} particles = {w.StrandCount:N0} strands, {w.ParticleCount:N0} particles (built in {build.Elapsed.TotalMilliseconds:F0} ms)");
        Console.WriteLine($"pipeline ({settings.Path}, {dispatcher.ThreadCount} thread(s)): {string.Join(" → ", sim.Pipeline.SystemNames)}");
        string model = settings.Bend switch
        {
            BendModel.RestShape => $"bend model RestShape (Sag {settings.Sag}: a horizontal strand's tip sags {settings.Sag * 100:0.##} % of its length under 1 g; lengths kept by the bend sweep)",
            BendModel.SourceTriples => $"bend model SourceTriples (α = {settings.Alpha}, length pass {settings.Length})",
            _ => $"bend model Limp (length pass {settings.Length})",
        };
        Console.WriteLine($"settings: {hz} Hz, {settings.Substeps} substeps, {model}, damping {settings.Damping} per natural time √(L/1 g)");
        Console.WriteLine(shake
            ? "head: shaking \"no\" (±40° at 1.5 Hz) while bobbing 3 cm at 2 Hz"
            : "head: still (--shake moves it)");
        Console.WriteLine(o.Volume ? "hair volume: on (strands push apart and drag one another)" : "hair volume: off (strands pass through one another; --volume turns it on)");

        int frames = (int)Math.Ceiling(seconds * hz);
        float dt = 1f / hz;
        var times = new double[frames];
        var progress = new Progress("simulating", frames);
        var sw = new Stopwatch();
        var wall = Stopwatch.StartNew();
        for (int f = 0; f < frames; f++)
        {
            // --paced: frames start on the real-time clock, idle in between, as a game's 60 Hz loop would be.
            if (paced) { double due = f * dt - wall.Elapsed.TotalSeconds; if (due > 0) Thread.Sleep(TimeSpan.FromSeconds(due)); }
            var head = shake ? HeadMotion.Shake((f + 1) * dt) : w.Head;
            sw.Restart();
            sim.Step(dt, head);
            times[f] = sw.Elapsed.TotalMilliseconds;
            progress.Report(f + 1, $"t = {(f + 1) * dt:F2} s, {times[f]:F2} ms/frame");
        }
        var m = WorldMetrics.Measure(scene);
        foreach (var line in FrameTimeLines(times, hz, (double)w.ParticleCount * settings.Substeps)) Console.WriteLine(line);
        var inv = CultureInfo.InvariantCulture;
        Console.WriteLine(string.Create(inv, $"after {frames * dt:F2} s:"));
        Console.WriteLine(string.Create(inv, $"  length / rest length = {m.LengthRatio:F5} (every segment of every strand summed: the hair's total length over its total rest length; 1 = no stretch)"));
        Console.WriteLine(string.Create(inv, $"  max edge stretch     = {m.MaxEdgeStretch * 100:F3} % (the segment most stretched or compressed against its rest length)"));
        Console.WriteLine(string.Create(inv, $"  max penetration      = {m.MaxPenetration * 1000:F3} mm ({m.ParticlesInside} particles inside the head)"));
        Console.WriteLine($"  non-finite values    = {m.NonFinite}");
        if (m.NonFinite != 0)
        {
            Console.Error.WriteLine($"error: the simulation produced {m.NonFinite} non-finite values{(exportFolder != null ? "; nothing exported" : "")}");
            return ExitCodes.NonFinite;
        }
        if (exportFolder != null) Export(scene, exportFolder);
        return ExitCodes.Ok;
    }

    /// <summary>
    /// Frame-time lines: the first frame on its own (it includes the JIT compiling the step), the statistics of the
    /// others, and how they compare with the frame's budget (16.7 ms at 60 Hz).
    /// </summary>
    public static List<string> FrameTimeLines(double[] times, int hz, double particleStepsPerFrame)
    {
        var inv = CultureInfo.InvariantCulture;
        var lines = new List<string>();
        double budget = 1000.0 / hz;
        var timed = times.Length > 1 ? times[1..] : times;
        if (times.Length > 1)
            lines.Add(string.Create(inv, $"first frame: {times[0]:F2} ms (includes compiling the step: left out of the figures below)"));
        var sorted = (double[])timed.Clone();
        Array.Sort(sorted);
        double mean = sorted.Average();
        int n = sorted.Length;
        lines.Add(string.Create(inv,
            $"frame time over {n} frame{(n == 1 ? "" : "s")}: mean {mean:F2} ms, median {sorted[n / 2]:F2} ms, p95 {sorted[Math.Min(n - 1, (int)(n * 0.95))]:F2} ms, max {sorted[^1]:F2} ms ({particleStepsPerFrame * n / (sorted.Sum() / 1000) / 1e6:F1} M particle-steps/s)"));
        int over = sorted.Count(t => t > budget);
        lines.Add(string.Create(inv,
            $"budget of a {hz} Hz frame: {budget:F1} ms: the mean uses {mean / budget * 100:F0} % of it, the p95 {sorted[Math.Min(n - 1, (int)(n * 0.95))] / budget * 100:F0} %; {over} of {n} frames over it{(mean <= budget ? "" : " (the mean is over: this scene does not run in real time here)")}"));
        return lines;
    }

    /// <summary>A saved haircut with its own settings; the command line's --substeps and --path still apply, and --bend when given.</summary>
    private static HairScene LoadHairstyle(string path, SimulationSettings overrides, BendModel? bend)
    {
        var scene = HairSim.IO.HairstyleFile.Load(path);
        scene.Settings.Substeps = overrides.Substeps;
        scene.Settings.Path = overrides.Path;
        if (bend is { } b) scene.Settings.Bend = b;
        scene.SettingsChanged();
        Console.WriteLine($"hairstyle {path}: {scene.World.StrandCount:N0} strands, {scene.World.ParticleCount:N0} particles, {scene.Colliders.Count} collider(s)");
        return scene;
    }

    /// <summary>The strands after the run as .hair, OBJ and USD, and front and side pictures.</summary>
    private static void Export(HairScene scene, string folder)
    {
        var curves = HairSim.IO.StrandCurves.FromWorld(scene.World);
        HairSim.IO.CurveExport.WriteCyHair(Path.Combine(folder, "hair.hair"), curves);
        HairSim.IO.CurveExport.WriteObj(Path.Combine(folder, "hair.obj"), curves);
        HairSim.IO.CurveExport.WriteUsda(Path.Combine(folder, "hair.usda"), curves);
        HairSim.IO.HairstyleFile.Save(scene, Path.Combine(folder, "hair.hairstyle"));
        foreach (var view in new[] { HairSim.IO.SvgExport.View.Front, HairSim.IO.SvgExport.View.Side })
            HairSim.IO.SvgExport.Write(Path.Combine(folder, $"{view.ToString().ToLowerInvariant()}.svg"), scene, view,
                title: $"after the run, {view.ToString().ToLowerInvariant()} view", every: Math.Max(1, scene.World.StrandCount / 2000));
        Console.WriteLine($"wrote hair.hair, hair.obj, hair.usda, hair.hairstyle, front.svg and side.svg to {folder}");
    }
}
