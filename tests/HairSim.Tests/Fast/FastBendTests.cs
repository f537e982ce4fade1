using System.Numerics;
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

    /// <summary>
    /// 64 strands whose rows take the 16-lane sweep's rare paths, which it skips when a whole row is ordinary. The
    /// first chunk of 32: a segment turned back against its target (the frame's flip, strands 0–7), a pin half way
    /// down (8–15), speeds over the limit (16–23), a free strand (24). The second: a zero-length segment (32–39) and
    /// strands of other lengths (40–63: the rows past their tips have no rest direction). The head stays still.
    /// </summary>
    private static HairScene RarePathScene()
    {
        var w = new HairWorld(8, 8, 16);
        var rest = new Vector3[16];
        var start = new Vector3[16];
        for (int s = 0; s < w.StrandCount; s++)
        {
            int n = s >= 40 ? 6 + s % 11 : 16;
            bool flip = s < 8, zeroLength = s is >= 32 and < 40;
            var x0 = new Vector3(0.02f * (s % 8), 0.3f, 0.02f * (s / 8));
            for (int k = 0; k < n; k++)
            {
                rest[k] = x0 + (flip || zeroLength ? new Vector3(0, -0.015f * k, 0) : new Vector3(0.002f * k * (s % 3), -0.015f * k, 0.001f * k * (s % 2)));
                // Folded back up from particle 8 on (0.4° off straight up), or particle 8 on particle 7.
                start[k] = flip && k >= 8 ? 2 * rest[7] - rest[k] + new Vector3(1e-4f * (k - 7), 0, 0) : zeroLength && k == 8 ? rest[7] : rest[k];
            }
            w.SetStrand(s, rest.AsSpan(0, n), start.AsSpan(0, n), pinned: s == 24 ? 0 : flip || zeroLength ? 8 : 1, straightRestShape: s % 4 == 0);
        }
        for (int s = 8; s < 16; s++) w.InvMass[w.StrandFirst[s] + 8] = 0f;
        for (int s = 16; s < 24; s++) w.SetVelocity(w.StrandFirst[s] + 5 + s % 8, new Vector3(300f, -200f, 100f));
        w.MarkEdited();
        return new HairScene(w, new SimulationSettings { Path = SolverPath.Fast });
    }

    [Fact]
    public void WideSweepGivesTheBitsOfTheNarrowSweepOnItsRarePaths()
    {
        // The 8-lane sweep system by system is the reference; the 16-lane sweep runs in strand chunks (each row
        // integrated in the sweep) and system by system (the sweep alone).
        var narrow = RarePathScene();
        var chunked = RarePathScene();
        var plain = RarePathScene();
        var simN = new HairSimulation(narrow, NarrowBend());
        var simC = new HairSimulation(chunked);
        var simP = new HairSimulation(plain);
        simN.Pipeline.UseStrandChunks = false;
        simP.Pipeline.UseStrandChunks = false;
        Assert.Contains(simP.Pipeline.Systems, s => s is FastBendSystem { UsesWide: var w } && w == FastPathInfo.Avx512);
        for (int f = 1; f <= 12; f++)
        {
            simN.Step(1f / 60f, RigidTransform.Identity);
            simC.Step(1f / 60f, RigidTransform.Identity);
            simP.Step(1f / 60f, RigidTransform.Identity);
            Assert.Equal(0, narrow.World.CountNonFinite());
            Assert.True(chunked.World.BitEquals(narrow.World), $"the chunked sweep differs after frame {f}");
            Assert.True(plain.World.BitEquals(narrow.World), $"the sweep system by system differs after frame {f}");
        }
        if (FastPathInfo.Avx512) Assert.True(simC.Pipeline.LastFrameChunks.Stepped > 0, "no strand chunk was stepped");
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
