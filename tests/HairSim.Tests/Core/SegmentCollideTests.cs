using System.Numerics;
using Xunit.Abstractions;

namespace HairSim.Tests.Core;

/// <summary>
/// Colliders thinner than a segment: a 1 cm bar under strands of 16 particles and 25 cm (segments of 1.67 cm). The
/// particle test alone lets a strand fall through between two particles; the segment test catches it.
/// </summary>
public class SegmentCollideTests(ITestOutputHelper output)
{
    private const float BarRadius = 0.005f;

    /// <summary>
    /// Free strands (nothing pinned) lying across the bar (along x, the bar along z), 3 cm above it and a little off
    /// centre, dropped; limp, so only the bar can hold them.
    /// </summary>
    private static HairScene Scene(SolverPath path)
    {
        var w = new HairWorld(1, 5, 16);
        var pts = new Vector3[16];
        for (int s = 0; s < 5; s++)
        {
            for (int k = 0; k < 16; k++) pts[k] = new Vector3(-0.12f + 0.25f * k / 15f, 0.03f, 0.02f * (s - 2));
            w.SetStrand(s, pts, pinned: 1);
            w.InvMass[w.StrandFirst[s]] = 1f; // dropped: the root is free too
        }
        w.MarkEdited();
        // PBD lengths: symmetric, so a free strand has no leading end (follow-the-leader would let its root fall through first).
        var scene = new HairScene(w, new SimulationSettings { Path = path, Bend = BendModel.Limp, Length = LengthMode.Pbd, LengthIterations = 8 });
        scene.AddCollider(Collider.Capsule(new Vector3(0, 0, -0.2f), new Vector3(0, 0, 0.2f), BarRadius));
        return scene;
    }

    private static float Highest(HairWorld w, int s)
    {
        float y = float.MinValue;
        for (int k = 0; k < w.StrandParticleCount[s]; k++) y = MathF.Max(y, w.PosY[w.StrandFirst[s] + k]);
        return y;
    }

    /// <summary>Smallest distance of any live segment from the bar's axis (the z axis).</summary>
    private static double Closest(HairWorld w)
    {
        double best = double.MaxValue;
        for (int s = 0; s < w.StrandCount; s++)
            for (int k = 1; k < w.StrandParticleCount[s]; k++)
            {
                // In the x-y plane the bar is a point: the segment's distance to the origin.
                var a = w.GetPosition(w.StrandFirst[s] + k - 1); var b = w.GetPosition(w.StrandFirst[s] + k);
                var p = new Vector2(a.X, a.Y); var q = new Vector2(b.X, b.Y);
                var d = q - p;
                float t = d.LengthSquared() > 0 ? Math.Clamp(-Vector2.Dot(p, d) / d.LengthSquared(), 0f, 1f) : 0f;
                best = Math.Min(best, (p + d * t).Length());
            }
        return best;
    }

    [Theory]
    [InlineData(SolverPath.Reference)]
    [InlineData(SolverPath.Fast)]
    public void StrandsDroppedOnAThinBarDrapeOverItInsteadOfPassingThrough(SolverPath path)
    {
        var scene = Scene(path);
        var sim = new HairSimulation(scene);
        Assert.Contains(SegmentCollideSystem.SystemName, sim.Pipeline.SystemNames);
        double closest = double.MaxValue;
        for (int f = 0; f < 120; f++)
        {
            sim.Step(1f / 60f);
            closest = Math.Min(closest, Closest(scene.World));
        }
        var w = scene.World;
        // Caught: the strand hangs over the bar, its highest particle on top of it; one that fell through keeps falling.
        int caught = 0;
        for (int s = 0; s < w.StrandCount; s++) if (Highest(w, s) > 0f) caught++;
        output.WriteLine($"strand 0: highest particle at y = {Highest(w, 0) * 1000:F1} mm, ends at {w.GetPosition(w.RootIndex(0))} and {w.GetPosition(w.TipIndex(0))}");
        output.WriteLine($"{path}: closest segment to the bar's axis {closest * 1000:F2} mm (radius {BarRadius * 1000} mm), {caught} of {w.StrandCount} strands hang over it");
        Assert.True(closest > 0.9 * BarRadius, $"a segment passed {closest * 1000:F2} mm from the axis of a {BarRadius * 1000} mm bar");
        Assert.Equal(w.StrandCount, caught);
        Assert.Equal(0, w.CountNonFinite());
    }

    [Fact]
    public void WithoutTheSegmentTestTheStrandsFallThroughTheBar()
    {
        // The same scene with the particle test only: the point of the segment test.
        var scene = Scene(SolverPath.Reference);
        var builder = new PipelineBuilder();
        foreach (var f in PipelineBuilder.CreateDefault().Factories) if (f.Name != SegmentCollideSystem.SystemName) builder.Add(f);
        var sim = new HairSimulation(scene, builder);
        for (int f = 0; f < 120; f++) sim.Step(1f / 60f);
        var w = scene.World;
        int caught = 0;
        for (int s = 0; s < w.StrandCount; s++) if (Highest(w, s) > 0f) caught++;
        Assert.True(caught < w.StrandCount, "the particle test alone held every strand; the scene does not test the segment test");
    }

    [Fact]
    public void OnlyScenesWithCollidersThinnerThanASegmentRunIt()
    {
        // Segments of 1.67 cm: a 5 cm sphere (shoulder-sized) is held by the particle test, a 5 mm one is not.
        var head = GroomBuilder.BuildScene(HairSim.Measurement.CanonicalCases.SmallGroom());
        Assert.DoesNotContain(SegmentCollideSystem.SystemName, new HairSimulation(head).Pipeline.SystemNames);
        head.AddCollider(Collider.Sphere(new Vector3(0, -0.2f, 0), 0.05f));
        Assert.DoesNotContain(SegmentCollideSystem.SystemName, new HairSimulation(head).Pipeline.SystemNames);
        head.AddCollider(Collider.Capsule(new Vector3(-0.1f, -0.2f, 0.1f), new Vector3(0.1f, -0.2f, 0.1f), 0.005f));
        Assert.Contains(SegmentCollideSystem.SystemName, new HairSimulation(head).Pipeline.SystemNames);
    }

    [Fact]
    public void FastPathMatchesTheReferenceOnOneFrame()
    {
        // Strands half-way onto the bar (the reference path's state after 0.4 s), then one frame of the segment test
        // alone on each path.
        var start = Scene(SolverPath.Reference);
        var warm = new HairSimulation(start);
        for (int frame = 0; frame < 24; frame++) warm.Step(1f / 60f);
        var only = new PipelineBuilder();
        foreach (var factory in PipelineBuilder.CreateDefault().Factories) if (factory.Name == SegmentCollideSystem.SystemName) only.Add(factory);
        HairWorld Step(SolverPath path)
        {
            var scene = Scene(path);
            start.World.CopyTo(scene.World);
            // Push the strands 3 mm into the bar so the test has contacts to resolve.
            for (int i = 0; i < scene.World.ParticleCount; i++) scene.World.PosY[i] -= 0.003f;
            only.Build(scene).Step(1f / 60f, RigidTransform.Identity);
            return scene.World;
        }
        var r = Step(SolverPath.Reference);
        var fast = Step(SolverPath.Fast);
        float dx = HairSim.Tests.Fast.FastPathScenes.MaxPositionDifference(r, fast);
        var moved = Scene(SolverPath.Reference).World;
        start.World.CopyTo(moved);
        for (int i = 0; i < moved.ParticleCount; i++) moved.PosY[i] -= 0.003f;
        float pushed = HairSim.Tests.Fast.FastPathScenes.MaxPositionDifference(moved, r);
        output.WriteLine($"segment test, one frame: pushed up to {pushed * 1000:F2} mm, fast differs by {dx:E2} m");
        Assert.True(pushed > 1e-4f, "no segment was pushed");
        Assert.True(dx <= 2e-6f, $"fast differs from reference by {dx:E3} m");
    }
}
