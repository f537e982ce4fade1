using System.Numerics;
using HairSim;
using HairSim.Editing;

namespace HairSim.Tests.Editing;

public class HistoryTests
{
    private static (HairScene scene, StrokeCamera front, StrokeCamera side) Scene()
    {
        var g = new GroomSettings { SheetCount = 24, StrandsPerSheet = 6, ParticlesPerStrand = 12 };
        var scene = GroomBuilder.BuildScene(g);
        var sim = new HairSimulation(scene);
        for (int f = 0; f < 20; f++) sim.Step(1f / 60f); // hanging, moving: velocities are non-zero
        var front = StrokeCamera.LookAtOrthographic(new Vector3(0, 0, 1), Vector3.Zero, Vector3.UnitY, 0.6f, new Vector2(600, 600));
        var side = StrokeCamera.LookAtOrthographic(new Vector3(-1, 0, 0), Vector3.Zero, Vector3.UnitY, 0.6f, new Vector2(600, 600));
        return (scene, front, side);
    }

    [Fact]
    public void UndoRestoresTheWorldBitForBitAndRedoRepeatsTheEditExactly()
    {
        var (scene, front, side) = Scene();
        var w = scene.World;
        var history = new EditHistory();
        scene.SetComponent(history);
        var s0 = w.Clone();
        Assert.True(history.Do(HairEditor.Cut(scene, new Stroke([new Vector2(0, 380), new Vector2(600, 360)], front), new CutOptions { Reach = CutReach.AllThrough })));
        var s1 = w.Clone();
        Assert.False(s1.BitEquals(s0));
        var selection = HairEditor.Select(scene, side, SelectionArea.Rectangle(new Vector2(330, 0), new Vector2(600, 600)));
        Assert.True(selection.Count > 0);
        Assert.True(history.Do(HairEditor.Fit(scene, selection, new Stroke([new Vector2(400, 200), new Vector2(460, 300), new Vector2(420, 420)], side))));
        var s2 = w.Clone();
        Assert.True(history.Do(HairEditor.ResetToRest(scene, selection)));
        var s3 = w.Clone();

        Assert.True(history.Undo()); Assert.True(w.BitEquals(s2));
        Assert.True(history.Undo()); Assert.True(w.BitEquals(s1));
        Assert.True(history.Undo()); Assert.True(w.BitEquals(s0));
        Assert.False(history.Undo());
        Assert.True(history.Redo()); Assert.True(w.BitEquals(s1));
        Assert.True(history.Redo()); Assert.True(w.BitEquals(s2));
        Assert.True(history.Redo()); Assert.True(w.BitEquals(s3));
        Assert.False(history.Redo());
        Assert.Same(history, scene.GetComponent<EditHistory>());
    }

    [Fact]
    public void RegrowBringsCutStrandsBackFromTheGroomAndUndoesExactly()
    {
        var (scene, front, _) = Scene();
        var w = scene.World;
        var groom = GroomBuilder.Build(new GroomSettings { SheetCount = 24, StrandsPerSheet = 6, ParticlesPerStrand = 12 });
        var history = new EditHistory();
        history.Do(HairEditor.Cut(scene, new Stroke([new Vector2(0, 380), new Vector2(600, 360)], front), new CutOptions { Reach = CutReach.AllThrough }));
        var cut = w.Clone();
        Assert.True(w.TotalRestLength() < groom.TotalRestLength() - 0.01);
        history.Do(HairEditor.Regrow(scene, groom));
        Assert.Equal(groom.TotalRestLength(), w.TotalRestLength(), 6);
        for (int s = 0; s < w.StrandCount; s++)
        {
            Assert.Equal(groom.StrandCapacity[s], w.StrandParticleCount[s]);
            for (int k = 0; k < w.StrandCapacity[s]; k++)
            {
                int i = w.StrandFirst[s] + k;
                Assert.Equal(groom.GetRest(i), w.GetRest(i));
                Assert.Equal(groom.ShapeNext[i], w.ShapeNext[i]);
                Assert.Equal(w.Head.TransformPoint(w.GetRest(i)), w.GetPosition(i));
            }
        }
        history.Undo();
        Assert.True(w.BitEquals(cut));
        Assert.Throws<ArgumentException>(() => HairEditor.Regrow(scene, new HairWorld(2, 2, 4)));
    }

    [Fact]
    public void BakeRestPoseMakesTheSettledShapeTheRestShapeWithoutMovingAnything()
    {
        var (scene, _, _) = Scene();
        var w = scene.World;
        w.PlaceHead(new RigidTransform(new Vector3(0.2f, 0.1f, 0), Quaternion.CreateFromAxisAngle(Vector3.UnitX, 0.3f)));
        var before = w.Clone();
        var history = new EditHistory();
        history.Do(HairEditor.BakeRestPose(scene));
        for (int i = 0; i < w.ParticleCount; i++)
        {
            Assert.Equal(before.GetPosition(i), w.GetPosition(i));
            Assert.Equal(before.GetVelocity(i), w.GetVelocity(i));
        }
        bool anyBend = false;
        for (int s = 0; s < w.StrandCount; s++)
            for (int k = 0; k < w.StrandParticleCount[s]; k++)
            {
                int i = w.StrandFirst[s] + k;
                Assert.True(Vector3.Distance(w.Head.TransformPoint(w.GetRest(i)), w.GetPosition(i)) < 1e-5f);
                anyBend |= w.ShapeBend[i] > 1e-4f;
            }
        Assert.True(anyBend, "the hanging (bent) shape was not taken into the rest shape");
        history.Undo();
        Assert.True(w.BitEquals(before));
    }

    [Fact]
    public void MemoryPerCommandIsTheAffectedStrandsOnlyAndHistoryStaysWithinItsBound()
    {
        var (scene, front, _) = Scene();
        var w = scene.World;
        var cmd = HairEditor.Cut(scene, new Stroke([new Vector2(250, 380), new Vector2(330, 370)], front), new CutOptions { Reach = CutReach.AllThrough });
        Assert.True(cmd.Strands.Count > 0);
        Assert.Equal(0 + 4L * cmd.Strands.Count + 64L * cmd.Strands.Count, cmd.MemoryBytes); // plan only, before applying
        cmd.Apply();
        long particles = 0;
        foreach (int s in cmd.Strands) particles += w.StrandCapacity[s];
        long snapshot = 4L * w.Buffers().Length * particles + 8L * cmd.Strands.Count; // floats + strand ids + counts
        Assert.Equal(2 * snapshot + 4L * cmd.Strands.Count + 64L * cmd.Strands.Count, cmd.MemoryBytes);
        Assert.True(cmd.MemoryBytes < 0.2 * 4L * 15 * w.ParticleCount * 2, "a partial cut should cost far less than two whole-world copies");
        cmd.Revert();

        // A bound of 1.5 commands keeps only the newest one.
        var history = new EditHistory((long)(cmd.MemoryBytes * 1.5));
        for (int k = 0; k < 3; k++)
        {
            history.Do(HairEditor.Cut(scene, new Stroke([new Vector2(250, 380 - 20 * k), new Vector2(330, 370 - 20 * k)], front), new CutOptions { Reach = CutReach.AllThrough }));
            Assert.True(history.MemoryBytes <= history.MaxBytes);
        }
        Assert.True(history.UndoCount >= 1 && history.UndoCount < 3);
        Assert.Equal(3, history.UndoCount + history.Forgotten);
        // An edit that changes nothing is not recorded.
        Assert.False(history.Do(HairEditor.Cut(scene, new Stroke([new Vector2(0, 2), new Vector2(5, 2)], front))));
    }

    [Fact]
    public void UndoAfterTheHeadMovedCarriesTheRestoredStrandsWithTheHead()
    {
        var (scene, front, _) = Scene();
        var w = scene.World;
        var history = new EditHistory();
        var before = w.Clone();
        history.Do(HairEditor.Cut(scene, new Stroke([new Vector2(0, 380), new Vector2(600, 360)], front), new CutOptions { Reach = CutReach.AllThrough }));
        var pose = new RigidTransform(new Vector3(0.1f, 0.2f, 0), Quaternion.CreateFromAxisAngle(Vector3.UnitY, 0.5f));
        w.PlaceHead(pose);
        history.Undo();
        var delta = RigidTransform.Delta(before.Head, pose);
        for (int s = 0; s < w.StrandCount; s += 7)
        {
            int tip = before.TipIndex(s);
            Assert.Equal(before.StrandParticleCount[s], w.StrandParticleCount[s]);
            Assert.True(Vector3.Distance(delta.TransformPoint(before.GetPosition(tip)), w.GetPosition(tip)) < 1e-5f);
        }
    }
}
