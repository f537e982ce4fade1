using HairSim;
using HairSim.Fast;

namespace HairSim.Tests.Fast;

public class FastPathDefaultTests
{
    [Fact]
    public void DefaultSettingsBuildTheFastSystems()
    {
        var scene = GroomBuilder.BuildScene(new GroomSettings { SheetCount = 4, StrandsPerSheet = 4, ParticlesPerStrand = 8 });
        Assert.Equal(SolverPath.Fast, scene.Settings.Path);
        var sim = new HairSimulation(scene);
        var types = sim.Pipeline.Systems.Select(s => s.GetType()).ToArray();
        Assert.Equal(
            [typeof(FastHeadFollowSystem), typeof(FastIntegrateSystem), typeof(FastBendSystem), typeof(FastCollideSystem)],
            types);
    }

    [Fact]
    public void TheSourcesSchemeBuildsItsFastSystems()
    {
        var scene = GroomBuilder.BuildScene(new GroomSettings { SheetCount = 4, StrandsPerSheet = 4, ParticlesPerStrand = 8 },
            new SimulationSettings { Bend = BendModel.SourceTriples });
        var sim = new HairSimulation(scene);
        Assert.Equal(
            [typeof(FastHeadFollowSystem), typeof(FastShapeMatchSystem), typeof(FastIntegrateSystem), typeof(FastLengthSystem), typeof(FastCollideSystem)],
            sim.Pipeline.Systems.Select(s => s.GetType()).ToArray());
    }

    [Fact]
    public void ReferencePathStaysAvailable()
    {
        var scene = GroomBuilder.BuildScene(new GroomSettings { SheetCount = 4, StrandsPerSheet = 4, ParticlesPerStrand = 8 },
            new SimulationSettings { Path = SolverPath.Reference });
        var sim = new HairSimulation(scene);
        Assert.Equal(
            [typeof(HeadFollowSystem), typeof(IntegrateSystem), typeof(BendSystem), typeof(CollideSystem)],
            sim.Pipeline.Systems.Select(s => s.GetType()).ToArray());
    }
}
