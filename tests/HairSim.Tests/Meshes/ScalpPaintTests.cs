using System.Numerics;
using HairSim.Editing;
using HairSim.Meshes;
using Xunit;

namespace HairSim.Tests.Meshes;

/// <summary>Painting where hair grows on a mesh with strokes (issue 18's scalp selection stroke).</summary>
public class ScalpPaintTests
{
    private static readonly Vector2 Viewport = new(600, 600);

    // Looking at the head's front (the head faces +z) from 1 m away, 0.5 m of view.
    private static StrokeCamera Front(TriangleMesh mesh)
    {
        var centre = (mesh.BoundsMin + mesh.BoundsMax) / 2f;
        return StrokeCamera.LookAtPerspective(centre + new Vector3(0, 0, 1f), centre, Vector3.UnitY, 0.5f, Viewport);
    }

    [Fact]
    public void A_brush_marks_only_the_front_faces_under_it_and_hair_grows_there()
    {
        var head = ProceduralHead.Create();
        var field = SignedDistanceField.Bake(head, 0.0025f);
        var cam = Front(head);
        var brush = SelectionArea.Brush(new Vector2(300, 220), 60f);
        var paint = new ScalpPaint(head);
        int changed = paint.Paint(cam, brush, ScalpPaintMode.Add, RigidTransform.Identity, new MeshCollider(field, 0f, head));

        Assert.True(changed > 20, $"painted {changed} triangles");
        Assert.Equal(changed, paint.Count);
        for (int t = 0; t < head.TriangleCount; t++)
        {
            var (a, b, c) = head.Triangle(t);
            var centre = (a + b + c) / 3f;
            bool under = cam.Project(centre, out var s, out _) && brush.Contains(s);
            bool facing = Vector3.Dot(head.FaceNormal(t), cam.Position - centre) > 0f;
            if (paint.IsScalp(t)) Assert.True(under && facing, $"triangle {t} painted but not under the brush and facing the camera");
            // Nothing on the back half of the head, however it projects.
            if (paint.IsScalp(t)) Assert.True(centre.Z > (head.BoundsMin.Z + head.BoundsMax.Z) / 2f, $"triangle {t} is on the back");
        }

        var world = MeshScalp.Grow(head, field, new MeshGroomSettings { SheetCount = 10, StrandsPerSheet = 6, ParticlesPerStrand = 8, StrandLength = 0.1f, Scalp = paint });
        for (int s = 0; s < world.StrandCount; s++)
        {
            var root = new Vector3(world.RestX[world.StrandFirst[s]], world.RestY[world.StrandFirst[s]], world.RestZ[world.StrandFirst[s]]);
            Assert.True(cam.Project(root, out var screen, out _));
            // Roots lie on painted triangles (lifted 2 mm): within the brush plus a triangle's size on screen.
            Assert.True(Vector2.Distance(screen, new Vector2(300, 220)) < 60f + 25f, $"root of strand {s} at {screen} is off the painted patch");
        }
    }

    [Fact]
    public void The_mesh_hides_what_lies_behind_it()
    {
        // A sphere with a plate in front of its lower half: painting the whole view marks the plate's front and the
        // sphere's upper front, never the sphere behind the plate.
        var sphere = TriangleMesh.Ellipsoid(Vector3.Zero, new Vector3(0.1f), 24, 48);
        var plate = TriangleMesh.Box(new Vector3(-0.15f, -0.15f, 0.14f), new Vector3(0.15f, -0.02f, 0.16f));
        var mesh = TriangleMesh.Combine([sphere, plate]);
        var field = SignedDistanceField.Bake(mesh, 0.004f);
        var cam = StrokeCamera.LookAtPerspective(new Vector3(0, 0, 1f), Vector3.Zero, Vector3.UnitY, 0.6f, Viewport);
        var all = SelectionArea.Rectangle(Vector2.Zero, Viewport);

        var seen = new ScalpPaint(mesh);
        seen.Paint(cam, all, ScalpPaintMode.Add, RigidTransform.Identity, new MeshCollider(field, 0f, mesh));
        var facing = new ScalpPaint(mesh);
        facing.Paint(cam, all, ScalpPaintMode.Add, RigidTransform.Identity);

        int behindPlate = 0, behindPlateFacing = 0, upper = 0;
        for (int t = 0; t < sphere.TriangleCount; t++)
        {
            var (a, b, c) = sphere.Triangle(t);
            var centre = (a + b + c) / 3f;
            if (centre.Y < -0.04f && centre.Y > -0.13f && centre.Z > 0.02f)
            {
                if (seen.IsScalp(t)) behindPlate++;
                if (facing.IsScalp(t)) behindPlateFacing++;
            }
            if (centre.Y > 0.02f && centre.Z > 0.05f && seen.IsScalp(t)) upper++;
        }
        Assert.True(behindPlateFacing > 10, "without an occluder the faces behind the plate are painted (the control)");
        Assert.Equal(0, behindPlate);
        Assert.True(upper > 10, $"the sphere's visible upper front is painted ({upper})");
        for (int t = sphere.TriangleCount; t < mesh.TriangleCount; t++)
            if (mesh.FaceNormal(t).Z > 0.9f) Assert.True(seen.IsScalp(t), "the plate's front is painted");
    }

    [Fact]
    public void Strokes_erase_undo_and_redo_exactly()
    {
        var head = ProceduralHead.Create();
        var cam = Front(head);
        var paint = ScalpPaint.FromVertexColours(head, 0.5f);
        var start = paint.Triangles.ToArray();
        Assert.True(paint.Count > 0);

        int erased = paint.Paint(cam, SelectionArea.Rectangle(Vector2.Zero, new Vector2(600, 300)), ScalpPaintMode.Remove, RigidTransform.Identity);
        Assert.True(erased > 0);
        Assert.Equal(start.Count(b => b) - erased, paint.Count);
        var afterErase = paint.Triangles.ToArray();
        int added = paint.Paint(cam, SelectionArea.Brush(new Vector2(300, 400), 80f), ScalpPaintMode.Add, RigidTransform.Identity);
        Assert.True(added > 0);
        var afterAdd = paint.Triangles.ToArray();

        Assert.True(paint.Undo());
        Assert.Equal(afterErase, paint.Triangles.ToArray());
        Assert.True(paint.Undo());
        Assert.Equal(start, paint.Triangles.ToArray());
        Assert.False(paint.Undo());
        Assert.True(paint.Redo());
        Assert.True(paint.Redo());
        Assert.Equal(afterAdd, paint.Triangles.ToArray());
        Assert.False(paint.Redo());

        // A stroke that changes nothing (off the mesh) leaves no undo step; a new stroke clears the redo steps.
        Assert.Equal(0, paint.Paint(cam, SelectionArea.Brush(new Vector2(5, 5), 3f), ScalpPaintMode.Add, RigidTransform.Identity));
        Assert.True(paint.Undo());
        Assert.Equal(afterErase, paint.Triangles.ToArray());
        paint.Paint(cam, SelectionArea.Brush(new Vector2(300, 100), 40f), ScalpPaintMode.Add, RigidTransform.Identity);
        Assert.False(paint.CanRedo);
    }

    [Fact]
    public void A_stroke_of_several_areas_and_a_whole_mask_are_one_undo_step_each()
    {
        var head = ProceduralHead.Create();
        var cam = Front(head);
        var dabs = new[] { SelectionArea.Brush(new Vector2(260, 220), 30f), SelectionArea.Brush(new Vector2(300, 220), 30f), SelectionArea.Brush(new Vector2(340, 220), 30f) };
        var union = new ScalpPaint(head);
        int n = union.Paint(cam, dabs, ScalpPaintMode.Add, RigidTransform.Identity);
        // The same triangles as the dabs painted one at a time, in one step.
        var oneByOne = new ScalpPaint(head);
        foreach (var d in dabs) oneByOne.Paint(cam, d, ScalpPaintMode.Add, RigidTransform.Identity);
        Assert.True(n > 20);
        Assert.Equal(oneByOne.Triangles.ToArray(), union.Triangles.ToArray());
        Assert.Equal(1, union.UndoCount);
        Assert.Equal(3, oneByOne.UndoCount);

        // A whole mask with marks and clears at once (the vertex colours' scalp over the brushed patch): one step,
        // undone and redone exactly.
        var painted = union.Triangles.ToArray();
        var colours = ScalpPaint.FromVertexColours(head, 0.5f);
        int changed = union.SetMask(colours.Triangles);
        Assert.True(changed > 0);
        Assert.Equal(colours.Triangles.ToArray(), union.Triangles.ToArray());
        Assert.Equal(0, union.SetMask(colours.Triangles));   // no change, no step
        Assert.Equal(2, union.UndoCount);
        Assert.True(union.Undo());
        Assert.Equal(painted, union.Triangles.ToArray());
        Assert.True(union.Redo());
        Assert.Equal(colours.Triangles.ToArray(), union.Triangles.ToArray());

        // A copy keeps the mask, not the history, and does not follow later strokes.
        var copy = union.CopyMask();
        Assert.Equal(union.Triangles.ToArray(), copy.Triangles.ToArray());
        Assert.False(copy.CanUndo);
        union.SetMask(new bool[head.TriangleCount]);
        Assert.Equal(0, union.Count);
        Assert.Equal(colours.Count, copy.Count);
        Assert.Throws<ArgumentException>(() => union.SetMask(new bool[3]));
        Assert.Throws<ArgumentException>(() => union.Paint(cam, Array.Empty<SelectionArea>(), ScalpPaintMode.Add, RigidTransform.Identity));
        Assert.Equal(0, union.Count);
    }

    [Fact]
    public void The_head_pose_places_the_mesh_for_the_stroke()
    {
        // The head turned half round: a stroke on the front of the view now paints the back of the head.
        var head = ProceduralHead.Create();
        var cam = Front(head);
        var centre = (head.BoundsMin + head.BoundsMax) / 2f;
        var turned = new RigidTransform(centre - Vector3.Transform(centre, Quaternion.CreateFromAxisAngle(Vector3.UnitY, MathF.PI)),
            Quaternion.CreateFromAxisAngle(Vector3.UnitY, MathF.PI));
        var paint = new ScalpPaint(head);
        // With the mesh as occluder: the nose's inner half, now turned to the camera, lies inside the head.
        var occluder = new MeshCollider(SignedDistanceField.Bake(head, 0.004f), 0f, head);
        Assert.True(paint.Paint(cam, SelectionArea.Brush(new Vector2(300, 250), 40f), ScalpPaintMode.Add, turned, occluder) > 20);
        for (int t = 0; t < head.TriangleCount; t++)
            if (paint.IsScalp(t))
            {
                var (a, b, c) = head.Triangle(t);
                Assert.True((a + b + c).Z / 3f < centre.Z, $"triangle {t} is not on the back of the head");
            }
    }

    [Fact]
    public void Bad_input_is_refused_and_changes_nothing()
    {
        var head = ProceduralHead.Create();
        var field = SignedDistanceField.Bake(head, 0.005f);
        var paint = ScalpPaint.FromVertexColours(head, 0.5f);
        var before = paint.Triangles.ToArray();
        var cam = Front(head);
        Assert.Throws<ArgumentNullException>(() => paint.Paint(null!, SelectionArea.Brush(Vector2.One, 1f), ScalpPaintMode.Add, RigidTransform.Identity));
        Assert.Throws<ArgumentNullException>(() => paint.Paint(cam, (SelectionArea)null!, ScalpPaintMode.Add, RigidTransform.Identity));
        Assert.Throws<ArgumentNullException>(() => paint.Paint(cam, (IReadOnlyList<SelectionArea>)null!, ScalpPaintMode.Add, RigidTransform.Identity));
        Assert.Throws<ArgumentOutOfRangeException>(() => paint.Paint(cam, SelectionArea.Brush(Vector2.One, 1f), (ScalpPaintMode)7, RigidTransform.Identity));
        Assert.Throws<ArgumentOutOfRangeException>(() => ScalpPaint.FromVertexColours(head, float.NaN));
        Assert.Equal(before, paint.Triangles.ToArray());
        Assert.False(paint.CanUndo);

        // A painted scalp of another mesh, or an empty one, grows nothing and says why.
        var other = new ScalpPaint(TriangleMesh.Box(Vector3.Zero, Vector3.One), everywhere: true);
        Assert.Throws<ArgumentException>(() => MeshScalp.Grow(head, field, new MeshGroomSettings { SheetCount = 2, StrandsPerSheet = 2, Scalp = other }));
        Assert.Throws<ArgumentException>(() => MeshScalp.Grow(head, field, new MeshGroomSettings { SheetCount = 2, StrandsPerSheet = 2, Scalp = new ScalpPaint(head) }));
    }
}
