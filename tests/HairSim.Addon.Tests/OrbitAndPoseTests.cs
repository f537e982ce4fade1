using System.Numerics;
using HairSheet.Logic;
using HairSim;
using static HairSheet.Addon.Tests.TestScenes;

namespace HairSheet.Addon.Tests;

public class OrbitAndPoseTests
{
    [Fact]
    public void Orbit_camera_at_rest_sits_in_front_of_the_target_looking_at_it()
    {
        var o = new OrbitCamera { Target = new Vector3(0, 0.1f, 0), Distance = 0.8f };
        AssertClose(new Vector3(0, 0.1f, 0.8f), o.Eye);
        var (x, y, z) = o.Basis;
        AssertClose(Vector3.UnitX, x); AssertClose(Vector3.UnitY, y); AssertClose(Vector3.UnitZ, z);
    }

    [Theory]
    [InlineData(0.3f, 0.2f)]
    [InlineData(-2.5f, -1.0f)]
    [InlineData(3.1f, 1.4f)]
    public void Orbit_basis_is_right_handed_and_the_target_projects_to_the_centre(float yaw, float pitch)
    {
        var o = new OrbitCamera { Target = new Vector3(0.1f, 0.2f, -0.3f), Yaw = yaw, Pitch = pitch, Distance = 1.2f };
        var (x, y, z) = o.Basis;
        AssertClose(z, Vector3.Cross(x, y), 1e-5f);
        Assert.Equal(1.2f, Vector3.Distance(o.Eye, o.Target), 4);
        var viewport = new Vector2(1280, 720);
        var cam = new CameraMatrices(StrokeCameraMath.View(x, y, z, o.Eye), StrokeCameraMath.Perspective(60, 0.05f, 50f, viewport), viewport);
        Assert.True(StrokeCameraMath.WorldToScreen(cam, o.Target, out var px));
        AssertClose(viewport / 2, px, 1e-2f);
    }

    [Fact]
    public void Orbit_clamps_pitch_and_zoom()
    {
        var o = new OrbitCamera { Distance = 1f };
        o.Orbit(new Vector2(0, 100000));
        Assert.Equal(o.PitchLimit, o.Pitch);
        o.Zoom(1000);
        Assert.Equal(o.MinDistance, o.Distance);
        o.Zoom(-1000);
        Assert.Equal(o.MaxDistance, o.Distance);
        o.Orbit(new Vector2(float.NaN, 0));
        Assert.Equal(o.PitchLimit, o.Pitch);
        var yaw = o.Yaw;
        o.Orbit(new Vector2(10, 0));
        Assert.True(o.Yaw < yaw);
    }

    [Fact]
    public void Head_pose_keeps_rotation_and_drops_scale()
    {
        var q = Quaternion.CreateFromYawPitchRoll(0.7f, -0.3f, 0.2f);
        Vector3 bx = Vector3.Transform(Vector3.UnitX, q) * 2f, by = Vector3.Transform(Vector3.UnitY, q) * 0.5f, bz = Vector3.Transform(Vector3.UnitZ, q) * 3f;
        var pose = HeadPoseMath.ToRigid(bx, by, bz, new Vector3(1, 2, 3));
        var local = new Vector3(0.05f, 0.1f, -0.02f);
        AssertClose(new Vector3(1, 2, 3) + Vector3.Transform(local, q), pose.TransformPoint(local), 1e-5f);
        Assert.Throws<ArgumentException>(() => HeadPoseMath.ToRigid(bx, by, -bz, Vector3.Zero));
        Assert.Throws<ArgumentException>(() => HeadPoseMath.ToRigid(Vector3.Zero, by, bz, Vector3.Zero));
    }

    [Fact]
    public void A_mirrored_head_keeps_its_rotation_and_says_so()
    {
        var q = Quaternion.CreateFromYawPitchRoll(0.7f, -0.3f, 0.2f);
        Vector3 bx = Vector3.Transform(Vector3.UnitX, q) * 2f, by = Vector3.Transform(Vector3.UnitY, q) * 0.5f, bz = Vector3.Transform(Vector3.UnitZ, q) * 3f;
        var origin = new Vector3(1, 2, 3);
        var plain = HeadPoseMath.HeadPose(bx, by, bz, origin, out bool m0);
        Assert.False(m0);
        // Mirrored bones: Z scaled by −3. The pose is the unmirrored one, reported as mirrored.
        var mirrored = HeadPoseMath.HeadPose(bx, by, -bz, origin, out bool m1);
        Assert.True(m1);
        var local = new Vector3(0.05f, 0.1f, -0.02f);
        AssertClose(plain.TransformPoint(local), mirrored.TransformPoint(local), 1e-5f);
        AssertClose(origin + Vector3.Transform(local, q), mirrored.TransformPoint(local), 1e-5f);
        // Zero scale still has no rotation to take.
        Assert.Throws<ArgumentException>(() => HeadPoseMath.HeadPose(Vector3.Zero, by, bz, origin, out _));
    }

    [Fact]
    public void Collider_nodes_put_their_scale_into_the_shape()
    {
        var e = HeadPoseMath.Ellipsoid(Vector3.UnitX * 2, Vector3.UnitY, Vector3.UnitZ * 0.5f, new Vector3(0, 0.1f, 0), new Vector3(0.1f, 0.1f, 0.1f));
        AssertClose(new Vector3(0.2f, 0.1f, 0.05f), e.Radii);
        Assert.Equal(ColliderKind.Ellipsoid, e.Kind);
        // A point 0.15 m along X from the centre is inside the stretched ellipsoid, 0.15 along Z is not.
        Assert.True(e.Penetration(new Vector3(0.15f, 0.1f, 0)) > 0f);
        Assert.Equal(0f, e.Penetration(new Vector3(0, 0.1f, 0.15f)));
        var s = HeadPoseMath.Sphere(Vector3.UnitX, Vector3.UnitY * 3, Vector3.UnitZ, Vector3.Zero, 0.1f);
        Assert.Equal(0.3f, s.Radius, 5);
        var c = HeadPoseMath.Capsule(Vector3.UnitX, Vector3.UnitY, Vector3.UnitZ, new Vector3(0, 1, 0), 0.05f, 0.2f);
        AssertClose(new Vector3(0, 0.8f, 0), c.Center);
        AssertClose(new Vector3(0, 1.2f, 0), c.End);
        Assert.Throws<ArgumentOutOfRangeException>(() => HeadPoseMath.Capsule(Vector3.UnitX, Vector3.UnitY, Vector3.UnitZ, Vector3.Zero, 0.05f, -1f));
    }

    [Fact]
    public void Fixed_step_clock_runs_whole_steps_and_drops_a_hitch()
    {
        var c = new FixedStepClock(1.0 / 60, maxStepsPerFrame: 3);
        Assert.Equal(1, c.Advance(1.0 / 60));
        Assert.Equal(0, c.Advance(0.5 / 60));
        Assert.Equal(1, c.Advance(0.5 / 60));
        Assert.Equal(3, c.Advance(1.0));           // a one-second hitch
        Assert.Equal(57, c.DroppedSteps);
        Assert.True(c.Accumulated < c.Step);
        Assert.Equal(0, c.Advance(double.NaN));
        Assert.Equal(0, c.Advance(-1));
        Assert.Throws<ArgumentOutOfRangeException>(() => new FixedStepClock(0));
    }
}
