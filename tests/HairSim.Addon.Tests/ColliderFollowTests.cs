using System.Numerics;
using HairSheet.Logic;
using HairSim;
using HairSim.Meshes;
using static HairSheet.Addon.Tests.TestScenes;

namespace HairSheet.Addon.Tests;

/// <summary>
/// A mesh collider following a bone or a node (<see cref="ColliderFollowMath"/>): the frames composed as Godot composes
/// them, scale and reflections stripped alike at bake time and every frame, bad transforms refused, and a moving bone
/// carrying its field (and the hair meeting it) through the library's world-space placement.
/// </summary>
public class ColliderFollowTests
{
    /// <summary>A Godot Transform3D (basis columns, origin) as GodotConvert.ToNumericsMatrix writes it.</summary>
    private static Matrix4x4 Godot(Vector3 x, Vector3 y, Vector3 z, Vector3 origin) =>
        new(x.X, x.Y, x.Z, 0, y.X, y.Y, y.Z, 0, z.X, z.Y, z.Z, 0, origin.X, origin.Y, origin.Z, 1);

    private static Matrix4x4 Godot(Quaternion rotation, Vector3 scale, Vector3 origin) => Godot(
        Vector3.Transform(Vector3.UnitX, rotation) * scale.X, Vector3.Transform(Vector3.UnitY, rotation) * scale.Y,
        Vector3.Transform(Vector3.UnitZ, rotation) * scale.Z, origin);

    /// <summary>Godot's Transform3D * Vector3: basis columns times the point's coordinates, plus the origin.</summary>
    private static Vector3 Apply(Matrix4x4 godot, Vector3 p) =>
        p.X * new Vector3(godot.M11, godot.M12, godot.M13) + p.Y * new Vector3(godot.M21, godot.M22, godot.M23) +
        p.Z * new Vector3(godot.M31, godot.M32, godot.M33) + new Vector3(godot.M41, godot.M42, godot.M43);

    // A character imported at 1/100 with its skeleton scaled back up (a common FBX/glTF import), turned and moved.
    private static readonly Matrix4x4 Skeleton = Godot(Quaternion.CreateFromYawPitchRoll(0.6f, 0f, 0f), new Vector3(0.01f), new Vector3(1f, 0f, 2f));
    private static readonly Matrix4x4 NeckPose = Godot(Quaternion.CreateFromYawPitchRoll(0.1f, 0.2f, -0.3f), Vector3.One, new Vector3(0f, 150f, 4f));

    [Fact]
    public void A_bone_frame_is_the_skeleton_transform_times_the_bone_pose_as_Godot_composes_them()
    {
        var local = new Vector3(3f, 10f, -2f);   // a point on the bone, in skeleton units
        var expected = Apply(Skeleton, Apply(NeckPose, local));
        var bone = ColliderFollowMath.BoneGlobal(Skeleton, NeckPose);
        AssertClose(expected, Vector3.Transform(local, bone), 1e-5f);
        Assert.True(ColliderFollowMath.TryFrame(bone, out var frame, out bool mirrored));
        Assert.False(mirrored);
        AssertClose(expected, frame.TransformPoint(local * 0.01f), 1e-5f); // the frame is rigid: the 0.01 scale is gone
    }

    [Fact]
    public void Scale_is_stripped_alike_at_bake_time_and_every_frame_so_the_baked_mesh_keeps_its_place()
    {
        var unscaled = Godot(Quaternion.CreateFromYawPitchRoll(0.6f, 0f, 0f), Vector3.One, new Vector3(1f, 0f, 2f));
        Assert.True(ColliderFollowMath.TryFrame(Skeleton, out var scaled, out _));
        Assert.True(ColliderFollowMath.TryFrame(unscaled, out var plain, out _));
        AssertClose(plain.Position, scaled.Position);
        Assert.True(MathF.Abs(Quaternion.Dot(plain.Rotation, scaled.Rotation)) > 1 - 1e-6f, "scale changed the frame's rotation");

        // The bake reads a mesh (with its own non-uniform scale) through MeshToFrame; placing the field at the same frame
        // gives back every vertex where Godot draws it.
        var bone = ColliderFollowMath.BoneGlobal(Skeleton, NeckPose);
        Assert.True(ColliderFollowMath.TryFrame(bone, out var frame, out _));
        var source = Godot(Quaternion.CreateFromYawPitchRoll(-0.4f, 0.1f, 0f), new Vector3(1.3f, 0.9f, 1.1f), new Vector3(0.2f, 1.6f, 1.9f));
        var toFrame = ColliderFollowMath.MeshToFrame(source, frame);
        foreach (var v in new[] { new Vector3(0.1f, 0f, 0f), new Vector3(0f, -0.07f, 0.03f), new Vector3(-0.02f, 0.05f, 0.09f) })
            AssertClose(Apply(source, v), frame.TransformPoint(Vector3.Transform(v, toFrame)), 1e-5f);
    }

    [Fact]
    public void A_mirrored_bone_has_its_reflection_stripped_and_reported_and_still_round_trips()
    {
        var mirroredBone = Godot(Quaternion.CreateFromYawPitchRoll(0.3f, -0.2f, 0.1f), new Vector3(-1f, 1f, 1f), new Vector3(0.1f, 1.5f, 0f));
        Assert.True(ColliderFollowMath.TryFrame(mirroredBone, out var frame, out bool mirrored));
        Assert.True(mirrored);
        Assert.True(MathF.Abs(frame.Rotation.Length() - 1f) < 1e-5f);
        var source = Godot(Quaternion.Identity, Vector3.One, new Vector3(0.12f, 1.5f, 0.01f));
        var v = new Vector3(0.01f, 0.02f, 0.03f);
        AssertClose(Apply(source, v), frame.TransformPoint(Vector3.Transform(v, ColliderFollowMath.MeshToFrame(source, frame))), 1e-5f);
    }

    [Fact]
    public void Transforms_without_a_rotation_are_refused_without_throwing()
    {
        var zeroScale = Godot(Quaternion.Identity, new Vector3(1f, 0f, 1f), Vector3.Zero);
        var nan = Godot(Quaternion.Identity, Vector3.One, new Vector3(float.NaN, 0f, 0f));
        var flat = Godot(Vector3.UnitX, Vector3.UnitX * 2f, Vector3.UnitZ, Vector3.Zero); // X and Y parallel
        foreach (var m in new[] { zeroScale, nan, flat })
        {
            Assert.False(ColliderFollowMath.TryFrame(m, out var frame, out _));
            Assert.Equal(RigidTransform.Identity, frame);
        }
    }

    [Fact]
    public void Frame_names_say_what_a_field_was_baked_relative_to()
    {
        Assert.Equal("head", ColliderFollowMath.FrameName(null, null));
        Assert.Equal("head", ColliderFollowMath.FrameName("", "Neck"));
        Assert.Equal("Chest", ColliderFollowMath.FrameName("Chest", ""));
        Assert.Equal("Skeleton3D:Neck", ColliderFollowMath.FrameName("Skeleton3D", "Neck"));
    }

    /// <summary>A 2 cm ball modelled on the neck bone: baked relative to the bone frame at the bind pose.</summary>
    private static (MeshCollider Collider, Matrix4x4 Offset) BallOnTheNeck(out RigidTransform bakeFrame)
    {
        var ball = TriangleMesh.Ellipsoid(Vector3.Zero, new Vector3(0.02f), 24, 48);
        var offset = Godot(Quaternion.Identity, new Vector3(100f), new Vector3(0f, 8f, 0f)); // the ball's node under the bone (skeleton units)
        var bone = ColliderFollowMath.BoneGlobal(Skeleton, NeckPose);
        Assert.True(ColliderFollowMath.TryFrame(bone, out bakeFrame, out _));
        var source = offset * bone;   // Godot: bone * offset
        var field = SignedDistanceField.Bake(ball.Transformed(ColliderFollowMath.MeshToFrame(source, bakeFrame)), 0.002f);
        return (new MeshCollider(field, 0.001f, space: ColliderSpace.World) { Placement = bakeFrame }, offset);
    }

    private static float DistanceAt(MeshCollider c, Vector3 world) =>
        c.Field.Distance(c.PoseFor(RigidTransform.Identity).InverseTransformPoint(world));

    [Fact]
    public void A_moving_bone_carries_its_field()
    {
        var (collider, offset) = BallOnTheNeck(out var bakeFrame);
        var centreAtBind = Apply(ColliderFollowMath.BoneGlobal(Skeleton, NeckPose), Apply(offset, Vector3.Zero));
        Assert.True(DistanceAt(collider, centreAtBind) < -0.018f, "the ball's centre is inside at the bind pose");

        // The neck turns and the character walks 20 cm: the placement follows the bone, the field with it.
        var turned = Godot(Quaternion.CreateFromYawPitchRoll(1.2f, -0.3f, 0.2f), Vector3.One, new Vector3(0f, 150f, 4f));
        var walked = Godot(Quaternion.CreateFromYawPitchRoll(0.6f, 0f, 0f), new Vector3(0.01f), new Vector3(1.2f, 0f, 2f));
        var bone = ColliderFollowMath.BoneGlobal(walked, turned);
        Assert.True(ColliderFollowMath.TryFrame(bone, out var frame, out _));
        collider.Placement = frame;
        var centreNow = Apply(bone, Apply(offset, Vector3.Zero));
        Assert.True(Vector3.Distance(centreAtBind, centreNow) > 0.1f, $"the test moves the ball too little ({Vector3.Distance(centreAtBind, centreNow)} m)");
        Assert.True(DistanceAt(collider, centreNow) < -0.018f, "the field did not come along with the bone");
        Assert.True(DistanceAt(collider, centreAtBind) > 0.02f, "the field stayed where the bone was");
        // The head's pose plays no part in a world-space placement.
        Assert.Equal(frame, collider.PoseFor(new RigidTransform(new Vector3(3f, 1f, 0f), Quaternion.CreateFromYawPitchRoll(1f, 0f, 0f))));
    }

    [Fact]
    public void Hair_meets_a_ball_a_bone_carries_into_it_and_stays_out_and_the_update_allocates_nothing()
    {
        // Settle a groom, then a ball following a "shoulder" bone sweeps into the hanging hair and holds there. The
        // placement is set before every step, as HairSystem3D does.
        var groom = new GroomSettings { SheetCount = 40, StrandsPerSheet = 8, ParticlesPerStrand = 12, StrandLength = 0.25f };
        var scene = GroomBuilder.BuildScene(groom, new SimulationSettings { Path = SolverPath.Fast });
        var sim = new HairSimulation(scene);
        for (int f = 0; f < 60; f++) sim.Step(1f / 60f);
        var w = scene.World;
        var target = w.GetPosition(w.TipIndex(w.SkeletonStrand(10)));
        var ball = TriangleMesh.Ellipsoid(Vector3.Zero, new Vector3(0.02f), 24, 48);
        var collider = new MeshCollider(SignedDistanceField.Bake(ball, 0.002f), 0.001f, space: ColliderSpace.World);
        scene.SetComponent(collider);
        Matrix4x4 ShoulderAt(int f)
        {
            float s = MathF.Min(1f, f / 60f);
            var spin = Quaternion.CreateFromYawPitchRoll(2f * s, 0f, 0f);   // the bone turns too: the ball is round, its centre is what moves
            return Godot(spin, new Vector3(1.7f), target + new Vector3(0.15f * (1f - s), 0f, 0f));
        }
        float deepest = 0f, nearest = float.MaxValue;
        var allocations = new UpdateAllocations();
        for (int f = 0; f <= 150; f++)
        {
            var shoulder = ShoulderAt(f);
            allocations.Begin();
            Assert.True(ColliderFollowMath.TryFrame(shoulder, out var frame, out _));
            collider.Placement = frame;
            allocations.End();
            sim.Step(1f / 60f);
            var centre = new Vector3(shoulder.M41, shoulder.M42, shoulder.M43);
            for (int i = 0; i < w.ParticleCount; i++)
            {
                if (w.InvMass[i] == 0f) continue;
                float r = Vector3.Distance(w.GetPosition(i), centre);
                if (f >= 60) { deepest = MathF.Max(deepest, 0.02f - r); nearest = MathF.Min(nearest, r); }
            }
        }
        allocations.AssertNonePerUpdate();
        Assert.Equal(0, w.CountNonFinite());
        Assert.True(nearest < 0.023f, $"no hair came within 3 mm of the ball (nearest {nearest * 1000:F1} mm from its centre): the test sees nothing");
        Assert.True(deepest < 0.001f, $"a particle is {deepest * 1000:F2} mm inside the ball the bone carried in");
    }
}
