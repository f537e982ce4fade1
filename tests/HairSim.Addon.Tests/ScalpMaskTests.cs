using System.Numerics;
using HairSheet.Logic;
using HairSim;
using HairSim.Meshes;

namespace HairSheet.Addon.Tests;

/// <summary>
/// The editor's scalp brushes as HairSystem3D runs them (<see cref="ScalpMask"/>): the stored bits, a stroke painted
/// through a Godot-style camera onto the project's head, growth on the painted area, the overlay's triangles, and
/// bad strokes refused with the mask unchanged.
/// </summary>
public class ScalpMaskTests
{
    private static readonly TriangleMesh Head = ScalpGrowth.HeadSpaceMesh([ScalpGrowthTests.AsGodotSurface(ProceduralHead.CreateLowPoly())], Matrix4x4.Identity);
    private static readonly Vector2 Viewport = new(800, 600);

    /// <summary>A Godot camera 60 cm in front of the face (+Z), looking along −Z, 50° fov.</summary>
    private static CameraMatrices FrontCamera() => new(
        StrokeCameraMath.View(Vector3.UnitX, Vector3.UnitY, Vector3.UnitZ, new Vector3(0f, 0.05f, 0.6f)),
        StrokeCameraMath.Perspective(50f, 0.05f, 10f, Viewport), Viewport);

    private static readonly Vector2[] AcrossTheFace = [new(330, 300), new(400, 290), new(470, 300)];

    [Fact]
    public void Bits_pack_and_unpack_and_a_mask_of_another_mesh_is_refused()
    {
        var flags = new bool[19];
        foreach (int t in new[] { 0, 3, 8, 15, 18 }) flags[t] = true;
        var bits = ScalpMask.Pack(flags);
        Assert.Equal(3, bits.Length);
        Assert.Equal(flags, ScalpMask.Unpack(bits, 19));
        Assert.Equal(5, ScalpMask.Count(bits));
        Assert.Throws<ArgumentException>(() => ScalpMask.Unpack(bits, 25));
        Assert.Throws<ArgumentException>(() => ScalpMask.Start(Head, bits, 0.5f));
        var other = (bool[])flags.Clone();
        other[1] = true;
        Assert.NotEqual(ScalpMask.Key(bits), ScalpMask.Key(ScalpMask.Pack(other)));
    }

    [Fact]
    public void A_stroke_across_the_face_paints_only_front_facing_triangles_under_the_brush_and_erasing_it_gives_the_colours_back()
    {
        var camera = FrontCamera();
        var cam = StrokeCameras.From(camera);
        var colours = ScalpPaint.FromVertexColours(Head, 0.5f).Triangles.ToArray();
        const float Radius = 20f;
        var painted = ScalpMask.Paint(Head, null, 0.5f, AcrossTheFace, Radius, ScalpPaintMode.Add, camera, RigidTransform.Identity);
        Assert.NotNull(painted);
        var after = ScalpMask.Unpack(painted!, Head.TriangleCount);
        int added = 0;
        for (int t = 0; t < Head.TriangleCount; t++)
        {
            if (colours[t]) { Assert.True(after[t], $"triangle {t} of the colours' scalp was lost by painting"); continue; }
            if (!after[t]) continue;
            added++;
            var (a, b, c) = Head.Triangle(t);
            var centre = (a + b + c) / 3f;
            Assert.True(Vector3.Dot(Head.FaceNormal(t), new Vector3(0f, 0.05f, 0.6f) - centre) > 0f, $"triangle {t} faces away from the camera");
            Assert.True(cam.Project(centre, out var screen, out _));
            Assert.True(DistanceToStroke(screen) <= Radius + 0.01f, $"triangle {t}'s centre is {DistanceToStroke(screen):F1} px from the stroke");
        }
        Assert.True(added > 10, $"only {added} triangles painted");
        // The same stroke again changes nothing.
        Assert.Null(ScalpMask.Paint(Head, painted, 0.5f, AcrossTheFace, Radius, ScalpPaintMode.Add, camera, RigidTransform.Identity));
        // Erasing with a wider brush along the same line removes what was added, and the face part of the colours' scalp (none).
        var erased = ScalpMask.Paint(Head, painted, 0.5f, AcrossTheFace, Radius + 1f, ScalpPaintMode.Remove, camera, RigidTransform.Identity);
        Assert.NotNull(erased);
        var back = ScalpMask.Unpack(erased!, Head.TriangleCount);
        for (int t = 0; t < Head.TriangleCount; t++)
            if (after[t] && !colours[t]) Assert.False(back[t], $"triangle {t} painted by the stroke was not erased");
    }

    private static float DistanceToStroke(Vector2 p)
    {
        float best = float.MaxValue;
        for (int i = 1; i < AcrossTheFace.Length; i++)
        {
            var a = AcrossTheFace[i - 1]; var ab = AcrossTheFace[i] - a;
            float u = Math.Clamp(Vector2.Dot(p - a, ab) / ab.LengthSquared(), 0f, 1f);
            best = MathF.Min(best, Vector2.Distance(p, a + u * ab));
        }
        return best;
    }

    [Fact]
    public void Hair_grows_only_where_the_mask_is_painted()
    {
        var settings = new HairNodeSettings { Sheets = 40, StrandsPerSheet = 6, ParticlesPerStrand = 8, StrandLength = 0.15f, ScalpCellSize = 0.0025f };
        // The colours' scalp, left half only (x < 0 in the head's frame).
        var flags = ScalpPaint.FromVertexColours(Head, settings.ScalpMaskThreshold).Triangles.ToArray();
        for (int t = 0; t < flags.Length; t++)
        {
            var (a, b, c) = Head.Triangle(t);
            if ((a.X + b.X + c.X) / 3f > 0f) flags[t] = false;
        }
        var field = ScalpGrowth.BakeField(Head, settings);
        var scene = ScalpGrowth.Grow(Head, field, settings, ScalpMask.Pack(flags));
        var w = scene.World;
        Assert.Equal(40 * 6, w.StrandCount);
        float rightmost = float.MinValue;
        for (int s = 0; s < w.StrandCount; s++) rightmost = MathF.Max(rightmost, w.GetPosition(w.StrandFirst[s]).X);
        Assert.True(rightmost < 0.01f, $"a root grew at x = {rightmost * 1000:F1} mm, right of the painted half");
        // A mask painted on another mesh is refused with a reason, as the node reports it.
        var e = Assert.Throws<ArgumentException>(() => ScalpGrowth.Grow(Head, field, settings, new byte[3]));
        Assert.Contains("another mesh", e.Message);
    }

    [Fact]
    public void Bad_strokes_are_refused_and_leave_the_mask_as_it_was()
    {
        var camera = FrontCamera();
        var bits = ScalpMask.Pack(ScalpPaint.FromVertexColours(Head, 0.5f).Triangles);
        var copy = (byte[])bits.Clone();
        Assert.Throws<ArgumentException>(() => ScalpMask.Paint(Head, bits, 0.5f, [], 20f, ScalpPaintMode.Add, camera, RigidTransform.Identity));
        Assert.Throws<ArgumentException>(() => ScalpMask.Paint(Head, bits, 0.5f, [new(float.NaN, 3f)], 20f, ScalpPaintMode.Add, camera, RigidTransform.Identity));
        Assert.ThrowsAny<ArgumentException>(() => ScalpMask.Paint(Head, bits, 0.5f, AcrossTheFace, 0f, ScalpPaintMode.Add, camera, RigidTransform.Identity));
        Assert.ThrowsAny<ArgumentException>(() => ScalpMask.Paint(Head, new byte[2], 0.5f, AcrossTheFace, 20f, ScalpPaintMode.Add, camera, RigidTransform.Identity));
        Assert.Equal(copy, bits);
    }

    [Fact]
    public void The_overlay_holds_each_painted_triangle_lifted_along_its_normal()
    {
        var flags = new bool[Head.TriangleCount];
        for (int t = 0; t < flags.Length; t += 7) flags[t] = true;
        var v = ScalpMask.Overlay(Head, flags, 0.001f);
        Assert.Equal(3 * flags.Count(f => f), v.Length);
        int o = 0;
        for (int t = 0; t < flags.Length; t++)
        {
            if (!flags[t]) continue;
            var (a, _, _) = Head.Triangle(t);
            Assert.True(Vector3.Distance(a + 0.001f * Head.FaceNormal(t), v[o]) < 1e-6f);
            o += 3;
        }
    }
}
