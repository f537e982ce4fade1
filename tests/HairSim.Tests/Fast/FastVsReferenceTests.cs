using HairSim;
using HairSim.Fast;
using Xunit.Abstractions;

namespace HairSim.Tests.Fast;

/// <summary>
/// The fast path (float, SIMD) against the reference path (double inside each system, float storage) on the
/// same input. Tolerances:
/// - One system, one frame: float carries ~6e-8 relative error per operation, ~2e-8 m on positions of ~0.3 m;
///   the reference rounds to float after every system too, so one system over one frame (4 substeps) differs by
///   a few roundings. Bound 2e-6 m (~70 float ulps at 0.3 m). Velocities: shape matching scales position
///   differences by α/h = 240 /s, so 2e-6 m becomes ~5e-4 m/s; bound 2e-3 m/s.
/// - Whole frames: the difference starts at float rounding and grows roughly linearly (~1e-6 m per frame in
///   these scenes: Müller shape matching puts a particle exactly on its goal, so goal roundings land in the
///   position and nothing pulls the two runs back together) until some particle sits within that distance of
///   a collider surface and is inside in one run and outside in the other; from then on the two runs differ by a
///   contact response (millimetres) — divergence of a chaotic system, not an error of either path. So the
///   particle-wise bound, 1e-4 m (0.1 mm, 1/160 of a segment), is checked over the first 10 frames (40 substeps,
///   including a teleport), before any contact flip in these scenes; a wrong term (missing goal, wrong mask,
///   wrong fallback) moves particles by millimetres within a frame or two.
/// - Long runs (120 frames): statistics that do not depend on individual contact flips must agree: the
///   hair's centroid within 0.5 mm and the length ratio (total length / rest length) within 1e-4.
/// </summary>
public class FastVsReferenceTests(ITestOutputHelper output)
{
    public const float SystemPositionTolerance = 2e-6f;
    public const float SystemVelocityTolerance = 2e-3f;
    public const float FramePositionTolerance = 1e-4f;

    public static TheoryData<string> Scenes()
    {
        var d = new TheoryData<string>();
        foreach (var n in FastPathScenes.Names) d.Add(n);
        return d;
    }

    public static TheoryData<string, string> SystemsAndScenes()
    {
        var d = new TheoryData<string, string>();
        string[] systems = [HeadFollowSystem.SystemName, ShapeMatchSystem.SystemName, IntegrateSystem.SystemName, BendSystem.SystemName, LengthSystem.SystemName, CollideSystem.SystemName, SegmentCollideSystem.SystemName];
        foreach (var s in systems)
            foreach (var n in FastPathScenes.Names) d.Add(s, n);
        return d;
    }

    [Theory]
    [MemberData(nameof(Scenes))]
    public void WholeFramesMatchReference(string scene)
    {
        var reference = FastPathScenes.Build(scene, SolverPath.Reference);
        var fast = FastPathScenes.Build(scene, SolverPath.Fast);
        using var dispatcher = new ParallelDispatcher(2);
        var simR = new HairSimulation(reference);
        var simF = new HairSimulation(fast, dispatcher: dispatcher);
        Assert.Equal(simR.Pipeline.SystemNames, simF.Pipeline.SystemNames);
        Assert.All(simF.Pipeline.Systems.Where(s => s.Phase == SystemPhase.Substep), s => Assert.StartsWith("Fast", s.GetType().Name));
        float worst = 0f;
        bool teleported = false;
        for (int f = 1; f <= 10; f++)
        {
            simR.Step(1f / 60f, FastPathScenes.HeadAt(f));
            simF.Step(1f / 60f, FastPathScenes.HeadAt(f));
            teleported |= simF.Pipeline.LastFrame.Teleported;
            worst = MathF.Max(worst, FastPathScenes.MaxPositionDifference(reference.World, fast.World));
        }
        output.WriteLine($"{scene}: max position difference over 10 frames {worst:E2} m");
        Assert.True(teleported, "the head path includes a teleport frame");
        Assert.Equal(0, fast.World.CountNonFinite());
        Assert.True(worst <= FramePositionTolerance, $"fast differs from reference by {worst:E3} m");
        // The comparison is not vacuous: the hair moved by far more than the tolerance.
        var rest = FastPathScenes.Build(scene, SolverPath.Reference);
        Assert.True(FastPathScenes.MaxPositionDifference(rest.World, fast.World) > 100 * FramePositionTolerance);
    }

    [Theory]
    [MemberData(nameof(SystemsAndScenes))]
    public void EachSystemMatchesReference(string system, string scene)
    {
        // A moving state first (reference path), so velocities, contacts and bends are all non-trivial.
        var start = FastPathScenes.Build(scene, SolverPath.Reference);
        var warm = new HairSimulation(start);
        for (int f = 1; f <= 12; f++) warm.Step(1f / 60f, FastPathScenes.HeadAt(f, teleport: false));

        var reference = FastPathScenes.Build(scene, SolverPath.Reference);
        var fast = FastPathScenes.Build(scene, SolverPath.Fast);
        start.World.CopyTo(reference.World);
        start.World.CopyTo(fast.World);
        var full = PipelineBuilder.CreateDefault();
        var only = new PipelineBuilder();
        foreach (var f in full.Factories) if (f.Name == system) only.Add(f);
        var pr = only.Build(reference);
        var pf = only.Build(fast, new ParallelDispatcher(2));
        if (!pr.Contains(system))
        {
            Assert.False(pf.Contains(system));
            return; // not in this scene's pipeline (e.g. Length with LengthMode.None, Collide without colliders)
        }
        Assert.StartsWith("Fast", pf.Systems[0].GetType().Name);
        // A moving head; for HeadFollow in some scenes the teleport frame (every particle carried rigidly).
        int frame = system == HeadFollowSystem.SystemName && scene is "straight" or "cut" or "odd-lengths" ? FastPathScenes.TeleportFrame : 13;
        var head = FastPathScenes.HeadAt(frame, teleport: frame == FastPathScenes.TeleportFrame);
        pr.Step(1f / 60f, head);
        pf.Step(1f / 60f, head);
        Assert.Equal(pr.LastFrame.Teleported, pf.LastFrame.Teleported);
        float dx = FastPathScenes.MaxPositionDifference(reference.World, fast.World);
        float dv = FastPathScenes.MaxVelocityDifference(reference.World, fast.World);
        output.WriteLine($"{system} on {scene}: |Δx| {dx:E2} m, |Δv| {dv:E2} m/s");
        Assert.True(dx <= SystemPositionTolerance, $"positions differ by {dx:E3} m");
        Assert.True(dv <= SystemVelocityTolerance, $"velocities differ by {dv:E3} m/s");
        // Particles past a cut are never touched (except carried rigidly on a teleport frame).
        if (!pf.LastFrame.Teleported)
        for (int s = 0; s < fast.World.StrandCount; s++)
            for (int k = fast.World.StrandParticleCount[s]; k < fast.World.StrandCapacity[s]; k++)
            {
                int i = fast.World.StrandFirst[s] + k;
                Assert.Equal(start.World.GetPosition(i), fast.World.GetPosition(i));
            }
    }

    [Theory]
    [InlineData("straight")]
    [InlineData("cut")]
    [InlineData("bent")]
    [InlineData("all-colliders")]
    [InlineData("pbd")]
    [InlineData("planes")]
    public void LongRunStatisticsMatchReference(string scene)
    {
        var reference = FastPathScenes.Build(scene, SolverPath.Reference);
        var fast = FastPathScenes.Build(scene, SolverPath.Fast);
        using var dispatcher = new ParallelDispatcher(2);
        var simR = new HairSimulation(reference);
        var simF = new HairSimulation(fast, dispatcher: dispatcher);
        for (int f = 1; f <= 120; f++)
        {
            simR.Step(1f / 60f, FastPathScenes.HeadAt(f, teleport: false));
            simF.Step(1f / 60f, FastPathScenes.HeadAt(f, teleport: false));
        }
        var mr = WorldMetrics.Measure(reference);
        var mf = WorldMetrics.Measure(fast);
        float centroid = System.Numerics.Vector3.Distance(FastPathScenes.Centroid(reference.World), FastPathScenes.Centroid(fast.World));
        output.WriteLine($"{scene}: centroid Δ {centroid:E2} m, length ratio {mr.LengthRatio:F6} vs {mf.LengthRatio:F6}, " +
                         $"rms Δ {FastPathScenes.RmsPositionDifference(reference.World, fast.World):E2} m, penetration {mr.MaxPenetration:E2} vs {mf.MaxPenetration:E2}");
        Assert.Equal(0, mf.NonFinite);
        Assert.True(centroid <= 5e-4f, $"centroids differ by {centroid:E3} m");
        Assert.True(Math.Abs(mr.LengthRatio - mf.LengthRatio) <= 1e-4, $"length ratios {mr.LengthRatio} vs {mf.LengthRatio}");
    }
}
