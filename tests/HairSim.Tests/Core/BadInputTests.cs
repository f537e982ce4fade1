using System.Numerics;

namespace HairSim.Tests.Core;

public class BadInputTests
{
    public static TheoryData<Action<GroomSettings>> BadGrooms => new()
    {
        g => g.SheetCount = 0,
        g => g.SheetCount = -3,
        g => g.StrandsPerSheet = 0,
        g => g.ParticlesPerStrand = 1,
        g => g.ParticlesPerStrand = -16,
        g => g.StrandLength = float.NaN,
        g => g.StrandLength = 0,
        g => g.StrandLength = -0.2f,
        g => g.StrandLength = float.PositiveInfinity,
        g => g.HeadRadii = new Vector3(0.1f, float.NaN, 0.1f),
        g => g.HeadRadii = new Vector3(0.1f, 0, 0.1f),
        g => g.RootJitter = float.NaN,
        g => g.PinnedPerStrand = 0,
        g => g.PinnedPerStrand = 16,
        g => g.ScalpAngleBack = float.NaN,
        // Absurd sizes: would need terabytes.
        g => { g.SheetCount = 1_000_000; g.StrandsPerSheet = 4096; g.ParticlesPerStrand = 4096; },
        g => { g.SheetCount = int.MaxValue; },
    };

    [Theory]
    [MemberData(nameof(BadGrooms))]
    public void BadGroomParametersThrowBeforeAllocating(Action<GroomSettings> spoil)
    {
        var g = TestWorlds.SmallGroom();
        spoil(g);
        long before = GC.GetAllocatedBytesForCurrentThread();
        var e = Assert.ThrowsAny<ArgumentException>(() => GroomBuilder.Build(g));
        long allocated = GC.GetAllocatedBytesForCurrentThread() - before;
        Assert.False(string.IsNullOrWhiteSpace(e.Message));
        Assert.True(allocated < 1 << 20, $"allocated {allocated} bytes before refusing");
    }

    [Fact]
    public void AbsurdWorldSizesAreRefused()
    {
        Assert.Throws<ArgumentOutOfRangeException>(() => new HairWorld(100_000, 4096, 4096));
        Assert.Throws<ArgumentOutOfRangeException>(() => new HairWorld(1, 1, 1));
        Assert.Throws<ArgumentOutOfRangeException>(() => new HairWorld(0, 1, 16));
        Assert.Throws<ArgumentException>(() => new HairWorld(new[] { 2 }, new[] { 16 }));
    }

    [Fact]
    public void BadStrandPointsLeaveTheWorldUnchanged()
    {
        var w = GroomBuilder.Build(TestWorlds.SmallGroom());
        var before = w.Clone();
        int n = w.StrandCapacity[3];
        var pts = new Vector3[n];
        for (int k = 0; k < n; k++) pts[k] = new Vector3(0, -0.01f * k, 0);

        var nan = (Vector3[])pts.Clone(); nan[4] = new Vector3(float.NaN, 0, 0);
        Assert.Throws<ArgumentException>(() => w.SetStrand(3, nan));
        var zeroEdge = (Vector3[])pts.Clone(); zeroEdge[5] = zeroEdge[4];
        Assert.Throws<ArgumentException>(() => w.SetStrand(3, zeroEdge));
        Assert.Throws<ArgumentException>(() => w.SetStrand(3, pts.AsSpan(0, 1)));
        Assert.Throws<ArgumentException>(() => w.SetStrand(3, new Vector3[n + 1]));
        Assert.Throws<ArgumentOutOfRangeException>(() => w.SetStrand(3, pts, pinned: -1));
        Assert.Throws<ArgumentOutOfRangeException>(() => w.SetStrand(w.StrandCount, pts));
        Assert.True(w.BitEquals(before));
    }

    [Fact]
    public void BadSettingsAndFrameTimesAreRefusedAndChangeNothing()
    {
        Assert.Throws<ArgumentOutOfRangeException>(() => new SimulationSettings { Alpha = float.NaN }.Validate());
        Assert.Throws<ArgumentOutOfRangeException>(() => new SimulationSettings { Substeps = 0 }.Validate());
        Assert.Throws<ArgumentException>(() => new SimulationSettings { Gravity = new Vector3(0, float.PositiveInfinity, 0) }.Validate());
        Assert.Throws<ArgumentOutOfRangeException>(() => new SimulationSettings { Damping = -1 }.Validate());
        Assert.Throws<ArgumentOutOfRangeException>(() => new RenderSettings { StrandsPerGap = -1 }.Validate());

        var scene = GroomBuilder.BuildScene(TestWorlds.SmallGroom(), TestWorlds.Settings());
        var sim = new HairSimulation(scene);
        sim.Step(1f / 60f);
        var before = scene.World.Clone();
        foreach (var dt in new[] { float.NaN, 0f, -1f / 60f, float.PositiveInfinity, 5f })
            Assert.Throws<ArgumentOutOfRangeException>(() => sim.Step(dt));
        Assert.Throws<ArgumentException>(() => new RigidTransform(new Vector3(float.NaN, 0, 0), Quaternion.Identity));
        Assert.Throws<ArgumentException>(() => new RigidTransform(Vector3.Zero, new Quaternion(0, 0, 0, 0)));
        Assert.True(scene.World.BitEquals(before));
    }
}
