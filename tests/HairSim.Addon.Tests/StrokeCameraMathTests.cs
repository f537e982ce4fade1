using System.Numerics;
using HairSheet.Logic;
using static HairSheet.Addon.Tests.TestScenes;

namespace HairSheet.Addon.Tests;

public class StrokeCameraMathTests
{
    private static readonly Vector2 Viewport = new(800, 600);

    private static CameraMatrices AtOrigin(Matrix4x4 projection) =>
        new(StrokeCameraMath.View(Vector3.UnitX, Vector3.UnitY, Vector3.UnitZ, Vector3.Zero), projection, Viewport);

    private static Vector2 Project(in CameraMatrices cam, Vector3 p)
    {
        Assert.True(StrokeCameraMath.WorldToScreen(cam, p, out var px), $"{p} should be in front of the camera");
        return px;
    }

    [Fact]
    public void Perspective_keep_height_maps_the_frustum_edges_to_the_viewport_borders()
    {
        var cam = AtOrigin(StrokeCameraMath.Perspective(75f, 0.05f, 100f, Viewport));
        float d = 5f, tanHalf = MathF.Tan(75f * MathF.PI / 360f), aspect = 800f / 600f;
        AssertClose(new Vector2(400, 300), Project(cam, new Vector3(0, 0, -d)));
        AssertClose(new Vector2(400, 0), Project(cam, new Vector3(0, d * tanHalf, -d)));
        AssertClose(new Vector2(400, 600), Project(cam, new Vector3(0, -d * tanHalf, -d)));
        AssertClose(new Vector2(800, 300), Project(cam, new Vector3(d * tanHalf * aspect, 0, -d)));
        AssertClose(new Vector2(0, 300), Project(cam, new Vector3(-d * tanHalf * aspect, 0, -d)));
        Assert.False(StrokeCameraMath.WorldToScreen(cam, new Vector3(0, 0, 5), out _)); // behind
    }

    [Fact]
    public void Perspective_keep_width_measures_the_fov_horizontally()
    {
        var cam = AtOrigin(StrokeCameraMath.Perspective(90f, 0.05f, 100f, Viewport, KeepAspect.Width));
        AssertClose(new Vector2(800, 300), Project(cam, new Vector3(3, 0, -3)));
        AssertClose(new Vector2(400, 0), Project(cam, new Vector3(0, 3 * 600f / 800f, -3)));
    }

    [Fact]
    public void Orthographic_size_is_the_full_viewport_height()
    {
        var cam = AtOrigin(StrokeCameraMath.Orthographic(2f, 0.05f, 100f, Viewport));
        AssertClose(new Vector2(400, 0), Project(cam, new Vector3(0, 1, -3)));
        AssertClose(new Vector2(400, 0), Project(cam, new Vector3(0, 1, -30)));   // no perspective
        AssertClose(new Vector2(800, 300), Project(cam, new Vector3(4f / 3f, 0, -7)));
    }

    [Fact]
    public void A_moved_and_turned_camera_sees_its_target_at_the_centre()
    {
        // Camera at +X looking at the origin: Godot basis Z = +X (back), X = −Z (right), Y = up.
        var view = StrokeCameraMath.View(-Vector3.UnitZ, Vector3.UnitY, Vector3.UnitX, new Vector3(5, 0, 0));
        var cam = new CameraMatrices(view, StrokeCameraMath.Perspective(60f, 0.05f, 100f, Viewport), Viewport);
        AssertClose(new Vector2(400, 300), Project(cam, Vector3.Zero));
        Assert.True(Project(cam, new Vector3(0, 0, -1)).X > 400);   // camera's right
        Assert.True(Project(cam, new Vector3(0, 1, 0)).Y < 300);    // up is up the screen
        // A scaled basis (a scaled camera parent) gives the same view.
        var scaled = StrokeCameraMath.View(-Vector3.UnitZ * 3, Vector3.UnitY * 3, Vector3.UnitX * 3, new Vector3(5, 0, 0));
        var cam2 = cam with { View = scaled };
        AssertClose(Project(cam, new Vector3(0.3f, 0.2f, -0.4f)), Project(cam2, new Vector3(0.3f, 0.2f, -0.4f)));
    }

    [Fact]
    public void Godot_projection_columns_give_the_same_pixels_as_the_lens_helper()
    {
        // Godot's Projection::set_perspective (OpenGL depth), written as columns.
        float fov = 70f, near = 0.1f, far = 50f, aspect = 800f / 600f;
        float f = 1f / MathF.Tan(fov * MathF.PI / 360f);
        var godot = StrokeCameraMath.FromGodotProjection(
            new Vector4(f / aspect, 0, 0, 0), new Vector4(0, f, 0, 0),
            new Vector4(0, 0, -(far + near) / (far - near), -1), new Vector4(0, 0, -2 * far * near / (far - near), 0));
        var a = AtOrigin(godot);
        var b = AtOrigin(StrokeCameraMath.Perspective(fov, near, far, Viewport));
        foreach (var p in new[] { new Vector3(0.4f, -0.2f, -2f), new Vector3(-1f, 0.7f, -3f), new Vector3(0, 0, -10f) })
            AssertClose(Project(b, p), Project(a, p));
    }

    [Fact]
    public void Screen_rays_pass_back_through_the_projected_point()
    {
        var view = StrokeCameraMath.View(-Vector3.UnitZ, Vector3.UnitY, Vector3.UnitX, new Vector3(2, 0.5f, 0));
        var cam = new CameraMatrices(view, StrokeCameraMath.Perspective(75f, 0.05f, 100f, Viewport), Viewport);
        var p = new Vector3(-0.3f, 0.6f, 0.25f);
        var px = Project(cam, p);
        var (o, dir) = StrokeCameraMath.ScreenRay(cam, px);
        var closest = o + dir * Vector3.Dot(p - o, dir);
        AssertClose(p, closest, 1e-3f);
        var (_, centre) = StrokeCameraMath.ScreenRay(cam, Viewport / 2);
        AssertClose(-Vector3.UnitX, centre, 1e-4f);
    }

    [Fact]
    public void Bad_camera_data_is_refused_with_a_reason()
    {
        Assert.Throws<ArgumentOutOfRangeException>(() => StrokeCameraMath.Perspective(0f, 0.1f, 10f, Viewport));
        Assert.Throws<ArgumentOutOfRangeException>(() => StrokeCameraMath.Perspective(75f, 0f, 10f, Viewport));
        Assert.Throws<ArgumentOutOfRangeException>(() => StrokeCameraMath.Perspective(75f, 1f, 0.5f, Viewport));
        Assert.Throws<ArgumentOutOfRangeException>(() => StrokeCameraMath.Perspective(75f, 0.1f, 10f, new Vector2(0, 600)));
        Assert.Throws<ArgumentOutOfRangeException>(() => StrokeCameraMath.Orthographic(-1f, 0.1f, 10f, Viewport));
        Assert.Throws<ArgumentException>(() => StrokeCameraMath.View(Vector3.UnitX, Vector3.Zero, Vector3.UnitZ, Vector3.Zero));
        Assert.Throws<ArgumentException>(() => StrokeCameraMath.View(-Vector3.UnitX, Vector3.UnitY, Vector3.UnitZ, Vector3.Zero));
        Assert.Throws<ArgumentException>(() => StrokeCameraMath.View(Vector3.UnitX, Vector3.UnitY, Vector3.UnitZ, new Vector3(float.NaN, 0, 0)));
    }
}
