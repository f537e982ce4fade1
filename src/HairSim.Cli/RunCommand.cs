using System.Diagnostics;
using System.Globalization;
using HairSim;
using HairSim.Measurement;

namespace HairSim.Cli;

/// <summary>The main job: build the reference scene, simulate it headless, report timings and error figures.</summary>
public static class RunCommand
{
    public const string Help = "simulate the reference scene (435 × 40 × 16) headless: --seconds 10 --hz 60 --substeps N --path fast|reference --sheets --strands --particles --shake --head mesh.glb|.gltf|.obj|procedural (grow on and collide with a mesh; procedural = the project's own head) --sdf-cell 0.0025 --hairstyle file.hairstyle (run a saved haircut) --export folder (write .hair/.obj/.usda/.hairstyle and front/side SVGs after the run) --paced (frames on the real-time clock, idle in between) --volume (hair volume: strands push apart and drag one another, docs/volume.md) --bend rest|triples|limp";

    /// <summary>Hair grown on the file's mesh (all of it is scalp unless its vertex colours mark one in red), colliding with its distance field.</summary>
    private static HairScene GrowOnMesh(string path, float cell, GroomSettings groom, SimulationSettings settings)
    {
        var load = Stopwatch.StartNew();
        var mesh = path == "procedural" ? HairSim.Meshes.ProceduralHead.Create() : HairSim.Meshes.MeshFile.Load(path);
        load.Stop();
        var field = HairSim.Meshes.SignedDistanceField.Bake(mesh, cell);
        var grow = Stopwatch.StartNew();
        var g = new HairSim.Meshes.MeshGroomSettings
        {
            SheetCount = groom.SheetCount, StrandsPerSheet = groom.StrandsPerSheet, ParticlesPerStrand = groom.ParticlesPerStrand,
            StrandLength = groom.StrandLength, ScalpMaskThreshold = mesh.Colors != null ? 0.5f : 0f,
        };
        var scene = HairSim.Meshes.MeshScalp.BuildScene(mesh, field, g, settings);
        grow.Stop();
        Console.WriteLine(string.Create(CultureInfo.InvariantCulture,
            $"head mesh {path}: {mesh.TriangleCount:N0} triangles (read in {load.Elapsed.TotalMilliseconds:F0} ms); distance field {field.Nx}×{field.Ny}×{field.Nz} cells of {cell * 1000:0.###} mm baked in {field.BakeTime.TotalMilliseconds:F0} ms; hair grown in {grow.Elapsed.TotalMilliseconds:F0} ms"));
        return scene;
    }

    public static int Execute(CliArgs a)
    {
        double seconds = a.Double("seconds", 10);
        int hz = a.Int("hz", 60);
        var groom = GroomSettings.Reference();
        groom.SheetCount = a.Int("sheets", groom.SheetCount);
        groom.StrandsPerSheet = a.Int("strands", groom.StrandsPerSheet);
        groom.ParticlesPerStrand = a.Int("particles", groom.ParticlesPerStrand);
        var settings = new SimulationSettings();
        settings.Substeps = a.Int("substeps", settings.Substeps);
        settings.Path = a.String("path", "fast") switch
        {
            "fast" => SolverPath.Fast,
            "reference" => SolverPath.Reference,
            var p => throw new ArgumentException($"--path must be fast or reference, got '{p}'."),
        };
        bool shake = a.Flag("shake");
        bool paced = a.Flag("paced");
        bool volume = a.Flag("volume");
        settings.Bend = a.String("bend", "rest") switch
        {
            "rest" => BendModel.RestShape,
            "triples" => BendModel.SourceTriples,
            "limp" => BendModel.Limp,
            var b => throw new ArgumentException($"--bend must be rest, triples or limp, got '{b}'."),
        };
        string? headFile = a.String("head");
        string? hairstyleFile = a.String("hairstyle");
        string? exportFolder = a.String("export") is { } ef ? a.OutputFolder("export", ef) : null;
        double cell = a.Double("sdf-cell", 0.0025);
        a.RejectUnknown();
        if (seconds <= 0 || seconds > 3600) throw new ArgumentException("--seconds must be in (0, 3600].");
        if (hz < 1 || hz > 1000) throw new ArgumentException("--hz must be in 1 … 1000.");

        if (!(cell > 0 && cell <= 1)) throw new ArgumentException("--sdf-cell must be in (0, 1] metres.");
        var build = Stopwatch.StartNew();
        if (hairstyleFile != null && headFile != null) throw new ArgumentException("--hairstyle and --head cannot be combined: a hairstyle file holds its own hair.");
        var scene = hairstyleFile != null ? LoadHairstyle(hairstyleFile, settings)
            : headFile == null ? GroomBuilder.BuildScene(groom, settings) : GrowOnMesh(headFile, (float)cell, groom, settings);
        if (volume) scene.SetComponent(new VolumeSettings());
        build.Stop();
        var w = scene.World;
        using var dispatcher = ThreadDispatchers.CreateDefault();
        var sim = new HairSimulation(scene, dispatcher: dispatcher);
        Console.WriteLine($"HairSheet reference scene: {w.SheetCount} sheets × {groom.StrandsPerSheet} strands × {groom.ParticlesPerStrand} particles = {w.StrandCount:N0} strands, {w.ParticleCount:N0} particles (built in {build.Elapsed.TotalMilliseconds:F0} ms)");
        Console.WriteLine($"pipeline ({settings.Path}, {dispatcher.ThreadCount} thread(s)): {string.Join(" → ", sim.Pipeline.SystemNames)}");
        string model = settings.Bend switch
        {
            BendModel.RestShape => $"bend model RestShape (Sag {settings.Sag}: a horizontal strand's tip sags {settings.Sag * 100:0.##} % of its length under 1 g; lengths kept by the bend sweep)",
            BendModel.SourceTriples => $"bend model SourceTriples (α = {settings.Alpha}, length pass {settings.Length})",
            _ => $"bend model Limp (length pass {settings.Length})",
        };
        Console.WriteLine($"settings: {hz} Hz, {settings.Substeps} substeps, {model}, damping {settings.Damping} per natural time √(L/1 g)");

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
        Array.Sort(times);
        double mean = times.Average();
        double particleSteps = (double)w.ParticleCount * settings.Substeps * frames;
        Console.WriteLine(string.Create(CultureInfo.InvariantCulture,
            $"frame time: mean {mean:F2} ms, median {times[frames / 2]:F2} ms, p95 {times[(int)(frames * 0.95)]:F2} ms, max {times[^1]:F2} ms ({particleSteps / (times.Sum() / 1000) / 1e6:F1} M particle-steps/s)"));
        Console.WriteLine(string.Create(CultureInfo.InvariantCulture,
            $"after {frames * dt:F2} s: length / rest length = {m.LengthRatio:F5}, max edge stretch = {m.MaxEdgeStretch * 100:F3} %, max penetration = {m.MaxPenetration * 1000:F3} mm ({m.ParticlesInside} particles inside), non-finite values = {m.NonFinite}"));
        if (exportFolder != null) Export(scene, exportFolder);
        return m.NonFinite == 0 ? 0 : 3;
    }

    /// <summary>A saved haircut with its own settings; the command line's --substeps and --path still apply.</summary>
    private static HairScene LoadHairstyle(string path, SimulationSettings overrides)
    {
        var scene = HairSim.IO.HairstyleFile.Load(path);
        scene.Settings.Substeps = overrides.Substeps;
        scene.Settings.Path = overrides.Path;
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
