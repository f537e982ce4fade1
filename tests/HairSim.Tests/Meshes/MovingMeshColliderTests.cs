using System.Numerics;
using HairSim.Fast;
using HairSim.Meshes;
using HairSim.Tests.Core;
using Xunit;

namespace HairSim.Tests.Meshes;

/// <summary>
/// Mesh colliders whose <see cref="MeshCollider.Placement"/> changes between frames (a body on a bone): carried from the
/// last frame's placement to this frame's across the substeps as the head is, snapped on a jump or a head teleport, on
/// both paths, allocation-free; the guards raise the substeps for a fast one.
/// </summary>
public class MovingMeshColliderTests
{
    private const float BarY = -0.15f;

    /// <summary>A bar 40 cm long and 4 cm thick (an ellipsoid mesh), baked at 2.5 mm, centred on the origin along x.</summary>
    private static readonly SignedDistanceField BarField =
        SignedDistanceField.Bake(TriangleMesh.Ellipsoid(Vector3.Zero, new Vector3(0.2f, 0.02f, 0.02f), 16, 48), 0.0025f);

    private static RigidTransform BarAt(float z) => new(new Vector3(0f, BarY, z), Quaternion.Identity);

    
    private static float DeepestInside(HairWorld w, MeshCollider c)
    {
        var pose = c.PoseFor(w.Head);
        float deepest = 0f;
        for (int i = 0; i < w.ParticleCount; i++) deepest = MathF.Max(deepest, -c.Field.Distance(pose.InverseTransformPoint(w.GetPosition(i))));
        return deepest;
    }

    private static void AssertPose(in RigidTransform expected, in RigidTransform actual, string what)
    {
        Assert.True(Vector3.Distance(expected.Position, actual.Position) < 1e-6f, $"{what}: expected {expected.Position}, got {actual.Position}");
        Assert.True(MathF.Abs(Quaternion.Dot(expected.Rotation, actual.Rotation)) > 1 - 1e-6f, $"{what}: rotation");
    }

    [Fact]
    public void A_moved_mesh_is_carried_across_the_substeps_and_a_jump_or_a_teleport_snaps()
    {
        var scene = SweptCurtain.Build(SolverPath.Reference);
        scene.Settings.Substeps = 5;
        scene.Settings.Guards = false; // exactly five substeps
        var a = new RigidTransform(new Vector3(0f, -0.1f, -0.05f), Quaternion.CreateFromYawPitchRoll(0.1f, 0f, 0f));
        var b = new RigidTransform(new Vector3(0.01f, -0.1f, 0.05f), Quaternion.CreateFromYawPitchRoll(0.4f, 0.2f, 0f));
        var world = new MeshCollider(BarField, space: ColliderSpace.World) { Placement = a };
        var onHead = new MeshCollider(BarField) { Placement = a };   // placed on the head: its own motion within the head
        scene.SetComponent(onHead);
        scene.AddMeshCollider(world);
        var sim = new HairSimulation(scene);
        sim.Step(1f / 60f);
        world.Placement = b;
        onHead.Placement = b;
        var head = new RigidTransform(new Vector3(0.02f, 0f, 0f), Quaternion.CreateFromYawPitchRoll(0.2f, 0f, 0f));
        sim.Step(1f / 60f, head);
        var ctx = sim.Pipeline.LastFrame;
        var meshes = scene.MeshColliderArray;
        Assert.Same(onHead, meshes[0]);
        for (int s = 0; s < 5; s++)
        {
            var between = RigidTransform.Interpolate(a, b, (s + 1) / 5f);
            AssertPose(between, ctx.MeshPoseAt(s, 1, meshes), $"world mesh, substep {s}");
            var headS = ctx.HeadAt(s);
            AssertPose(new RigidTransform(headS.TransformPoint(between.Position), headS.Rotation * between.Rotation),
                ctx.MeshPoseAt(s, 0, meshes), $"head mesh, substep {s}");
        }
        Assert.Equal(b, ctx.MeshPoseAt(4, 1, meshes)); // exact at the frame's end

        // Held: the next frame has it at its placement throughout.
        sim.Step(1f / 60f, head);
        for (int s = 0; s < 5; s++) Assert.Equal(b, sim.Pipeline.LastFrame.MeshPoseAt(s, 1, meshes));

        // A jump beyond the teleport distance (2 × the hair's reach) is placed at once.
        var far = new RigidTransform(new Vector3(5f, 0f, 0f), Quaternion.Identity);
        world.Placement = far;
        sim.Step(1f / 60f, head);
        for (int s = 0; s < 5; s++) Assert.Equal(far, sim.Pipeline.LastFrame.MeshPoseAt(s, 1, meshes));

        // A head teleport places moved meshes at once too.
        world.Placement = b;
        sim.Step(1f / 60f, new RigidTransform(new Vector3(10f, 0f, 0f), Quaternion.Identity));
        Assert.True(sim.Pipeline.LastFrame.Teleported);
        for (int s = 0; s < 5; s++) Assert.Equal(b, sim.Pipeline.LastFrame.MeshPoseAt(s, 1, meshes));

        // A collider added with a placement starts there (not carried from where it was before it joined).
        var late = new MeshCollider(BarField, space: ColliderSpace.World) { Placement = a };
        late.Placement = far;
        scene.AddMeshCollider(late);
        sim.Step(1f / 60f, new RigidTransform(new Vector3(10f, 0f, 0f), Quaternion.Identity));
        for (int s = 0; s < sim.Pipeline.LastFrame.Substeps; s++) Assert.Equal(far, sim.Pipeline.LastFrame.MeshPoseAt(s, 2, scene.MeshColliderArray));
    }

    [Theory]
    [InlineData(SolverPath.Reference)]
    [InlineData(SolverPath.Fast)]
    public void A_fast_mesh_bar_sweeps_the_hair_along_and_the_hair_stays_out_of_it(SolverPath path)
    {
        var scene = SweptCurtain.Build(path);
        var bar = new MeshCollider(BarField, space: ColliderSpace.World) { Placement = BarAt(SweptCurtain.BarZ(0)) };
        scene.AddMeshCollider(bar);
        // Held for all substeps at its frame-end place, the bar would jump 5 cm past the strands; carried, it pushes every one.
        float deepest = SweptCurtain.Sweep(scene, f => bar.Placement = BarAt(SweptCurtain.BarZ(f)), w => DeepestInside(w, bar));
        Assert.True(deepest < 1e-3f, $"{path}: a particle ended a frame {deepest * 1000:F2} mm inside the bar");
    }

    [Fact]
    public void With_one_substep_the_same_sweep_leaves_the_hair_behind_the_bar()
    {
        // The control: one substep per frame and no guards, so the bar's 5 cm moves jump over the strands.
        var scene = SweptCurtain.Build(SolverPath.Reference);
        scene.Settings.Substeps = 1;
        scene.Settings.Guards = false;
        var bar = new MeshCollider(BarField, space: ColliderSpace.World) { Placement = BarAt(SweptCurtain.BarZ(0)) };
        scene.AddMeshCollider(bar);
        var sim = new HairSimulation(scene);
        for (int f = 1; f <= SweptCurtain.Arrival; f++) { bar.Placement = BarAt(SweptCurtain.BarZ(f)); sim.Step(1f / 60f); }
        Assert.Equal(SweptCurtain.Strands, SweptCurtain.StrandsUntouched(scene.World));
    }

    [Fact]
    public void The_guards_raise_the_substeps_for_a_fast_mesh_as_for_a_fast_head()
    {
        var scene = SweptCurtain.Build(SolverPath.Reference);
        scene.Settings.Substeps = 1;
        var bar = new MeshCollider(BarField, space: ColliderSpace.World) { Placement = BarAt(-0.1f) };
        scene.AddMeshCollider(bar);
        var sim = new HairSimulation(scene);
        sim.Step(1f / 60f);
        bar.Placement = BarAt(0.1f); // 20 cm in a frame: at most MaxHeadTravel × the 15 mm segment per substep
        sim.Step(1f / 60f);
        Assert.Equal((int)Math.Ceiling(0.2 / (scene.Settings.MaxHeadTravel * SweptCurtain.Spacing)), sim.Pipeline.LastFrame.Substeps);
        // Turning in place: the surface moves by up to the angle × the field's farthest corner.
        bar.Placement = new RigidTransform(new Vector3(0f, BarY, 0.1f), Quaternion.CreateFromYawPitchRoll(0.3f, 0f, 0f));
        sim.Step(1f / 60f);
        Assert.True(sim.Pipeline.LastFrame.Substeps >= (int)Math.Ceiling(0.3 * 0.2 / (scene.Settings.MaxHeadTravel * SweptCurtain.Spacing)),
            $"{sim.Pipeline.LastFrame.Substeps} substeps for a 0.3 rad turn of a 20 cm bar");
    }

    [Fact]
    public void Fast_and_reference_paths_agree_while_a_mesh_moves_and_chunks_give_the_same_bits()
    {
        var scenes = new[] { SweptCurtain.Build(SolverPath.Reference), SweptCurtain.Build(SolverPath.Fast), SweptCurtain.Build(SolverPath.Fast) };
        var bars = new MeshCollider[3];
        var sims = new HairSimulation[3];
        for (int k = 0; k < 3; k++)
        {
            bars[k] = new MeshCollider(BarField, space: ColliderSpace.World) { Placement = BarAt(SweptCurtain.BarZ(0)) };
            scenes[k].AddMeshCollider(bars[k]);
            sims[k] = new HairSimulation(scenes[k]);
        }
        sims[2].Pipeline.UseStrandChunks = false;
        Assert.Equal(FastPathInfo.Avx512, sims[1].Pipeline.UsesStrandChunks);
        for (int f = 1; f <= SweptCurtain.Arrival; f++)
        {
            for (int k = 0; k < 3; k++) { bars[k].Placement = BarAt(SweptCurtain.BarZ(f)); sims[k].Step(1f / 60f); }
            Assert.True(scenes[1].World.BitEquals(scenes[2].World), $"chunks and the system-by-system fast path differ after frame {f}");
        }
        float worst = 0f;
        for (int i = 0; i < scenes[0].World.ParticleCount; i++)
            worst = MathF.Max(worst, Vector3.Distance(scenes[0].World.GetPosition(i), scenes[1].World.GetPosition(i)));
        Assert.True(worst < 2e-3f, $"fast and reference differ by {worst * 1000:F2} mm");
        Assert.Equal(0, SweptCurtain.StrandsUntouched(scenes[0].World) + SweptCurtain.StrandsUntouched(scenes[1].World));
    }

    [Fact]
    public void Moving_a_mesh_every_frame_allocates_nothing()
    {
        var scene = SweptCurtain.Build(SolverPath.Fast);
        var bar = new MeshCollider(BarField, space: ColliderSpace.World) { Placement = BarAt(SweptCurtain.BarZ(0)) };
        scene.AddMeshCollider(bar);
        var sim = new HairSimulation(scene);
        for (int f = 1; f <= 20; f++) { bar.Placement = BarAt(SweptCurtain.BarZ(f)); sim.Step(1f / 60f); }
        Action<int> step = f => { bar.Placement = BarAt(0.05f * MathF.Sin(f)); sim.Step(1f / 60f); };
        Assert.Equal(0, Allocation.InQuieterWindow(step, 21, 20));
    }
}
