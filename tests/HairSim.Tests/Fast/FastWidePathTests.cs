using System.Runtime.Intrinsics;
using System.Runtime.Intrinsics.X86;
using HairSim;
using HairSim.Fast;
using Xunit.Abstractions;

namespace HairSim.Tests.Fast;

/// <summary>
/// On CPUs with AVX-512 the fast systems take 16-lane paths where they can. Those paths do the same arithmetic in
/// the same order as the 8-lane paths (same reciprocal-square-root estimate), so a run with them must give exactly
/// the bits of a run with them turned off, in every scene (cuts, short and odd strands, bends, pins, all colliders).
/// The 8-lane path itself is checked against the reference path by <see cref="FastVsReferenceTests"/> on
/// machines without AVX-512, and here through this equality on machines with it.
/// </summary>
public class FastWidePathTests(ITestOutputHelper output)
{
    [Theory]
    [MemberData(nameof(FastVsReferenceTests.Scenes), MemberType = typeof(FastVsReferenceTests))]
    public void WidePathGivesTheBitsOfTheNarrowPath(string scene)
    {
        var wide = FastPathScenes.Build(scene, SolverPath.Fast);
        var narrow = FastPathScenes.Build(scene, SolverPath.Fast);
        using var dispatcher = new ParallelDispatcher(2);
        var simW = new HairSimulation(wide, dispatcher: dispatcher);
        var simN = new HairSimulation(narrow, PipelineBuilder.CreateDefault(allowAvx512: false), dispatcher);
        for (int f = 1; f <= 12; f++)
        {
            simW.Step(1f / 60f, FastPathScenes.HeadAt(f));
            simN.Step(1f / 60f, FastPathScenes.HeadAt(f));
            Assert.True(wide.World.BitEquals(narrow.World), $"{scene}: the paths differ after frame {f}");
        }
        Assert.False(FastPathScenes.Build(scene, SolverPath.Fast).World.BitEquals(wide.World));
        output.WriteLine($"{scene}: 16-lane paths {(WideExpected ? "on" : "not available on this CPU")}");
    }

    /// <summary>The 8-lane path with its register-only 16-particle strands on or off (everything else 8-lane too).</summary>
    private static PipelineBuilder Narrow(bool registerStrands)
    {
        var b = PipelineBuilder.CreateDefault(allowAvx512: false);
        foreach (var f in b.Factories.ToArray())
            if (f.Name == ShapeMatchSystem.SystemName)
                b.Replace(f with { CreateFast = s => new FastShapeMatchSystem(s.World.MaxStrandCapacity, allowWide: false, registerStrands) });
        return b;
    }

    [Theory]
    [MemberData(nameof(FastVsReferenceTests.Scenes), MemberType = typeof(FastVsReferenceTests))]
    public void RegisterStrandsGiveTheBitsOfTheGoalScratch(string scene)
    {
        var registers = FastPathScenes.Build(scene, SolverPath.Fast);
        var scratch = FastPathScenes.Build(scene, SolverPath.Fast);
        foreach (var w in new[] { registers.World, scratch.World })
        {
            // A triple whose ends coincide in a straight 16-particle strand that is not the world's first: the
            // register path must hand it to the general path (the reference's fallback axis).
            int f3 = w.StrandFirst[3];
            if (w.StrandParticleCount[3] == 16) w.SetPosition(f3 + 6, w.GetPosition(f3 + 4));
        }
        var simR = new HairSimulation(registers, Narrow(registerStrands: true));
        var simS = new HairSimulation(scratch, Narrow(registerStrands: false));
        for (int f = 1; f <= 12; f++)
        {
            simR.Step(1f / 60f, FastPathScenes.HeadAt(f));
            simS.Step(1f / 60f, FastPathScenes.HeadAt(f));
            Assert.True(registers.World.BitEquals(scratch.World), $"{scene}: the paths differ after frame {f}");
        }
        Assert.Equal(0, registers.World.CountNonFinite());
        Assert.False(FastPathScenes.Build(scene, SolverPath.Fast).World.BitEquals(registers.World));
    }

    private static bool WideExpected => Vector512.IsHardwareAccelerated && Avx512F.IsSupported && System.Numerics.Vector<float>.Count == 8;

    [Fact]
    public void WidePathIsUsedWhereTheCpuHasIt()
    {
        Assert.Equal(WideExpected, new FastShapeMatchSystem(16).UsesWide);
        Assert.False(new FastShapeMatchSystem(16, allowWide: false).UsesWide);
        Assert.Equal(WideExpected, new FastLengthSystem(16).UsesWide);
        Assert.False(new FastLengthSystem(16, allowWide: false).UsesWide);
        Assert.Equal(WideExpected, new FastIntegrateSystem().UsesWide);
        Assert.False(new FastIntegrateSystem(allowWide: false).UsesWide);
        // The switch reaches every system that has a 16-lane path.
        var scene = FastPathScenes.Build("straight", SolverPath.Fast);
        var narrow = PipelineBuilder.CreateDefault(allowAvx512: false).Build(scene);
        Assert.All(narrow.Systems, s => Assert.False(s is FastShapeMatchSystem { UsesWide: true } or FastLengthSystem { UsesWide: true } or FastCollideSystem { UsesWide: true } or FastIntegrateSystem { UsesWide: true }));
        var wide = PipelineBuilder.CreateDefault().Build(scene);
        Assert.Equal(WideExpected, wide.Systems.Any(s => s is FastCollideSystem { UsesWide: true }));
        Assert.Equal(WideExpected, wide.Systems.Any(s => s is FastIntegrateSystem { UsesWide: true }));
    }
}
