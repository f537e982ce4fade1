using System.Numerics;

namespace HairSim.Tests.Core;

public class DeterminismTests
{
    private static HairWorld Run(SolverPath path)
    {
        var scene = GroomBuilder.BuildScene(TestWorlds.SmallGroom(), TestWorlds.Settings(s => s.Path = path));
        scene.Render = new RenderSettings();
        var sim = new HairSimulation(scene);
        for (int f = 0; f < 45; f++)
            sim.Step(1f / 60f, new RigidTransform(new Vector3(0, 0, 0.002f * f), Quaternion.CreateFromAxisAngle(Vector3.UnitY, 0.01f * f)));
        return scene.World;
    }

    [Theory]
    [InlineData(SolverPath.Reference)]
    [InlineData(SolverPath.Fast)]
    public void SameInputGivesTheSameOutputBitForBit(SolverPath path)
    {
        var a = Run(path);
        var b = Run(path);
        Assert.True(a.BitEquals(b));
        Assert.Equal(0, a.CountNonFinite());
    }

    [Fact]
    public void SameSeedSameGroomDifferentSeedDifferentRoots()
    {
        var g = TestWorlds.SmallGroom();
        Assert.True(GroomBuilder.Build(g).BitEquals(GroomBuilder.Build(g)));
        var other = g.Clone();
        other.Seed = 99;
        Assert.False(GroomBuilder.Build(g).BitEquals(GroomBuilder.Build(other)));
    }
}
