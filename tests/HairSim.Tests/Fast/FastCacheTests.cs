using System.Numerics;
using HairSim;
using HairSim.Fast;

namespace HairSim.Tests.Fast;

/// <summary>
/// What the fast systems cache until the world's edit stamp changes: head follow, each strand's pinned particles (up
/// to two, with their rest positions); shape matching, whether each strand's rest shape is bent. Edits between frames
/// (marked) must be followed, and the bits must equal runs without the caches.
/// </summary>
public class FastCacheTests
{
    private static PipelineBuilder Scanning()
    {
        var b = PipelineBuilder.CreateDefault();
        foreach (var f in b.Factories.ToArray())
            if (f.Name == HeadFollowSystem.SystemName) b.Replace(f with { CreateFast = s => new FastHeadFollowSystem(s.World, cachePins: false) });
        return b;
    }

    [Theory]
    [InlineData(1)]
    [InlineData(2)]
    [InlineData(3)] // more than the cache holds
    public void CachedPinsGiveTheBitsOfScanning(int pinned)
    {
        var g = new GroomSettings { SheetCount = 8, StrandsPerSheet = 6, ParticlesPerStrand = 16, PinnedPerStrand = pinned };
        var cached = GroomBuilder.BuildScene(g, new SimulationSettings());
        var scanned = GroomBuilder.BuildScene(g, new SimulationSettings());
        var simC = new HairSimulation(cached);
        var simS = new HairSimulation(scanned, Scanning());
        for (int f = 1; f <= 8; f++)
        {
            simC.Step(1f / 60f, FastPathScenes.HeadAt(f));
            simS.Step(1f / 60f, FastPathScenes.HeadAt(f));
        }
        Assert.True(cached.World.BitEquals(scanned.World));
        Assert.False(GroomBuilder.BuildScene(g, new SimulationSettings()).World.BitEquals(cached.World));
    }

    [Fact]
    public void PinsEditedBetweenFramesAreFollowed()
    {
        var g = new GroomSettings { SheetCount = 4, StrandsPerSheet = 6, ParticlesPerStrand = 16 };
        var scene = GroomBuilder.BuildScene(g, new SimulationSettings());
        var reference = GroomBuilder.BuildScene(g, new SimulationSettings { Path = SolverPath.Reference });
        var sim = new HairSimulation(scene);
        var simR = new HairSimulation(reference);
        for (int f = 1; f <= 4; f++) { sim.Step(1f / 60f, FastPathScenes.HeadAt(f, teleport: false)); simR.Step(1f / 60f, FastPathScenes.HeadAt(f, teleport: false)); }
        // Pin every strand's tip where its rest pose is (and move the rest pose of strand 0's tip), as a tool would.
        foreach (var w in new[] { scene.World, reference.World })
        {
            for (int s = 0; s < w.StrandCount; s++) w.InvMass[w.StrandFirst[s] + w.StrandParticleCount[s] - 1] = 0f;
            int tip0 = w.StrandFirst[0] + w.StrandParticleCount[0] - 1;
            w.RestX[tip0] += 0.01f;
            w.MarkEdited();
        }
        for (int f = 5; f <= 6; f++) { sim.Step(1f / 60f, FastPathScenes.HeadAt(f, teleport: false)); simR.Step(1f / 60f, FastPathScenes.HeadAt(f, teleport: false)); }
        var head = scene.World.Head;
        for (int s = 0; s < scene.World.StrandCount; s++)
        {
            int tip = scene.World.StrandFirst[s] + scene.World.StrandParticleCount[s] - 1;
            var expected = head.TransformPoint(scene.World.GetRest(tip));
            Assert.True(Vector3.Distance(expected, scene.World.GetPosition(tip)) < 1e-6f, $"strand {s}: tip not at its pin");
            Assert.Equal(Vector3.Zero, scene.World.GetVelocity(tip));
        }
        Assert.True(FastPathScenes.MaxPositionDifference(reference.World, scene.World) < FastVsReferenceTests.FramePositionTolerance);
    }

    [Fact]
    public void RestShapeBentBetweenFramesIsFollowed()
    {
        var g = new GroomSettings { SheetCount = 4, StrandsPerSheet = 6, ParticlesPerStrand = 16 };
        var fast = GroomBuilder.BuildScene(g, new SimulationSettings());
        var reference = GroomBuilder.BuildScene(g, new SimulationSettings { Path = SolverPath.Reference });
        var uncached = GroomBuilder.BuildScene(g, new SimulationSettings());
        var b = PipelineBuilder.CreateDefault();
        foreach (var f in b.Factories.ToArray())
            if (f.Name == ShapeMatchSystem.SystemName) b.Replace(f with { CreateFast = s => new FastShapeMatchSystem(s.World.MaxStrandCapacity) });
        var sims = new[] { new HairSimulation(fast), new HairSimulation(reference), new HairSimulation(uncached, b) };
        for (int f = 1; f <= 3; f++) foreach (var sim in sims) sim.Step(1f / 60f, FastPathScenes.HeadAt(f, teleport: false));
        // Curl strand 2's rest shape (SetStrand marks the world edited), as a fit would.
        foreach (var w in new[] { fast.World, reference.World, uncached.World })
        {
            int first = w.StrandFirst[2];
            var root = w.GetRest(first);
            var dir = Vector3.Normalize(w.GetRest(first + 1) - root);
            var side = Vector3.Normalize(Vector3.Cross(dir, Vector3.UnitZ));
            var pts = new Vector3[16];
            for (int k = 0; k < 16; k++) pts[k] = root + dir * (0.016f * k) + side * (0.01f * (1 - MathF.Cos(0.5f * k)));
            w.SetStrand(2, pts, pinned: 1);
        }
        Assert.NotEqual(0f, fast.World.ShapeBend[fast.World.StrandFirst[2] + 5]);
        for (int f = 4; f <= 8; f++) foreach (var sim in sims) sim.Step(1f / 60f, FastPathScenes.HeadAt(f, teleport: false));
        Assert.True(fast.World.BitEquals(uncached.World), "the cached bend flags changed the result");
        Assert.True(FastPathScenes.MaxPositionDifference(reference.World, fast.World) < FastVsReferenceTests.FramePositionTolerance);
    }
}
