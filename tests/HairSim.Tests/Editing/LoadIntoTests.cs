using System.Numerics;
using HairSim.IO;

namespace HairSim.Tests.Editing;

public class LoadIntoTests
{
    private static HairScene SmallScene() => GroomBuilder.BuildScene(new GroomSettings { SheetCount = 8, StrandsPerSheet = 4, ParticlesPerStrand = 8 },
        new SimulationSettings { Path = SolverPath.Reference });

    private static byte[] Bytes(HairScene scene)
    {
        using var ms = new MemoryStream();
        HairstyleFile.Save(scene, ms);
        return ms.ToArray();
    }

    [Fact]
    public void SavedStyleAppliedToTheSameGroomRestoresItExactly()
    {
        var styled = SmallScene();
        var sim = new HairSimulation(styled);
        for (int f = 0; f < 20; f++) sim.Step(1f / 60f);
        styled.World.StrandParticleCount[5] = 3;   // a cut
        var data = Bytes(styled);

        var fresh = SmallScene();
        HairstyleFile.LoadInto(fresh, data);
        Assert.True(fresh.World.BitEquals(styled.World));
        Assert.Equal(3, fresh.World.StrandParticleCount[5]);
    }

    [Fact]
    public void StyleIsCarriedToWhereTheHeadIsNow()
    {
        var styled = SmallScene();
        var data = Bytes(styled);
        var fresh = SmallScene();
        var head = new RigidTransform(new Vector3(1, 2, 3), Quaternion.CreateFromAxisAngle(Vector3.UnitY, 1f));
        fresh.World.PlaceHead(head);
        HairstyleFile.LoadInto(fresh, data);
        Assert.Equal(head, fresh.World.Head);
        int root = fresh.World.RootIndex(7);
        Assert.True(Vector3.Distance(head.TransformPoint(styled.World.GetPosition(root)), fresh.World.GetPosition(root)) < 1e-5f);
    }

    [Fact]
    public void StyleOfAnotherGroomOrCorruptBytesChangeNothing()
    {
        var other = GroomBuilder.BuildScene(new GroomSettings { SheetCount = 9, StrandsPerSheet = 4, ParticlesPerStrand = 8 });
        var data = Bytes(other);
        var scene = SmallScene();
        var before = scene.World.Clone();
        Assert.Throws<InvalidDataException>(() => HairstyleFile.LoadInto(scene, data));
        var corrupt = Bytes(SmallScene());
        corrupt[corrupt.Length / 2] ^= 0x5A;
        Assert.Throws<InvalidDataException>(() => HairstyleFile.LoadInto(scene, corrupt));
        Assert.True(scene.World.BitEquals(before));
    }
}
