using System.Numerics;
using HairSim;
using HairSim.Editing;

namespace HairSim.Tests.Editing;

/// <summary>Random strokes from random cameras: edits stay finite, keep their promises, and undo exactly.</summary>
public class EditPropertyTests
{
    private static HairScene Settled()
    {
        var scene = GroomBuilder.BuildScene(new GroomSettings { SheetCount = 20, StrandsPerSheet = 5, ParticlesPerStrand = 10 });
        var sim = new HairSimulation(scene);
        for (int f = 0; f < 15; f++) sim.Step(1f / 60f);
        return scene;
    }

    private static StrokeCamera RandomCamera(ref SplitMix64 rng)
    {
        float yaw = 6.28f * rng.NextFloat(), pitch = rng.NextFloat() - 0.5f;
        var eye = 0.9f * new Vector3(MathF.Cos(pitch) * MathF.Sin(yaw), MathF.Sin(pitch), MathF.Cos(pitch) * MathF.Cos(yaw));
        var size = new Vector2(400 + 400 * rng.NextFloat(), 300 + 300 * rng.NextFloat());
        return rng.Next() % 2 == 0
            ? StrokeCamera.LookAtPerspective(eye, new Vector3(0, -0.05f, 0), Vector3.UnitY, 0.6f + rng.NextFloat(), size)
            : StrokeCamera.LookAtOrthographic(eye, new Vector3(0, -0.05f, 0), Vector3.UnitY, 0.4f + 0.3f * rng.NextFloat(), size);
    }

    private static Stroke RandomStroke(ref SplitMix64 rng, StrokeCamera cam)
    {
        var pts = new Vector2[2 + (int)(rng.Next() % 9)];
        for (int k = 0; k < pts.Length; k++) pts[k] = new Vector2(cam.ViewportSize.X * rng.NextFloat(), cam.ViewportSize.Y * rng.NextFloat());
        return new Stroke(pts, cam);
    }

    [Fact]
    public void RandomCutsPutTipsOnTheStrokeKeepRootsAndUndoExactly()
    {
        var scene = Settled();
        var w = scene.World;
        var rng = new SplitMix64(77);
        int totalCut = 0;
        for (int trial = 0; trial < 40; trial++)
        {
            var cam = RandomCamera(ref rng);
            var stroke = RandomStroke(ref rng, cam);
            var options = new CutOptions { Reach = rng.Next() % 2 == 0 ? CutReach.VisibleOnly : CutReach.AllThrough, MinRemainingLength = 0.03f * rng.NextFloat() };
            var before = w.Clone();
            var cmd = HairEditor.Cut(scene, stroke, options);
            cmd.Apply();
            totalCut += cmd.Strands.Count;
            Assert.Equal(0, w.CountNonFinite());
            foreach (int s in cmd.Strands)
            {
                Assert.True(w.StrandParticleCount[s] >= 2 && w.StrandParticleCount[s] <= before.StrandParticleCount[s]);
                Assert.True(EditScenes.StrandRestLength(w, s) >= options.MinRemainingLength - 1e-5f);
                Assert.Equal(before.GetPosition(w.RootIndex(s)), w.GetPosition(w.RootIndex(s)));
                Assert.True(cam.Project(w.GetPosition(w.TipIndex(s)), out var tip, out _));
                Assert.True(EditScenes.DistanceToPolyline(tip, stroke.Points) < 0.1f);
            }
            cmd.Revert();
            Assert.True(w.BitEquals(before));
        }
        Assert.True(totalCut > 100, $"the random strokes cut only {totalCut} strands in all");
    }

    [Fact]
    public void RandomFitsKeepLengthsAndRootsStayFiniteAndUndoExactly()
    {
        var scene = Settled();
        var w = scene.World;
        var rng = new SplitMix64(78);
        int fitted = 0;
        for (int trial = 0; trial < 30; trial++)
        {
            var cam = RandomCamera(ref rng);
            var c = cam.ViewportSize * new Vector2(rng.NextFloat(), rng.NextFloat());
            var selection = HairEditor.Select(scene, cam, SelectionArea.Brush(c, 20 + 150 * rng.NextFloat()));
            if (selection.Count == 0) continue;
            var before = w.Clone();
            var cmd = HairEditor.Fit(scene, selection, RandomStroke(ref rng, cam));
            cmd.Apply();
            fitted++;
            Assert.Equal(0, w.CountNonFinite());
            foreach (int s in selection.Strands)
            {
                Assert.Equal(before.GetPosition(w.RootIndex(s)), w.GetPosition(w.RootIndex(s)));
                for (int k = 1; k < w.StrandParticleCount[s]; k++)
                {
                    int i = w.StrandFirst[s] + k;
                    Assert.Equal(w.RestLength[i], Vector3.Distance(w.GetPosition(i - 1), w.GetPosition(i)), 4);
                }
            }
            cmd.Revert();
            Assert.True(w.BitEquals(before));
        }
        Assert.True(fitted > 10);
    }
}
