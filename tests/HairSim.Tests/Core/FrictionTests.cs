using System.Numerics;
using HairSim;
using HairSim.Fast;
using HairSim.Measurement;
using HairSim.Tests.Fast;
using Xunit.Abstractions;

namespace HairSim.Tests.Core;

/// <summary>
/// Coulomb friction against colliders (<see cref="SimulationSettings.StaticFriction"/>,
/// <see cref="SimulationSettings.KineticFriction"/>), position-based as in Macklin et al. 2014 §6.1, on both paths.
/// With both 0 the collide systems run their old code unchanged (the rest of the suite checks those bits).
/// </summary>
[Collection(nameof(AllocationCollection))]
public class FrictionTests(ITestOutputHelper output)
{
    private const float SphereRadius = 0.1f;
    /// <summary>Polar angle of the latitude the strand is laid along: a 35° slope (tan 35° = 0.70).</summary>
    private const float Slope = 35f * MathF.PI / 180f;

    public static TheoryData<SolverPath> Paths => new() { SolverPath.Reference, SolverPath.Fast };

    /// <summary>
    /// A limp 16-particle strand laid along a latitude circle of a sphere (a 35° slope), half way round, 1 mm off
    /// the surface, root pinned. Frictionless, gravity slides it down the sphere (it swings round its root and ends
    /// hanging off the side); μs = 1 (above tan 35°) holds it.
    /// </summary>
    private static HairScene StrandOnSphere(SolverPath path, float muS, float muK)
    {
        var w = new HairWorld(1, 1, 16);
        var pts = new Vector3[16];
        float r = SphereRadius + 0.001f;
        for (int k = 0; k < pts.Length; k++)
        {
            float az = MathF.PI * k / (pts.Length - 1);
            pts[k] = new Vector3(r * MathF.Sin(Slope) * MathF.Cos(az), r * MathF.Cos(Slope), r * MathF.Sin(Slope) * MathF.Sin(az));
        }
        w.SetStrand(0, pts, pinned: 1);
        var st = new SimulationSettings { Path = path, Bend = BendModel.Limp, StaticFriction = muS, KineticFriction = muK };
        var scene = new HairScene(w, st);
        // A sphere made as an ellipsoid: the particle test only (SegmentCollideSystem, frictionless, also pushes the
        // segments of a strand lying on a Collider.Sphere out of it and would hold the particles just off the surface).
        scene.AddCollider(Collider.Ellipsoid(Vector3.Zero, new Vector3(SphereRadius)));
        return scene;
    }

    /// <summary>Steps a scene at 60 Hz for <paramref name="seconds"/>; the largest distance any particle moved from its start.</summary>
    private static float MaxTravel(HairScene scene, float seconds)
    {
        var start = Positions(scene.World);
        var sim = new HairSimulation(scene);
        for (int f = 0; f < (int)MathF.Round(seconds * 60f); f++) sim.Step(1f / 60f);
        Assert.Equal(0, scene.World.CountNonFinite());
        var end = Positions(scene.World);
        float max = 0f;
        for (int i = 0; i < start.Length; i++) max = MathF.Max(max, Vector3.Distance(start[i], end[i]));
        return max;
    }

    private static Vector3[] Positions(HairWorld w)
    {
        var p = new Vector3[w.ParticleCount];
        for (int i = 0; i < p.Length; i++) p[i] = w.GetPosition(i);
        return p;
    }

    [Theory]
    [MemberData(nameof(Paths))]
    public void StaticFrictionHoldsAStrandThatSlidesOffWithout(SolverPath path)
    {
        float free = MaxTravel(StrandOnSphere(path, 0f, 0f), 1.5f);
        float held = MaxTravel(StrandOnSphere(path, 1f, 1f), 3f);
        output.WriteLine($"{path}: frictionless strand moved {free * 1000:F1} mm in 1.5 s; with μs = μk = 1 {held * 1000:F2} mm in 3 s");
        Assert.True(free > 0.05f, $"frictionless, the strand only moved {free * 1000:F1} mm");
        Assert.True(held < 0.003f, $"with static friction the strand moved {held * 1000:F2} mm");
    }

    [Theory]
    [MemberData(nameof(Paths))]
    public void KineticFrictionSlowsTheSlide(SolverPath path)
    {
        const float t = 0.2f;
        float free = MaxTravel(StrandOnSphere(path, 0f, 0f), t);
        float kinetic = MaxTravel(StrandOnSphere(path, 0f, 0.3f), t);
        output.WriteLine($"{path}: in {t} s the strand's tip slid {free * 1000:F1} mm frictionless, {kinetic * 1000:F1} mm with μk = 0.3");
        Assert.True(kinetic > 0.005f, "with kinetic friction only the strand still slides");
        Assert.True(kinetic < 0.85f * free, $"kinetic friction did not slow the slide ({kinetic * 1000:F1} vs {free * 1000:F1} mm)");
    }

    [Theory]
    [MemberData(nameof(Paths))]
    public void GroomMovesLessOnTheHeadWithFriction(SolverPath path)
    {
        double free = MeanTravel(new SimulationSettings { Path = path, Bend = BendModel.Limp }, 2f);
        double held = MeanTravel(new SimulationSettings { Path = path, Bend = BendModel.Limp, StaticFriction = 1f, KineticFriction = 0.8f }, 2f);
        output.WriteLine($"{path}: small groom, mean displacement after 2 s {free * 1000:F1} mm frictionless, {held * 1000:F1} mm with μs 1, μk 0.8");
        Assert.True(held < free, $"friction did not hold the groom ({held * 1000:F1} vs {free * 1000:F1} mm)");
    }

    private static double MeanTravel(SimulationSettings settings, float seconds)
    {
        var scene = GroomBuilder.BuildScene(CanonicalCases.SmallGroom(), settings);
        var start = Positions(scene.World);
        var sim = new HairSimulation(scene);
        for (int f = 0; f < (int)MathF.Round(seconds * 60f); f++) sim.Step(1f / 60f);
        Assert.Equal(0, scene.World.CountNonFinite());
        double sum = 0; int n = 0;
        var w = scene.World;
        for (int s = 0; s < w.StrandCount; s++)
            for (int i = w.StrandFirst[s]; i < w.StrandFirst[s] + w.StrandParticleCount[s]; i++, n++)
                sum += Vector3.Distance(start[i], w.GetPosition(i));
        return sum / n;
    }

    private static void SetFriction(HairScene scene, float muS, float muK)
    {
        scene.Settings.StaticFriction = muS;
        scene.Settings.KineticFriction = muK;
        scene.SettingsChanged();
    }

    [Theory]
    [InlineData("rest", 1f, 0.8f)]
    [InlineData("rest", 0.3f, 0.3f)]
    [InlineData("all-colliders", 1f, 0.8f)]
    [InlineData("rotated-ellipsoid", 0.5f, 0.4f)]
    [InlineData("limp", 0f, 0.5f)]
    [InlineData("limp", 1f, 0.8f)]
    public void FastMatchesReferenceWithFriction(string name, float muS, float muK)
    {
        var reference = FastPathScenes.Build(name, SolverPath.Reference);
        var fast = FastPathScenes.Build(name, SolverPath.Fast);
        SetFriction(reference, muS, muK);
        SetFriction(fast, muS, muK);
        using var dispatcher = new ParallelDispatcher(2);
        var simR = new HairSimulation(reference);
        var simF = new HairSimulation(fast, dispatcher: dispatcher);
        float worst = 0f;
        for (int f = 1; f <= 10; f++)
        {
            simR.Step(1f / 60f, FastPathScenes.HeadAt(f));
            simF.Step(1f / 60f, FastPathScenes.HeadAt(f));
            worst = MathF.Max(worst, FastPathScenes.MaxPositionDifference(reference.World, fast.World));
        }
        // Friction changed the motion (so the comparison covers it).
        var frictionless = FastPathScenes.Build(name, SolverPath.Reference);
        var simN = new HairSimulation(frictionless);
        for (int f = 1; f <= 10; f++) simN.Step(1f / 60f, FastPathScenes.HeadAt(f));
        float effect = FastPathScenes.MaxPositionDifference(frictionless.World, reference.World);
        output.WriteLine($"{name}, μs {muS}, μk {muK}: fast vs reference {worst:E2} m over 10 frames; friction moved particles by up to {effect:E2} m");
        Assert.Equal(0, fast.World.CountNonFinite());
        Assert.True(worst <= FastVsReferenceTests.FramePositionTolerance, $"fast differs from reference by {worst:E3} m");
        // The draped "rest" groom holds its shape off the head: friction changes little there in 10 frames.
        if (name != "rest") Assert.True(effect > 10 * FastVsReferenceTests.FramePositionTolerance, $"friction changed nothing ({effect:E2} m)");
    }

    /// <summary>Friction turned on and off every few frames (stored start positions go stale and come back) on both paths.</summary>
    [Fact]
    public void FastMatchesReferenceWhenFrictionIsToggled()
    {
        var reference = FastPathScenes.Build("limp", SolverPath.Reference);
        var fast = FastPathScenes.Build("limp", SolverPath.Fast);
        var simR = new HairSimulation(reference);
        var simF = new HairSimulation(fast);
        float worst = 0f;
        for (int f = 1; f <= 12; f++)
        {
            float mu = f / 3 % 2 == 0 ? 0f : 1f;
            SetFriction(reference, mu, 0.8f * mu);
            SetFriction(fast, mu, 0.8f * mu);
            simR.Step(1f / 60f, FastPathScenes.HeadAt(f, teleport: false));
            simF.Step(1f / 60f, FastPathScenes.HeadAt(f, teleport: false));
            worst = MathF.Max(worst, FastPathScenes.MaxPositionDifference(reference.World, fast.World));
        }
        output.WriteLine($"friction toggled every 3 frames: fast vs reference {worst:E2} m over 12 frames");
        Assert.True(worst <= FastVsReferenceTests.FramePositionTolerance, $"fast differs from reference by {worst:E3} m");
    }

    /// <summary>
    /// The collide system alone over one frame from a moving state (as FastVsReferenceTests.EachSystemMatchesReference),
    /// friction on: every kernel (sphere, capsule, rotated ellipsoid) within the one-system tolerances.
    /// </summary>
    [Theory]
    [InlineData("sphere", 1f, 0.8f)]
    [InlineData("capsule", 1f, 0.8f)]
    [InlineData("capsule", 0f, 0.5f)]
    [InlineData("rotated-ellipsoid", 0.5f, 0.4f)]
    [InlineData("all-colliders", 2f, 1f)]
    [InlineData("rest", 1f, 0.8f)]
    public void FastCollideMatchesReferenceCollideWithFriction(string name, float muS, float muK)
    {
        var start = FastPathScenes.Build(name, SolverPath.Reference);
        var warm = new HairSimulation(start);
        for (int f = 1; f <= 12; f++) warm.Step(1f / 60f, FastPathScenes.HeadAt(f, teleport: false));
        var reference = FastPathScenes.Build(name, SolverPath.Reference);
        var fast = FastPathScenes.Build(name, SolverPath.Fast);
        start.World.CopyTo(reference.World);
        start.World.CopyTo(fast.World);
        SetFriction(reference, muS, muK);
        SetFriction(fast, muS, muK);
        var only = new PipelineBuilder();
        foreach (var f in PipelineBuilder.CreateDefault().Factories) if (f.Name == CollideSystem.SystemName) only.Add(f);
        var pr = only.Build(reference);
        using var dispatcher = new ParallelDispatcher(2);
        var pf = only.Build(fast, dispatcher);
        Assert.StartsWith("Fast", pf.Systems[0].GetType().Name);
        var frictionless = FastPathScenes.Build(name, SolverPath.Reference);
        start.World.CopyTo(frictionless.World);
        var pn = only.Build(frictionless);
        float dx = 0f, dv = 0f;
        for (int f = 13; f <= 15; f++)
        {
            var head = FastPathScenes.HeadAt(f, teleport: false);
            pr.Step(1f / 60f, head);
            pf.Step(1f / 60f, head);
            pn.Step(1f / 60f, head);
            dx = MathF.Max(dx, FastPathScenes.MaxPositionDifference(reference.World, fast.World));
            dv = MathF.Max(dv, FastPathScenes.MaxVelocityDifference(reference.World, fast.World));
        }
        float effect = FastPathScenes.MaxPositionDifference(frictionless.World, reference.World);
        output.WriteLine($"Collide on {name}, μs {muS}, μk {muK}: |Δx| {dx:E2} m, |Δv| {dv:E2} m/s over 3 frames; friction's effect {effect:E2} m");
        Assert.True(dx <= 3 * FastVsReferenceTests.SystemPositionTolerance, $"positions differ by {dx:E3} m");
        Assert.True(dv <= 3 * FastVsReferenceTests.SystemVelocityTolerance, $"velocities differ by {dv:E3} m/s");
    }

    [Theory]
    [InlineData("sphere")]
    [InlineData("capsule")]
    [InlineData("all-colliders")]
    [InlineData("rotated-ellipsoid")]
    [InlineData("rest")]
    [InlineData("cut")]
    public void WidePathGivesTheBitsOfTheNarrowPathWithFriction(string name)
    {
        var wide = FastPathScenes.Build(name, SolverPath.Fast);
        var narrow = FastPathScenes.Build(name, SolverPath.Fast);
        var plain = FastPathScenes.Build(name, SolverPath.Fast);
        foreach (var s in new[] { wide, narrow, plain }) SetFriction(s, 1f, 0.8f);
        using var dispatcher = new ParallelDispatcher(2);
        var simW = new HairSimulation(wide, dispatcher: dispatcher);
        var simN = new HairSimulation(narrow, PipelineBuilder.CreateDefault(allowAvx512: false), dispatcher);
        var simP = new HairSimulation(plain, dispatcher: dispatcher);
        simP.Pipeline.UseStrandChunks = false;
        int chunks = 0;
        for (int f = 1; f <= 12; f++)
        {
            simW.Step(1f / 60f, FastPathScenes.HeadAt(f));
            simN.Step(1f / 60f, FastPathScenes.HeadAt(f));
            simP.Step(1f / 60f, FastPathScenes.HeadAt(f));
            chunks += simW.Pipeline.LastFrameChunks.Stepped;
            Assert.True(wide.World.BitEquals(narrow.World), $"{name}: 16-lane and 8-lane paths differ after frame {f}");
            Assert.True(wide.World.BitEquals(plain.World), $"{name}: chunked and system-by-system paths differ after frame {f}");
        }
        output.WriteLine($"{name}: 16-lane {(FastPathInfo.Avx512 ? "on" : "not available")}, {chunks} chunks stepped with friction");
        // A chunk has no rows for the start-of-substep positions: friction frames step system by system.
        Assert.Equal(0, chunks);
    }

    [Theory]
    [InlineData("all-colliders", SolverPath.Fast)]
    [InlineData("limp", SolverPath.Fast)]
    [InlineData("rest", SolverPath.Fast)]
    [InlineData("limp", SolverPath.Reference)]
    public void StepWithFrictionAllocatesNothing(string name, SolverPath path)
    {
        var s = FastPathScenes.Build(name, path);
        SetFriction(s, 1f, 0.8f);
        var sim = new HairSimulation(s);
        for (int f = 1; f <= 40; f++) sim.Step(1f / 60f, FastPathScenes.HeadAt(f));
        long before = GC.GetAllocatedBytesForCurrentThread();
        for (int f = 41; f <= 60; f++) sim.Step(1f / 60f, FastPathScenes.HeadAt(f));
        Assert.Equal(0, GC.GetAllocatedBytesForCurrentThread() - before);
    }

    [Theory]
    [InlineData(-0.1f)]
    [InlineData(10.5f)]
    [InlineData(float.NaN)]
    public void FrictionOutOfRangeIsRefused(float mu)
    {
        Assert.Throws<ArgumentOutOfRangeException>(() => new SimulationSettings { StaticFriction = mu }.Validate());
        Assert.Throws<ArgumentOutOfRangeException>(() => new SimulationSettings { KineticFriction = mu }.Validate());
        new SimulationSettings { StaticFriction = 10f, KineticFriction = 0f }.Validate();
    }
}
