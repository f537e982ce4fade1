using System.Numerics;

namespace HairSim.Tests.Core;

public class CatmullRomTests
{
    [Fact]
    public void PassesThroughItsControlPoints()
    {
        var rng = new Random(3);
        Vector3 R() => new((float)rng.NextDouble(), (float)rng.NextDouble(), (float)rng.NextDouble());
        for (int i = 0; i < 200; i++)
        {
            Vector3 p0 = R(), p1 = R(), p2 = R(), p3 = R();
            Assert.True(Vector3.Distance(p1, CatmullRom.Evaluate(p0, p1, p2, p3, 0f)) < 1e-5f);
            Assert.True(Vector3.Distance(p2, CatmullRom.Evaluate(p0, p1, p2, p3, 1f)) < 1e-5f);
        }
    }

    [Fact]
    public void EvenlySpacedCollinearPointsGiveAStraightEvenCurve()
    {
        var p = new Vector3[] { new(0, 0, 0), new(1, 0, 0), new(2, 0, 0), new(3, 0, 0) };
        for (int k = 0; k <= 10; k++)
        {
            var q = CatmullRom.Evaluate(p[0], p[1], p[2], p[3], k / 10f);
            Assert.Equal(1f + k / 10f, q.X, 5);
            Assert.Equal(0f, q.Y, 6);
        }
    }

    [Fact]
    public void CoincidentControlPointsGiveFiniteValues()
    {
        var a = new Vector3(1, 2, 3);
        for (int k = 0; k <= 4; k++)
        {
            var q = CatmullRom.Evaluate(a, a, a, a, k / 4f);
            Assert.Equal(a, q);
            var r = CatmullRom.Evaluate(a, a, new Vector3(2, 2, 3), new Vector3(2, 2, 3), k / 4f);
            Assert.True(float.IsFinite(r.X) && float.IsFinite(r.Y) && float.IsFinite(r.Z));
        }
    }

    [Fact]
    public void CentripetalCurveHasNoCuspWhereUniformWould()
    {
        // Uneven spacing with a sharp turn: the curve between p1 and p2 stays close to the chord.
        var p0 = new Vector3(0, 0, 0); var p1 = new Vector3(1, 0, 0); var p2 = new Vector3(1.1f, 0.02f, 0); var p3 = new Vector3(0, 1, 0);
        float maxDev = 0;
        for (int k = 0; k <= 50; k++)
        {
            var q = CatmullRom.Evaluate(p0, p1, p2, p3, k / 50f);
            maxDev = MathF.Max(maxDev, MathF.Min(Vector3.Distance(q, p1), Vector3.Distance(q, p2)));
        }
        Assert.True(maxDev < Vector3.Distance(p1, p2), $"stays near the short segment: {maxDev}");
    }

    [Fact]
    public void RenderStrandsIncludeSimulatedStrandsAndFollowACut()
    {
        var scene = GroomBuilder.BuildScene(TestWorlds.SmallGroom(), TestWorlds.Settings());
        scene.Render = new RenderSettings { StrandsPerGap = 3 };
        var w = scene.World;
        // Shorten strand 1 of sheet 0, as a cut would.
        w.StrandParticleCount[1] = 4;
        var sim = new HairSimulation(scene);
        sim.Step(1f / 60f);
        var r = scene.RenderOutput!;
        // Render strand 0 is simulated strand 0, render strand 4 is simulated strand 1.
        Assert.Equal(w.GetStrandPositions(0), r.Strand(0).ToArray());
        Assert.Equal(w.GetStrandPositions(1), r.Strand(4).ToArray());
        // Between a full strand (10) and the cut one (4) the lengths step down.
        Assert.Equal(new[] { 10, 9, 7, 6, 4 }, r.Counts.AsSpan(0, 5).ToArray());
        int sum = 0;
        foreach (int c in r.Counts) sum += c;
        Assert.Equal(sum, r.TotalPoints);
        foreach (var p in r.Points.AsSpan(0, r.Stride * 5))
            Assert.True(float.IsFinite(p.X) && float.IsFinite(p.Y) && float.IsFinite(p.Z));
    }
}
