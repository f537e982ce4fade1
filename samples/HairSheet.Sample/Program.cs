// A whole program with HairSheet's library: grow a groom, run a game loop while the head turns, cut and fit the
// hair with strokes as a user would draw them on screen, undo, save the haircut and export the strands.
// Run it: dotnet run --project samples/HairSheet.Sample -- out
using System.Numerics;
using HairSim;
using HairSim.Editing;
using HairSim.IO;

public static class HairSheetSample
{
    public static int Main(string[] args) => Run(Console.Out, GroomSettings.Reference(), args.Length > 0 ? args[0] : "out");

    public static int Run(TextWriter log, GroomSettings groom, string outputFolder)
    {
        var scene = GroomBuilder.BuildScene(groom);               // default settings: styles hold, fast path
        using var threads = ThreadDispatchers.CreateDefault();     // every core; no worker thread outlives it
        var sim = new HairSimulation(scene, dispatcher: threads);
        var history = new EditHistory();
        scene.SetComponent(history);

        // The game loop: 60 Hz frames while the head turns from side to side, then one second still.
        for (int frame = 1; frame <= 180; frame++)
        {
            float turn = frame <= 120 ? 0.4f * MathF.Sin(frame / 12f) : 0f;
            sim.Step(1f / 60f, new RigidTransform(Vector3.Zero, Quaternion.CreateFromYawPitchRoll(turn, 0f, 0f)));
        }

        // A camera 80 cm in front of the head; strokes are screen points on its 800 × 800 pixel view.
        var screen = new Vector2(800, 800);
        var camera = StrokeCamera.LookAtPerspective(new Vector3(0, 0, 0.8f), Vector3.Zero, Vector3.UnitY, 0.8f, screen);

        // Cut: a line across the screen at chin height; every strand crossing it ends on it.
        var cut = HairEditor.Cut(scene, new Stroke([new(0, 560), new(400, 560), new(799, 560)], camera),
            new CutOptions { Reach = CutReach.VisibleOnly });
        history.Do(cut);

        // Fit: select the fringe by its roots in a rectangle, then draw the curl it should follow.
        var fringe = HairEditor.Select(scene, camera, SelectionArea.Rectangle(new(250, 150), new(550, 350)),
            new SelectionOptions { RootsOnly = true });
        var curl = new Vector2[40];
        for (int i = 0; i < curl.Length; i++)
        {
            float t = i / 39f * 4 * MathF.PI;
            curl[i] = new Vector2(400 + 40 * MathF.Sin(t) * (1 - i / 60f), 250 + 5 * i - 40 * MathF.Cos(t));
        }
        history.Do(HairEditor.Fit(scene, fringe, new Stroke(curl, camera)));
        log.WriteLine($"cut {cut.Cuts.Count} strands, fitted {fringe.Count} fringe strands");

        // The fitted curl is the fringe's rest shape now: it holds while the head moves again.
        for (int frame = 1; frame <= 60; frame++) sim.Step(1f / 60f, RigidTransform.Identity);

        // Undo the fit and redo it (bit-exact), then save the haircut and export the strands.
        history.Undo();
        history.Redo();
        Directory.CreateDirectory(outputFolder);
        HairstyleFile.Save(scene, Path.Combine(outputFolder, "style.hairstyle"));       // temp file, then rename
        CurveExport.WriteCyHair(Path.Combine(outputFolder, "style.hair"), StrandCurves.FromWorld(scene.World));
        log.WriteLine($"saved {Path.Combine(outputFolder, "style.hairstyle")} and {Path.Combine(outputFolder, "style.hair")}");
        return scene.World.CountNonFinite() == 0 ? 0 : 3;
    }
}
