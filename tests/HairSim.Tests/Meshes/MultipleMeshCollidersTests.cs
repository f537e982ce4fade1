using System.Numerics;
using HairSim.Editing;
using HairSim.Fast;
using HairSim.Meshes;
using Xunit;

namespace HairSim.Tests.Meshes;

/// <summary>
/// Several mesh colliders in one scene (<see cref="HairScene.MeshColliders"/>): the component and the added ones listed
/// in order, hair held out of each (a ball on the head and one fixed in the world), chunks giving the bits of the
/// system-by-system pass, the reference path near, no allocation per frame, the metrics and the editor seeing them all.
/// </summary>
public sealed class MultipleMeshCollidersTests
{
    private const int Strands = 64, N = 16;
    private const float Radius = 0.03f;
    private static readonly SignedDistanceField Ball = SignedDistanceField.Bake(TriangleMesh.Ellipsoid(Vector3.Zero, new Vector3(Radius), 24, 48), 0.002f);
    // Each ball's centre 2 cm behind the curtain of hanging strands: both cut into it.
    private static readonly Vector3 OnHead = new(-0.05f, -0.12f, 0.02f), InWorld = new(0.05f, -0.12f, 0.02f);

    private static HairScene Curtain(SolverPath path)
    {
        var w = new HairWorld(1, Strands, N);
        var pts = new Vector3[N];
        for (int s = 0; s < Strands; s++)
        {
            for (int k = 0; k < N; k++) pts[k] = new Vector3(-0.1f + 0.2f * s / (Strands - 1), -0.015f * k, 0f);
            w.SetStrand(s, pts, pinned: 1);
        }
        return new HairScene(w, new SimulationSettings { Path = path, Bend = BendModel.Limp });
    }

    private static MeshCollider HeadBall() => new(Ball, 0.001f) { Placement = new RigidTransform(OnHead, Quaternion.Identity) };
    private static MeshCollider WorldBall() => new(Ball, 0.001f, space: ColliderSpace.World) { Placement = new RigidTransform(InWorld, Quaternion.Identity) };

    /// <summary>Two balls: the head's as the scene's component, the world's added beside it.</summary>
    private static HairScene TwoBalls(SolverPath path)
    {
        var scene = Curtain(path);
        scene.SetComponent(HeadBall());
        scene.AddMeshCollider(WorldBall());
        return scene;
    }

    /// <summary>The head moves 2 cm sideways and turns a little: the head's ball moves with it, the world's stays.</summary>
    private static RigidTransform HeadAt(int f) =>
        new(new Vector3(0.02f * MathF.Min(1f, f / 30f), 0f, 0f), Quaternion.CreateFromYawPitchRoll(0.1f * MathF.Sin(f / 10f), 0f, 0f));

    /// <summary>How deep the deepest live particle is inside mesh collider c (its field, at the world's head pose).</summary>
    private static float Deepest(HairWorld w, MeshCollider c)
    {
        var pose = c.PoseFor(w.Head);
        float deepest = float.MinValue;
        for (int i = 0; i < w.ParticleCount; i++)
            if (w.InvMass[i] != 0f) deepest = MathF.Max(deepest, -c.Field.Distance(pose.InverseTransformPoint(w.GetPosition(i))));
        return deepest;
    }

    [Fact]
    public void The_component_and_the_added_meshes_are_listed_in_order_and_each_change_rebuilds()
    {
        var scene = Curtain(SolverPath.Fast);
        var sim = new HairSimulation(scene);
        Assert.DoesNotContain(MeshCollideSystem.SystemName, sim.Pipeline.SystemNames);
        var body = WorldBall();
        int revision = scene.Revision;
        scene.AddMeshCollider(body); // without a component: the pipeline collides with it alone
        Assert.True(scene.Revision > revision);
        Assert.Contains(MeshCollideSystem.SystemName, sim.Pipeline.SystemNames);
        var head = HeadBall();
        scene.SetComponent(head);
        Assert.Equal(new[] { head, body }, scene.MeshColliders);
        Assert.Same(head, scene.GetComponent<MeshCollider>()); // the single-collider calls keep working
        Assert.Throws<ArgumentException>(() => scene.AddMeshCollider(body));
        Assert.Throws<ArgumentException>(() => scene.AddMeshCollider(head));
        Assert.Throws<ArgumentNullException>(() => scene.AddMeshCollider(null!));
        Assert.Equal(new[] { head, body }, scene.MeshColliders);
        Assert.True(scene.RemoveMeshCollider(head));
        Assert.Null(scene.GetComponent<MeshCollider>());
        Assert.Equal(new[] { body }, scene.MeshColliders);
        Assert.False(scene.RemoveMeshCollider(head));
        scene.SetComponent(head);
        scene.ClearMeshColliders();
        Assert.Empty(scene.MeshColliders);
        Assert.False(scene.HasComponent<MeshCollider>());
        Assert.DoesNotContain(MeshCollideSystem.SystemName, sim.Pipeline.SystemNames);
    }

    [Theory]
    [InlineData(SolverPath.Reference)]
    [InlineData(SolverPath.Fast)]
    public void Hair_is_held_out_of_both_meshes(SolverPath path)
    {
        var scene = TwoBalls(path);
        var sim = new HairSimulation(scene);
        float deepest = 0f;
        for (int f = 1; f <= 90; f++)
        {
            sim.Step(1f / 60f, HeadAt(f));
            foreach (var mesh in scene.MeshColliders) deepest = MathF.Max(deepest, Deepest(scene.World, mesh));
        }
        Assert.Equal(0, scene.World.CountNonFinite());
        Assert.True(deepest < 1e-3f, $"{path}: a particle ended a frame {deepest * 1000:F2} mm inside a ball");
        // Each ball holds hair against it (within 3 mm of its surface), and the metrics see both.
        foreach (var mesh in scene.MeshColliders) Assert.True(Deepest(scene.World, mesh) > -3e-3f, $"{path}: no hair rests on a ball");
        Assert.True(WorldMetrics.Measure(scene).MaxPenetration < 1e-3);

        // The control: without the world's ball the hair hangs through where it was.
        var control = Curtain(path);
        control.SetComponent(HeadBall());
        var controlSim = new HairSimulation(control);
        for (int f = 1; f <= 90; f++) controlSim.Step(1f / 60f, HeadAt(f));
        Assert.True(Deepest(control.World, WorldBall()) > 5e-3f, $"{path}: the control's hair does not pass through the world ball's place");
    }

    [Fact]
    public void Chunks_give_the_bits_of_the_system_by_system_pass_and_the_reference_path_is_near()
    {
        var chunked = TwoBalls(SolverPath.Fast);
        var plain = TwoBalls(SolverPath.Fast);
        var reference = TwoBalls(SolverPath.Reference);
        var sims = new[] { new HairSimulation(chunked), new HairSimulation(plain), new HairSimulation(reference) };
        sims[1].Pipeline.UseStrandChunks = false;
        Assert.Equal(FastPathInfo.Avx512 && System.Runtime.Intrinsics.X86.Avx2.IsSupported, sims[0].Pipeline.UsesStrandChunks);
        for (int f = 1; f <= 60; f++)
        {
            foreach (var sim in sims) sim.Step(1f / 60f, HeadAt(f));
            Assert.True(chunked.World.BitEquals(plain.World), $"chunks and the system-by-system pass differ after frame {f}");
        }
        float worst = 0f;
        for (int i = 0; i < chunked.World.ParticleCount; i++)
            worst = MathF.Max(worst, Vector3.Distance(chunked.World.GetPosition(i), reference.World.GetPosition(i)));
        Assert.True(worst < 2e-3f, $"fast and reference differ by {worst * 1000:F2} mm");
    }

    [Fact]
    public void Two_meshes_allocate_nothing_per_frame()
    {
        var scene = TwoBalls(SolverPath.Fast);
        var body = scene.MeshColliders[1];
        var sim = new HairSimulation(scene);
        for (int f = 1; f <= 30; f++) sim.Step(1f / 60f, HeadAt(f));
        Action<int> step = f =>
        {
            body.Placement = new RigidTransform(InWorld + new Vector3(0f, 0f, 0.001f * (f - 30)), Quaternion.Identity);
            sim.Step(1f / 60f, HeadAt(f));
        };
        Assert.Equal(0, Allocation.InQuieterWindow(step, 31, 20));
    }

    [Fact]
    public void The_visible_only_selection_is_hidden_by_any_of_the_meshes()
    {
        // Looking along +z from in front of the curtain at the world ball's place: strands behind the ball are hidden by
        // it, whichever list it is in; without it, they are picked.
        var scene = Curtain(SolverPath.Fast);
        var sim = new HairSimulation(scene);
        sim.Step(1f / 60f);
        var camera = StrokeCamera.LookAtPerspective(new Vector3(0.05f, -0.15f, -0.5f), new Vector3(0.05f, -0.15f, 0f), Vector3.UnitY, 0.6f, new Vector2(400, 400));
        var area = SelectionArea.Brush(new Vector2(200, 200), 15f);
        var options = new SelectionOptions { VisibleOnly = true };
        int open = HairEditor.Select(scene, camera, area, options).Count;
        Assert.True(open > 0, "the test's brush sees no strands");
        scene.AddMeshCollider(new MeshCollider(Ball, space: ColliderSpace.World) { Placement = new RigidTransform(new Vector3(0.05f, -0.15f, -0.1f), Quaternion.Identity) });
        scene.SetComponent(new MeshCollider(Ball, space: ColliderSpace.World) { Placement = new RigidTransform(new Vector3(5f, 0f, 0f), Quaternion.Identity) });
        Assert.Equal(0, HairEditor.Select(scene, camera, area, options).Count);
    }
}
