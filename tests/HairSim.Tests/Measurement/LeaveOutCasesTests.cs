using HairSim.Measurement;

namespace HairSim.Tests.Measurement;

/// <summary>
/// Leaving systems out changes nothing but the time: each case's lean pipeline (only what the scene needs) and the
/// pipeline with every core system kept give the same bits, on both paths.
/// </summary>
public class LeaveOutCasesTests
{
    private static readonly string[] Core =
    [
        VolumeSystem.SystemName, HeadFollowSystem.SystemName, ShapeMatchSystem.SystemName, IntegrateSystem.SystemName, BendSystem.SystemName,
        LengthSystem.SystemName, CollideSystem.SystemName, HairSim.Meshes.MeshCollideSystem.SystemName, SegmentCollideSystem.SystemName, StrandContactSystem.SystemName,
        InterpolateSystem.SystemName,
    ];

    /// <summary>What a game character's hair needs with the default settings: no triples, lengths kept by the bend sweep.</summary>
    private static readonly string[] Character =
    [
        HeadFollowSystem.SystemName, IntegrateSystem.SystemName, BendSystem.SystemName, CollideSystem.SystemName, InterpolateSystem.SystemName,
    ];

    public static TheoryData<string, SolverPath> Cases()
    {
        var d = new TheoryData<string, SolverPath>();
        foreach (var c in LeaveOutCase.All)
            foreach (var p in new[] { SolverPath.Fast, SolverPath.Reference })
                d.Add(c.Name, p);
        return d;
    }

    private static GroomSettings Groom()
    {
        var g = GroomSettings.Reference();
        g.SheetCount = 3; // 120 strands of 16: several strand chunks on the fast path
        return g;
    }

    [Theory]
    [MemberData(nameof(Cases))]
    public void LeanAndKeptPipelinesGiveTheSameBits(string name, SolverPath path)
    {
        var c = LeaveOutCase.All.First(x => x.Name == name);
        var settings = new SimulationSettings { Path = path };
        var leanScene = c.BuildLean(Groom(), settings);
        var keptScene = c.BuildKept(Groom(), settings);
        var lean = new HairSimulation(leanScene);
        var kept = new HairSimulation(keptScene, LeaveOutCase.KeepEverything());
        Assert.Equal(Core, kept.Pipeline.SystemNames);

        float dt = 1f / 60f;
        for (int f = 0; f < 20; f++)
        {
            var head = HeadMotion.Shake((f + 1) * dt);
            lean.Step(dt, head);
            kept.Step(dt, head);
        }
        Assert.True(leanScene.World.BitEquals(keptScene.World), "keeping the unneeded systems changed the hair");
        Assert.Equal(0, leanScene.World.CountNonFinite());
        var start = c.BuildLean(Groom(), settings);
        Assert.False(start.World.BitEquals(leanScene.World), "the hair did not move");
    }

    [Fact]
    public void EachCaseLeavesOutWhatItsSceneLacks()
    {
        var settings = new SimulationSettings();
        string[] Names(string n) => [.. new HairSimulation(LeaveOutCase.All.First(x => x.Name == n).BuildLean(Groom(), settings)).Pipeline.SystemNames];
        Assert.Equal(Character, Names("game character"));
        Assert.Equal(Character[..4], Names("no render strands"));
        Assert.DoesNotContain(CollideSystem.SystemName, Names("no collider"));
        Assert.DoesNotContain(BendSystem.SystemName, Names("limp hair"));
        Assert.Contains(LengthSystem.SystemName, Names("limp hair"));
        Assert.DoesNotContain(LengthSystem.SystemName, Names("no length pass"));
        Assert.Equal([HeadFollowSystem.SystemName, IntegrateSystem.SystemName], Names("bare"));
        Assert.Equal([VolumeSystem.SystemName, .. Character], Names("hair volume"));
        foreach (var c in LeaveOutCase.All)
        {
            bool volume = c.Name.StartsWith("hair volume", StringComparison.Ordinal);
            Assert.Equal(c.Name switch { "game character" => 5, "limp hair" => 5, "bare" => 2, _ when volume => 6, _ => 4 }, Names(c.Name).Length);
            Assert.Equal(volume, Names(c.Name).Contains(VolumeSystem.SystemName)); // present only where asked for
        }
    }
}
