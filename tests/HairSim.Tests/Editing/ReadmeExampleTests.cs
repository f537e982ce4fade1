using System.Numerics;
using HairSim.Editing;
using HairSim.IO;

namespace HairSim.Tests.Editing;

/// <summary>README's library example, run as written (with a small groom and a front camera).</summary>
public class ReadmeExampleTests
{
    [Fact]
    public void ReadmeCutFitUndoSaveExportWorks()
    {
        var scene = GroomBuilder.BuildScene(new GroomSettings { SheetCount = 60, StrandsPerSheet = 6, ParticlesPerStrand = 12 },
            new SimulationSettings { Path = SolverPath.Reference });
        var sim = new HairSimulation(scene);
        for (int f = 0; f < 60; f++) sim.Step(1f / 60f);   // let the hair fall

        var viewportSize = new Vector2(800, 800);
        var front = StrokeCamera.LookAtPerspective(new Vector3(0, 0, 0.8f), Vector3.Zero, Vector3.UnitY, 0.8f, viewportSize);
        var view = front.View; var projection = front.Projection;
        var cam = StrokeCamera.Perspective(view, projection, viewportSize);
        var history = new EditHistory();
        scene.SetComponent(history);
        var before = scene.World.Clone();

        // A horizontal stroke across the whole view, below the head.
        var mousePoints = new[] { new Vector2(0, 560), new Vector2(400, 560), new Vector2(799, 560) };
        var cut = HairEditor.Cut(scene, new Stroke(mousePoints, cam), new CutOptions { Reach = CutReach.VisibleOnly });
        history.Do(cut);
        Assert.True(cut.Cuts.Count > 0);

        Vector2 a = new(250, 150), b = new(550, 350);
        var fringe = HairEditor.Select(scene, cam, SelectionArea.Rectangle(a, b), new SelectionOptions { RootsOnly = true });
        Assert.True(fringe.Count > 0);
        var curlPoints = new Vector2[40];
        for (int i = 0; i < curlPoints.Length; i++)
        {
            float t = i / 39f * 4 * MathF.PI;
            curlPoints[i] = new Vector2(400 + 40 * MathF.Sin(t) * (1 - i / 60f), 250 + 5 * i - 40 * MathF.Cos(t));
        }
        history.Do(HairEditor.Fit(scene, fringe, new Stroke(curlPoints, cam)));
        scene.Settings.Sag = 0.01f;   // how stiff the style holds: the default, tip sag of a horizontal strand, share of its length
        scene.SettingsChanged();
        Assert.Equal(2, history.UndoCount);

        history.Undo();
        history.Undo();
        Assert.True(scene.World.BitEquals(before));

        string dir = Path.Combine(Path.GetTempPath(), "hairsheet-readme-" + Guid.NewGuid().ToString("N"));
        Directory.CreateDirectory(dir);
        try
        {
            HairstyleFile.Save(scene, Path.Combine(dir, "style.hairstyle"));
            CurveExport.WriteCyHair(Path.Combine(dir, "style.hair"), StrandCurves.FromWorld(scene.World));
            Assert.True(HairstyleFile.Load(Path.Combine(dir, "style.hairstyle")).World.BitEquals(scene.World));
            Assert.True(new FileInfo(Path.Combine(dir, "style.hair")).Length > 128);
        }
        finally { Directory.Delete(dir, recursive: true); }
    }
}
