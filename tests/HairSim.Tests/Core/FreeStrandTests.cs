using System.Numerics;
using HairSim.Tests.Fast;

namespace HairSim.Tests.Core;

/// <summary>
/// Free strands (no pinned particle: a clipping, a loose hair): built with <c>SetStrand(…, pinned: 0)</c>, they fall as a
/// whole, collide, keep their lengths and shape, and conserve momentum through the solver's sweeps, on both paths.
/// </summary>
public class FreeStrandTests
{
    private const int N = 16;
    private const float Segment = 0.0125f; // 18.75 cm strands

    /// <summary>One free straight strand, horizontal along x, centred above the origin at height y0 (world = head space).</summary>
    private static HairScene Straight(SolverPath path, float y0, BendModel bend = BendModel.RestShape, Action<SimulationSettings>? settings = null, int strands = 1)
    {
        var w = new HairWorld(1, strands, N);
        var pts = new Vector3[N];
        for (int s = 0; s < strands; s++)
        {
            for (int k = 0; k < N; k++) pts[k] = new Vector3((k - (N - 1) / 2f) * Segment, y0, 0.03f * s);
            w.SetStrand(s, pts, pinned: 0);
        }
        var st = new SimulationSettings { Path = path, Bend = bend };
        settings?.Invoke(st);
        return new HairScene(w, st);
    }

    [Fact]
    public void SetStrand_takes_zero_pinned_particles_and_refuses_negative_counts()
    {
        var w = new HairWorld(1, 2, 5);
        var pts = Enumerable.Range(0, 5).Select(k => new Vector3(0.01f * k, 0, 0)).ToArray();
        w.SetStrand(0, pts, pinned: 0);
        Assert.All(Enumerable.Range(0, 5), k => Assert.Equal(1f, w.InvMass[k]));
        Assert.True(w.IsFreeStrand(0));
        Assert.True(w.IsFreeStrand(1)); // a new world's particles all have inverse mass 1: free until SetStrand pins some
        w.SetStrand(1, pts, pinned: 1);
        Assert.False(w.IsFreeStrand(1));
        Assert.Equal(1, w.FreeStrandCount);
        var before = w.Clone();
        Assert.Throws<ArgumentOutOfRangeException>(() => w.SetStrand(0, pts, pinned: -1));
        Assert.Throws<ArgumentOutOfRangeException>(() => w.SetStrand(0, pts, pinned: 6));
        Assert.True(w.BitEquals(before));
        // A cut that leaves only free particles makes a strand free; the flag follows the edit stamp.
        w.InvMass[w.StrandFirst[1]] = 1f;
        w.MarkEdited();
        Assert.Equal(2, w.FreeStrandCount);
    }

    [Theory]
    [InlineData(SolverPath.Reference, BendModel.RestShape)]
    [InlineData(SolverPath.Fast, BendModel.RestShape)]
    [InlineData(SolverPath.Reference, BendModel.Limp)]
    [InlineData(SolverPath.Fast, BendModel.Limp)]
    [InlineData(SolverPath.Reference, BendModel.SourceTriples)]
    [InlineData(SolverPath.Fast, BendModel.SourceTriples)]
    public void A_free_strand_falls_as_a_whole_under_gravity(SolverPath path, BendModel bend)
    {
        // No drag, no collider: every particle falls g·t²/2 and the strand stays straight and level.
        var scene = Straight(path, 0f, bend, st => st.Damping = 0f);
        scene.ClearColliders();
        var sim = new HairSimulation(scene);
        var w = scene.World;
        const int frames = 30;
        int n = 0;
        for (int f = 0; f < frames; f++) { sim.Step(1f / 60f); n += sim.Pipeline.LastFrame.Substeps; }
        // Semi-implicit Euler's free fall after n substeps of h: v = −g·h·n, y = −g·h²·n(n+1)/2 (g·t²/2 to within 1/n).
        double h = frames / 60.0 / n, g = 9.81, expectedY = -g * h * h * n * (n + 1) / 2, expectedV = -g * h * n;
        for (int k = 0; k < N; k++)
        {
            var p = w.GetPosition(k);
            Assert.True(Math.Abs(p.Y - expectedY) < 1e-4 * Math.Abs(expectedY), $"{bend}: particle {k} at y = {p.Y}, free fall gives {expectedY:F5}");
            Assert.True(MathF.Abs(p.X - (k - (N - 1) / 2f) * Segment) < 1e-5f, $"{bend}: particle {k} moved sideways to x = {p.X}");
            Assert.True(Math.Abs(w.VelY[k] - expectedV) < 1e-4 * Math.Abs(expectedV), $"{bend}: particle {k} falls at {w.VelY[k]} m/s, free fall gives {expectedV:F4}");
        }
    }

    public static TheoryData<SolverPath, BendModel, LengthMode> Models()
    {
        var d = new TheoryData<SolverPath, BendModel, LengthMode>();
        foreach (var path in new[] { SolverPath.Reference, SolverPath.Fast })
        {
            d.Add(path, BendModel.RestShape, LengthMode.FollowTheLeader);
            d.Add(path, BendModel.Limp, LengthMode.FollowTheLeader);
            d.Add(path, BendModel.Limp, LengthMode.Pbd);
        }
        return d;
    }

    [Theory]
    [MemberData(nameof(Models))]
    public void The_sweeps_keep_a_free_strands_momentum(SolverPath path, BendModel bend, LengthMode length)
    {
        // No gravity, no drag, no collider, no speed limit: whatever the length and bend passes do to a tumbling free strand
        // is internal, so its total momentum stays what it was (a sweep that never moved the root and did not share its
        // corrections out would drag the strand towards its root end).
        var scene = Straight(path, 0f, bend, st => { st.Gravity = Vector3.Zero; st.Damping = 0f; st.MaxSpeed = 0f; st.Length = length; });
        scene.ClearColliders();
        var w = scene.World;
        var rng = new Random(5);
        for (int k = 0; k < N; k++) w.SetVelocity(k, 0.2f * new Vector3(rng.NextSingle() - 0.5f, rng.NextSingle() - 0.5f, rng.NextSingle() - 0.5f));
        Vector3 Momentum() { var m = Vector3.Zero; for (int k = 0; k < N; k++) m += w.GetVelocity(k); return m; }
        var before = Momentum();
        var sim = new HairSimulation(scene);
        for (int f = 0; f < 20; f++) sim.Step(1f / 60f);
        var after = Momentum();
        Assert.True(Vector3.Distance(before, after) < 1e-4f, $"momentum {before} became {after}");
        Assert.Equal(0, w.CountNonFinite());
        // Lengths by Gauss–Seidel constraints (free strands have no root to sweep from), against the stiff default bend
        // constraints: within one per cent while tumbling from this start (each particle flung at up to 0.17 m/s, three
        // hundredths of a segment per substep); a start five times as violent leaves segments up to 1.1 % off.
        float worst = 0f;
        for (int k = 1; k < N; k++) worst = MathF.Max(worst, MathF.Abs(Vector3.Distance(w.GetPosition(k), w.GetPosition(k - 1)) / Segment - 1f));
        Assert.True(worst < 1e-2f, $"a segment is {worst:P3} off its length");
    }

    private static HairScene OnSphere(SolverPath path)
    {
        // A straight free strand 5 cm above a 10 cm ball fixed in the world, dropped; static friction holds it where it
        // lands (a frictionless straight rod on top of a ball is balanced on a point and slides off either way).
        var scene = Straight(path, 0.15f, settings: st => st.StaticFriction = 1f);
        scene.AddCollider(Collider.Sphere(Vector3.Zero, 0.1f).InWorldSpace());
        return scene;
    }

    [Theory]
    [InlineData(SolverPath.Reference)]
    [InlineData(SolverPath.Fast)]
    public void A_free_strand_dropped_on_a_ball_comes_to_rest_on_it(SolverPath path)
    {
        var scene = OnSphere(path);
        var sim = new HairSimulation(scene);
        var w = scene.World;
        for (int f = 0; f < 150; f++) sim.Step(1f / 60f);
        var settled = w.Clone();
        for (int f = 0; f < 30; f++) sim.Step(1f / 60f);
        Assert.Equal(0, w.CountNonFinite());
        float nearest = float.MaxValue, moved = 0f, worstLength = 0f;
        for (int k = 0; k < N; k++)
        {
            var p = w.GetPosition(k);
            nearest = MathF.Min(nearest, p.Length());
            moved = MathF.Max(moved, Vector3.Distance(p, settled.GetPosition(k)));
            if (k > 0) worstLength = MathF.Max(worstLength, MathF.Abs(Vector3.Distance(p, w.GetPosition(k - 1)) / Segment - 1f));
        }
        // On the ball (touching it, not in it), still, whole, and on top of it (it did not slide off).
        Assert.InRange(nearest, 0.1f - 1e-4f, 0.1f + 1e-3f);
        Assert.True(moved < 1e-4f, $"still moving: {moved * 1000:F3} mm in half a second");
        // Collision runs after the constraints and pushes the draped segments out radially: a few per cent at most there,
        // the strand as a whole within one per cent.
        Assert.True(worstLength < 3e-2f, $"a segment is {worstLength:P2} off its length");
        double total = 0;
        for (int k = 1; k < N; k++) total += Vector3.Distance(w.GetPosition(k), w.GetPosition(k - 1));
        Assert.InRange(total / ((N - 1) * Segment), 0.99, 1.01);
        Assert.True(w.GetPosition(N / 2).Y > 0.095f, $"the middle is at {w.GetPosition(N / 2)}: the strand slid off");
        // It rests draped: the ends hang lower than the middle.
        Assert.True(w.PosY[0] < w.PosY[N / 2] && w.PosY[N - 1] < w.PosY[N / 2]);
    }

    [Fact]
    public void Both_paths_drop_a_free_strand_on_a_ball_the_same_way()
    {
        var a = OnSphere(SolverPath.Reference);
        var b = OnSphere(SolverPath.Fast);
        var ra = new HairSimulation(a);
        var rb = new HairSimulation(b);
        float worst = 0f;
        for (int f = 0; f < 180; f++)
        {
            ra.Step(1f / 60f); rb.Step(1f / 60f);
            worst = MathF.Max(worst, FastPathScenes.MaxPositionDifference(a.World, b.World));
        }
        // The free sweep is the same double code on both paths; integration and collision are float on the fast one.
        Assert.True(worst < 1e-3f, $"paths differ by {worst * 1000:F3} mm");
    }

    [Theory]
    [InlineData(SolverPath.Reference)]
    [InlineData(SolverPath.Fast)]
    public void A_free_strand_dropped_on_a_floor_lies_flat_on_it(SolverPath path)
    {
        var scene = Straight(path, 0.05f, strands: 3);
        // Tilted as it falls: one end lands first.
        var w = scene.World;
        for (int s = 0; s < 3; s++)
            for (int k = 0; k < N; k++) w.SetPosition(w.StrandFirst[s] + k, w.GetPosition(w.StrandFirst[s] + k) + new Vector3(0f, 0.02f * k / N, 0f));
        scene.AddCollider(Collider.Plane(new Vector3(0f, -0.1f, 0f), Vector3.UnitY).InWorldSpace());
        var sim = new HairSimulation(scene);
        for (int f = 0; f < 180; f++) sim.Step(1f / 60f);
        Assert.Equal(0, w.CountNonFinite());
        for (int i = 0; i < w.ParticleCount; i++)
            Assert.True(MathF.Abs(w.PosY[i] + 0.1f) < 1e-3f, $"particle {i} at height {w.PosY[i]}: not lying on the floor");
    }

    [Fact]
    public void Free_strands_among_held_ones_match_the_reference_path_and_leave_strand_chunks_to_the_others()
    {
        HairScene Build(SolverPath path)
        {
            var scene = FastPathScenes.Build("rest", path);
            var w = scene.World;
            // Runs of eight strands cut loose where they hang (their rest shape kept): chunks holding one go system by system.
            for (int s = 0; s < w.StrandCount; s++)
                if (s % 48 >= 40)
                w.SetStrand(s, Enumerable.Range(0, w.StrandParticleCount[s]).Select(k => w.GetRest(w.StrandFirst[s] + k)).ToArray(), pinned: 0);
            return scene;
        }
        var reference = Build(SolverPath.Reference);
        var fast = Build(SolverPath.Fast);
        var simR = new HairSimulation(reference);
        var simF = new HairSimulation(fast);
        float worst = 0f;
        for (int f = 1; f <= 10; f++)
        {
            simR.Step(1f / 60f, FastPathScenes.HeadAt(f, teleport: false));
            simF.Step(1f / 60f, FastPathScenes.HeadAt(f, teleport: false));
            worst = MathF.Max(worst, FastPathScenes.MaxPositionDifference(reference.World, fast.World));
        }
        Assert.True(worst <= FastVsReferenceTests.FramePositionTolerance, $"fast differs from reference by {worst:E3} m");
        Assert.Equal(0, fast.World.CountNonFinite());
        if (HairSim.Fast.FastPathInfo.Avx512) Assert.True(simF.Pipeline.LastFrameChunks.Stepped > 0, "the held strands still ride in chunks");
        // The free strands fell away from the head: their roots are lower than where they were cut.
        for (int s = 0; s < fast.World.StrandCount; s++)
            if (s % 48 >= 40) Assert.True(fast.World.PosY[fast.World.StrandFirst[s]] < fast.World.Head.TransformPoint(fast.World.GetRest(fast.World.StrandFirst[s])).Y - 0.01f);
    }
}
