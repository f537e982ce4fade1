using System.Numerics;
using HairSim.Fast;
using Xunit;

namespace HairSim.Tests.Core;

/// <summary>
/// Colliders moved every frame with <see cref="HairScene.SetCollider"/>: no pipeline rebuild, carried across the substeps
/// from last frame's placement to this frame's (snapped on a teleport), on both paths, allocation-free.
/// </summary>
public class MovingColliderTests
{
    private const float Radius = 0.02f, BarY = -0.15f;

    /// <summary>A horizontal bar across the curtain at height <see cref="BarY"/>, at depth z, fixed in the world.</summary>
    private static Collider Bar(float z) =>
        Collider.Capsule(new Vector3(-0.2f, BarY, z), new Vector3(0.2f, BarY, z), Radius).InWorldSpace();

    private static float DeepestInside(HairWorld w, in Collider c)
    {
        float deepest = 0f;
        for (int i = 0; i < w.ParticleCount; i++) deepest = MathF.Max(deepest, c.Penetration(w.GetPosition(i)));
        return deepest;
    }

    [Fact]
    public void Moving_a_collider_keeps_the_pipeline_and_bad_moves_change_nothing()
    {
        var scene = SweptCurtain.Build(SolverPath.Fast);
        scene.AddCollider(Collider.Sphere(new Vector3(0f, 0.1f, 0f), 0.05f)); // thicker than a segment: no segment test
        scene.AddCollider(Bar(-0.06f));
        var sim = new HairSimulation(scene);
        sim.Step(1f / 60f);
        var pipeline = sim.Pipeline;
        int revision = scene.Revision;
        scene.SetCollider(1, Bar(-0.05f));
        scene.SetCollider(0, Collider.Sphere(new Vector3(0.01f, 0.1f, 0f), 0.06f).InWorldSpace()); // size and space may change
        sim.Step(1f / 60f);
        Assert.Same(pipeline, sim.Pipeline);
        Assert.Equal(revision, scene.Revision);
        Assert.Equal(Bar(-0.05f).Center, scene.Colliders[1].Center);

        var before = scene.Colliders.ToArray();
        Assert.Throws<ArgumentOutOfRangeException>(() => scene.SetCollider(2, Bar(0f)));
        Assert.Throws<ArgumentOutOfRangeException>(() => scene.SetCollider(-1, Bar(0f)));
        Assert.Throws<ArgumentException>(() => scene.SetCollider(1, Collider.Sphere(Vector3.Zero, 0.02f))); // kind change
        Assert.Throws<ArgumentException>(() => scene.SetCollider(1, default)); // not made by a factory
        Assert.Throws<ArgumentException>(() => scene.AddCollider(default));
        Assert.Throws<ArgumentException>(() => scene.SetCollider(1, Bar(float.NaN))); // the factory refuses NaN first
        Assert.Equal(before, scene.Colliders.ToArray());
        Assert.Equal(revision, scene.Revision);
        Assert.Same(pipeline, sim.Pipeline);
    }

    [Fact]
    public void A_sphere_that_becomes_thinner_than_a_segment_brings_in_the_segment_test()
    {
        var scene = SweptCurtain.Build(SolverPath.Reference);
        scene.AddCollider(Collider.Sphere(new Vector3(0f, -0.1f, 0.1f), 0.05f));
        var sim = new HairSimulation(scene);
        Assert.DoesNotContain(SegmentCollideSystem.SystemName, sim.Pipeline.SystemNames);
        scene.SetCollider(0, Collider.Sphere(new Vector3(0f, -0.1f, 0.1f), 0.005f)); // thinner than the 15 mm segments
        Assert.Contains(SegmentCollideSystem.SystemName, sim.Pipeline.SystemNames);
    }

    [Fact]
    public void A_moved_collider_is_carried_across_the_substeps_and_a_jump_snaps()
    {
        var scene = SweptCurtain.Build(SolverPath.Reference);
        scene.Settings.Substeps = 5;
        scene.Settings.Guards = false; // exactly five substeps
        var a = Collider.Capsule(new Vector3(-0.1f, -0.1f, -0.05f), new Vector3(0.1f, -0.12f, -0.05f), 0.02f).InWorldSpace();
        var b = Collider.Capsule(new Vector3(-0.1f, -0.1f, 0.05f), new Vector3(0.12f, -0.1f, 0.04f), 0.03f).InWorldSpace();
        var qa = Quaternion.CreateFromYawPitchRoll(0.1f, 0f, 0f);
        var qb = Quaternion.CreateFromYawPitchRoll(0.5f, 0.2f, 0f);
        var ea = Collider.Ellipsoid(new Vector3(0f, 0.1f, 0f), new Vector3(0.08f, 0.1f, 0.09f), qa); // on the head
        var eb = Collider.Ellipsoid(new Vector3(0f, 0.12f, 0.01f), new Vector3(0.08f, 0.1f, 0.09f), qb);
        scene.AddCollider(a);
        scene.AddCollider(ea);
        var sim = new HairSimulation(scene);
        sim.Step(1f / 60f);
        scene.SetCollider(0, b);
        scene.SetCollider(1, eb);
        var head = new RigidTransform(new Vector3(0.02f, 0f, 0f), Quaternion.CreateFromYawPitchRoll(0.2f, 0f, 0f));
        sim.Step(1f / 60f, head);
        var ctx = sim.Pipeline.LastFrame;
        for (int s = 0; s < 5; s++)
        {
            float t = (s + 1) / 5f;
            var capsule = ctx.CollidersAt(s)[0];
            AssertNear(Vector3.Lerp(a.Center, b.Center, t), capsule.Center);
            AssertNear(Vector3.Lerp(a.End, b.End, t), capsule.End);
            Assert.Equal(0.02f + 0.01f * t, capsule.Radius, 6);
            // The head collider: its own motion within the head, placed by the substep's head pose.
            var ellipsoid = ctx.CollidersAt(s)[1];
            var headS = ctx.HeadAt(s);
            AssertNear(headS.TransformPoint(Vector3.Lerp(ea.Center, eb.Center, t)), ellipsoid.Center);
            var q = headS.Rotation * Quaternion.Slerp(qa, qb, t);
            Assert.True(MathF.Abs(Quaternion.Dot(Quaternion.Normalize(q), ellipsoid.Rotation)) > 1 - 1e-6f, $"substep {s}: rotation");
        }
        Assert.Equal(b, ctx.CollidersAt(4)[0]); // exact at the frame's end

        // Held: the next frame has it at its placement throughout.
        sim.Step(1f / 60f, head);
        for (int s = 0; s < 5; s++) Assert.Equal(b, sim.Pipeline.LastFrame.CollidersAt(s)[0]);

        // A jump beyond the teleport distance (2 × the hair's reach) is placed at once.
        var far = Collider.Capsule(new Vector3(5f, 0f, 0f), new Vector3(5.2f, 0f, 0f), 0.02f).InWorldSpace();
        scene.SetCollider(0, far);
        sim.Step(1f / 60f, head);
        for (int s = 0; s < 5; s++) Assert.Equal(far, sim.Pipeline.LastFrame.CollidersAt(s)[0]);

        // A head teleport places moved colliders at once too.
        scene.SetCollider(0, b);
        sim.Step(1f / 60f, new RigidTransform(new Vector3(10f, 0f, 0f), Quaternion.Identity));
        Assert.True(sim.Pipeline.LastFrame.Teleported);
        for (int s = 0; s < 5; s++) Assert.Equal(b, sim.Pipeline.LastFrame.CollidersAt(s)[0]);
    }

    private static void AssertNear(Vector3 expected, Vector3 actual) =>
        Assert.True(Vector3.Distance(expected, actual) < 1e-6f, $"expected {expected}, got {actual}");


    [Theory]
    [InlineData(SolverPath.Reference)]
    [InlineData(SolverPath.Fast)]
    public void A_fast_bar_sweeps_the_hair_along_and_the_hair_stays_out_of_it(SolverPath path)
    {
        var scene = SweptCurtain.Build(path);
        scene.AddCollider(Bar(SweptCurtain.BarZ(0)));
        // The bar passes every strand: pushed, each one swings up over it or under it (a hanging strand cannot reach round
        // the bar's front 7.5 cm ahead of the roots).
        var bar = Bar(SweptCurtain.BarZ(0));
        float deepest = SweptCurtain.Sweep(scene, f => scene.SetCollider(0, bar = Bar(SweptCurtain.BarZ(f))), w => DeepestInside(w, bar));
        Assert.True(deepest < 1e-3f, $"{path}: a particle ended a frame {deepest * 1000:F2} mm inside the bar");
    }

    [Fact]
    public void Without_the_substeps_the_same_sweep_leaves_hair_behind_the_bar()
    {
        // The control for the sweep above: with one substep per frame the bar's 5 cm moves jump over the strands it should push.
        var scene = SweptCurtain.Build(SolverPath.Reference);
        scene.Settings.Substeps = 1;
        scene.Settings.Guards = false;
        scene.AddCollider(Bar(SweptCurtain.BarZ(0)));
        var sim = new HairSimulation(scene);
        for (int f = 1; f <= SweptCurtain.Arrival; f++) { scene.SetCollider(0, Bar(SweptCurtain.BarZ(f))); sim.Step(1f / 60f); }
        Assert.Equal(SweptCurtain.Strands, SweptCurtain.StrandsUntouched(scene.World));
    }

    [Fact]
    public void The_guards_raise_the_substeps_for_a_fast_collider_as_for_a_fast_head()
    {
        var scene = SweptCurtain.Build(SolverPath.Reference);
        scene.Settings.Substeps = 1;
        scene.AddCollider(Bar(-0.1f));
        var sim = new HairSimulation(scene);
        sim.Step(1f / 60f);
        scene.SetCollider(0, Bar(0.1f)); // 20 cm in a frame: at most MaxHeadTravel × the 15 mm segment per substep
        sim.Step(1f / 60f);
        Assert.Equal((int)Math.Ceiling(0.2 / (scene.Settings.MaxHeadTravel * SweptCurtain.Spacing)), sim.Pipeline.LastFrame.Substeps);
    }

    [Fact]
    public void Fast_and_reference_paths_agree_while_a_collider_moves_and_chunks_give_the_same_bits()
    {
        var reference = SweptCurtain.Build(SolverPath.Reference);
        var chunked = SweptCurtain.Build(SolverPath.Fast);
        var plain = SweptCurtain.Build(SolverPath.Fast);
        var sims = new[] { new HairSimulation(reference), new HairSimulation(chunked), new HairSimulation(plain) };
        foreach (var sim in sims) sim.Scene.AddCollider(Bar(SweptCurtain.BarZ(0)));
        sims[2].Pipeline.UseStrandChunks = false;
        Assert.Equal(FastPathInfo.Avx512, sims[1].Pipeline.UsesStrandChunks);
        for (int f = 1; f <= SweptCurtain.Arrival; f++)
        {
            foreach (var sim in sims) { sim.Scene.SetCollider(0, Bar(SweptCurtain.BarZ(f))); sim.Step(1f / 60f); }
            Assert.True(chunked.World.BitEquals(plain.World), $"chunks and the system-by-system fast path differ after frame {f}");
        }
        float worst = 0f;
        for (int i = 0; i < reference.World.ParticleCount; i++)
            worst = MathF.Max(worst, Vector3.Distance(reference.World.GetPosition(i), chunked.World.GetPosition(i)));
        Assert.True(worst < 2e-3f, $"fast and reference differ by {worst * 1000:F2} mm");
        Assert.Equal(0, SweptCurtain.StrandsUntouched(reference.World) + SweptCurtain.StrandsUntouched(chunked.World));
    }

    [Fact]
    public void Moving_a_collider_every_frame_allocates_nothing()
    {
        var scene = SweptCurtain.Build(SolverPath.Fast);
        scene.AddCollider(Bar(SweptCurtain.BarZ(0)));
        scene.AddCollider(Collider.Sphere(new Vector3(0f, 0.1f, 0f), 0.05f));
        var sim = new HairSimulation(scene);
        for (int f = 1; f <= 20; f++) { scene.SetCollider(0, Bar(SweptCurtain.BarZ(f))); sim.Step(1f / 60f); }
        Action<int> step = f =>
        {
            scene.SetCollider(0, Bar(0.05f * MathF.Sin(f)));
            scene.SetCollider(1, Collider.Sphere(new Vector3(0f, 0.1f + 0.001f * f, 0f), 0.05f));
            sim.Step(1f / 60f);
        };
        Assert.Equal(0, Allocation.InQuieterWindow(step, 21, 20));
    }
}
