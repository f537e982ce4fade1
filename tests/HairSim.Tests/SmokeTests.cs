using HairSim;

namespace HairSim.Tests;

public class SmokeTests
{
    [Fact]
    public void SmallGroomSimulatesWithFiniteValues()
    {
        var g = new GroomSettings { SheetCount = 6, StrandsPerSheet = 4, ParticlesPerStrand = 8 };
        var scene = GroomBuilder.BuildScene(g);
        var sim = new HairSimulation(scene);
        for (int f = 0; f < 30; f++) sim.Step(1f / 60f);
        Assert.Equal(0, scene.World.CountNonFinite());
        Assert.Equal(6 * 4 * 8, scene.World.ParticleCount);
    }
}
