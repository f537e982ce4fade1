using HairSim;
using HairSim.Fast;

namespace HairSim.Tests.Fast;

/// <summary>
/// FastBendSystem sweeps 16-lane vectors where the CPU has AVX-512 and 8-lane vectors elsewhere, with the same
/// arithmetic in the same order: both must give the same bits on every scene of the default bend model (uniform
/// groups moved by transposes, cut and odd-length groups element by element, pins, styled rest shapes).
/// </summary>
public class FastBendTests
{
    public static IEnumerable<object[]> RestScenes()
    {
        foreach (var name in FastPathScenes.Names)
            if (FastPathScenes.IsRestShape(name)) yield return [name];
    }

    /// <summary>The default pipeline with the bend sweep kept to 8 lanes (everything else as the default).</summary>
    private static PipelineBuilder NarrowBend()
    {
        var b = PipelineBuilder.CreateDefault();
        foreach (var f in b.Factories.ToArray())
            if (f.Name == BendSystem.SystemName)
                b.Replace(f with { CreateFast = s => new FastBendSystem(s.World, allowWide: false) });
        return b;
    }

    [Theory]
    [MemberData(nameof(RestScenes))]
    public void WideSweepGivesTheBitsOfTheNarrowSweep(string scene)
    {
        var wide = FastPathScenes.Build(scene, SolverPath.Fast);
        var narrow = FastPathScenes.Build(scene, SolverPath.Fast);
        using var dispatcher = new ParallelDispatcher(2);
        var simW = new HairSimulation(wide, dispatcher: dispatcher);
        var simN = new HairSimulation(narrow, NarrowBend(), dispatcher);
        Assert.Contains(simN.Pipeline.Systems, s => s is FastBendSystem { UsesWide: false });
        Assert.Contains(simW.Pipeline.Systems, s => s is FastBendSystem { UsesWide: var w } && w == FastPathInfo.Avx512);
        for (int f = 1; f <= 12; f++)
        {
            simW.Step(1f / 60f, FastPathScenes.HeadAt(f));
            simN.Step(1f / 60f, FastPathScenes.HeadAt(f));
            Assert.True(wide.World.BitEquals(narrow.World), $"{scene}: the sweeps differ after frame {f}");
        }
        Assert.False(FastPathScenes.Build(scene, SolverPath.Fast).World.BitEquals(wide.World));
    }

    [Fact]
    public void NarrowAndDefaultPipelinesAgreeWithAvx512Off()
    {
        // CreateDefault(allowAvx512: false) keeps the other systems to 8 lanes; the bend sweep must not care.
        var a = FastPathScenes.Build("rest-cut", SolverPath.Fast);
        var b = FastPathScenes.Build("rest-cut", SolverPath.Fast);
        var simA = new HairSimulation(a, PipelineBuilder.CreateDefault(allowAvx512: false));
        var simB = new HairSimulation(b);
        for (int f = 1; f <= 8; f++)
        {
            simA.Step(1f / 60f, FastPathScenes.HeadAt(f));
            simB.Step(1f / 60f, FastPathScenes.HeadAt(f));
            Assert.True(a.World.BitEquals(b.World), $"the pipelines differ after frame {f}");
        }
    }
}
