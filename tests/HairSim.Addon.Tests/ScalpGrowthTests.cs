using System.Numerics;
using HairSheet.Logic;
using HairSim;
using HairSim.Meshes;

namespace HairSheet.Addon.Tests;

/// <summary>
/// Hair grown on a scalp mesh as HairSystem3D does it (<see cref="ScalpGrowth"/>): the project's head, held as Godot
/// holds an imported mesh (clockwise), read into head space, its field baked and the groom grown on the painted scalp;
/// the scalp key that feeds the growth key; the scalp's inspector values.
/// </summary>
public class ScalpGrowthTests
{
    /// <summary>
    /// A mesh as Godot's OBJ and glTF importers leave it: the same vertices and colours, each triangle's first two
    /// corners swapped (resource_importer_obj.cpp reads a face's corners in the order 1, 0, 2), so front faces are clockwise.
    /// </summary>
    internal static MeshSurfaces.Surface AsGodotSurface(TriangleMesh mesh)
    {
        var idx = (int[])mesh.Indices.Clone();
        for (int t = 0; t < idx.Length; t += 3) (idx[t], idx[t + 1]) = (idx[t + 1], idx[t]);
        return new MeshSurfaces.Surface(mesh.Positions, idx, mesh.Colors);
    }

    private static readonly TriangleMesh Head = ProceduralHead.CreateLowPoly();
    // The head mesh sits 3 cm above the hair node's head frame and turned a little, as a mesh placed under the head would.
    private static readonly Matrix4x4 MeshToHead = Matrix4x4.CreateRotationY(0.3f) * Matrix4x4.CreateTranslation(0f, 0.03f, 0.01f);

    private static HairNodeSettings SmallGroom() => new()
    {
        Sheets = 60, StrandsPerSheet = 8, ParticlesPerStrand = 10, StrandLength = 0.2f, ScalpCellSize = 0.0025f,
    };

    /// <summary>Angle from the crown (radians) and how far towards the face a head-space point lies, in the head mesh's own frame.</summary>
    private static (float FromTop, float Front) OnHead(Vector3 headSpace)
    {
        Matrix4x4.Invert(MeshToHead, out var toMesh);
        var u = Vector3.Normalize(Vector3.Transform(headSpace, toMesh) / ProceduralHead.CraniumRadii);
        return (MathF.Acos(Math.Clamp(u.Y, -1f, 1f)), MathF.Max(0f, u.Z));
    }

    [Fact]
    public void The_projects_head_held_as_Godot_holds_it_grows_hair_on_its_painted_scalp_outside_the_mesh()
    {
        var settings = SmallGroom();
        var surfaces = new[] { AsGodotSurface(Head) };
        var mesh = ScalpGrowth.HeadSpaceMesh(surfaces, MeshToHead);
        var field = ScalpGrowth.BakeField(mesh, settings);
        var scene = ScalpGrowth.Grow(mesh, field, settings);
        var w = scene.World;
        Assert.Equal(60 * 8, w.StrandCount);
        Assert.Equal(10, w.StrandParticleCount[0]);
        var collider = scene.GetComponent<MeshCollider>();
        Assert.NotNull(collider);
        Assert.Equal(ColliderSpace.Head, collider!.Space);
        Assert.Same(field, collider.Field);
        float ring = 1.5f * MathF.PI / 40;   // a triangle with two painted corners is scalp: it reaches past the painted line by up to a cell diagonal
        for (int s = 0; s < w.StrandCount; s++)
        {
            var root = w.GetPosition(w.StrandFirst[s]);
            var (fromTop, front) = OnHead(root);
            Assert.True(fromTop < 1.95f - 1.0f * front + ring, $"strand {s} roots off the painted scalp ({fromTop:F2} rad from the crown, front {front:F2})");
            float d = field.Distance(root);
            Assert.True(d > 0f && d < settings.ScalpRootLift + field.CellSize, $"strand {s}'s root is {d * 1000:F2} mm from the surface");
        }
        // Growth can leave a few particles in the 8 mm ears (a library limit); the scene's mesh collider pushes them out.
        Assert.True(CountInside(w, field, out float deepest) < w.ParticleCount / 100 && deepest > -0.004f, $"the deepest grown particle is {deepest * 1000:F2} mm inside");
        var sim = new HairSimulation(scene);
        for (int f = 0; f < 30; f++) sim.Step(1f / 60f);
        Assert.Equal(0, CountInside(w, field, out _));
    }

    private static int CountInside(HairWorld w, SignedDistanceField field, out float deepest)
    {
        int inside = 0;
        deepest = 0f;
        for (int i = 0; i < w.ParticleCount; i++)
        {
            float d = field.Distance(w.GetPosition(i));
            deepest = MathF.Min(deepest, d);
            if (d < -0.0005f) inside++;
        }
        return inside;
    }

    [Fact]
    public void The_demo_head_file_read_as_Godot_imports_it_grows_hair_that_settles_outside_it()
    {
        string root = AppContext.BaseDirectory;
        while (!File.Exists(Path.Combine(root, "project.godot"))) root = Path.GetDirectoryName(root) ?? throw new DirectoryNotFoundException("project.godot");
        var file = ObjReader.Read(Path.Combine(root, "scenes", "head.obj"));
        var settings = new HairNodeSettings { Sheets = 120, StrandsPerSheet = 10 };   // the demo's other values: the defaults
        var mesh = ScalpGrowth.HeadSpaceMesh([AsGodotSurface(file)], Matrix4x4.Identity);
        var field = ScalpGrowth.BakeField(mesh, settings);
        var scene = ScalpGrowth.Grow(mesh, field, settings);
        Assert.Equal(1200, scene.World.StrandCount);
        var sim = new HairSimulation(scene);
        for (int f = 0; f < 30; f++) sim.Step(1f / 60f);
        Assert.Equal(0, CountInside(scene.World, field, out _));
        Assert.True(field.Distance(Vector3.Zero) < -0.05f, "the head's centre is not inside: the winding went wrong");
    }

    [Fact]
    public void Without_the_mask_the_same_head_grows_hair_on_the_face_too()
    {
        var settings = SmallGroom();
        settings.ScalpMaskThreshold = 0f;
        var mesh = ScalpGrowth.HeadSpaceMesh([AsGodotSurface(Head)], MeshToHead);
        var scene = ScalpGrowth.Grow(mesh, ScalpGrowth.BakeField(mesh, settings), settings);
        var w = scene.World;
        int onFace = 0;
        for (int s = 0; s < w.StrandCount; s++)
        {
            var (fromTop, front) = OnHead(w.GetPosition(w.StrandFirst[s]));
            if (fromTop > 1.95f - 1.0f * front + 0.2f) onFace++;
        }
        Assert.True(onFace > 20, $"only {onFace} strands grew off the painted scalp with the mask off: the mask test above sees nothing");
    }

    [Fact]
    public void A_mask_that_leaves_no_scalp_is_reported_by_its_cause()
    {
        var settings = SmallGroom();
        settings.ScalpMaskThreshold = 1f;
        var grey = new TriangleMesh(Head.Positions, Head.Indices, Head.Colors!.Select(c => c * 0.5f).ToArray());
        var mesh = ScalpGrowth.HeadSpaceMesh([AsGodotSurface(grey)], MeshToHead);
        var e = Assert.ThrowsAny<ArgumentException>(() => ScalpGrowth.Grow(mesh, ScalpGrowth.BakeField(mesh, settings), settings));
        Assert.Contains("mask threshold", e.Message);
    }

    [Fact]
    public void The_scalp_key_changes_with_the_mesh_its_colours_and_place_but_not_with_float_noise()
    {
        var surfaces = new[] { AsGodotSurface(Head) };
        string key = ScalpGrowth.Key(surfaces, MeshToHead);
        Assert.Equal(key, ScalpGrowth.Key([AsGodotSurface(ProceduralHead.CreateLowPoly())], MeshToHead));
        // The same scene after the head moved and came back: the transform differs in its last bits.
        var noisy = MeshToHead;
        noisy.M41 += 3e-8f; noisy.M12 -= 2e-8f;
        Assert.Equal(key, ScalpGrowth.Key(surfaces, noisy));
        var moved = MeshToHead * Matrix4x4.CreateTranslation(0f, 0.001f, 0f);
        Assert.NotEqual(key, ScalpGrowth.Key(surfaces, moved));
        var repainted = new TriangleMesh(Head.Positions, Head.Indices, Head.Colors!.Select((c, i) => i == 7 ? new Vector4(0, 0, 0, 1) : c).ToArray());
        Assert.NotEqual(key, ScalpGrowth.Key([AsGodotSurface(repainted)], MeshToHead));
        var nudged = (Vector3[])Head.Positions.Clone();
        nudged[100] += new Vector3(0f, 1e-6f, 0f);
        Assert.NotEqual(key, ScalpGrowth.Key([new MeshSurfaces.Surface(nudged, surfaces[0].Indices, Head.Colors)], MeshToHead));
        Assert.NotEqual(ScalpGrowth.FieldKey(key, 0.0025f), ScalpGrowth.FieldKey(key, 0.003f));
    }

    [Fact]
    public void Scalp_values_regrow_only_hair_that_grows_on_a_scalp()
    {
        var plain = new HairNodeSettings();
        var changed = new HairNodeSettings { ScalpDrape = 0.5f, ScalpRootLift = 0.003f, ScalpMaskThreshold = 0.2f, ScalpCellSize = 0.003f };
        // No scalp mesh: the ellipsoid groom does not depend on them, so they must not regrow it (and lose its edits).
        Assert.Equal(GrowthKey.Of(plain), GrowthKey.Of(changed));
        string scalp = ScalpGrowth.Key([AsGodotSurface(Head)], MeshToHead);
        string onScalp = GrowthKey.Of(plain, scalp: scalp);
        Assert.NotEqual(GrowthKey.Of(plain), onScalp);
        foreach (var change in new Action<HairNodeSettings>[]
                 { s => s.ScalpDrape = 0.5f, s => s.ScalpRootLift = 0.003f, s => s.ScalpMaskThreshold = 0.2f, s => s.ScalpCellSize = 0.003f })
        {
            var s = new HairNodeSettings();
            change(s);
            Assert.NotEqual(onScalp, GrowthKey.Of(s, scalp: scalp));
        }
        Assert.NotEqual(onScalp, GrowthKey.Of(plain, scalp: ScalpGrowth.Key([AsGodotSurface(Head)], Matrix4x4.Identity)));
        Assert.Equal(onScalp, GrowthKey.Of(new HairNodeSettings(), scalp: ScalpGrowth.Key([AsGodotSurface(ProceduralHead.CreateLowPoly())], MeshToHead)));
    }

    [Fact]
    public void Scalp_values_are_checked_by_their_inspector_names_and_reach_the_mesh_groom()
    {
        var bad = new HairNodeSettings { ScalpMaskThreshold = 1.5f, ScalpRootLift = -0.001f, ScalpDrape = float.NaN, ScalpCellSize = 0.0001f };
        var problems = bad.Validate();
        foreach (var name in new[] { "Scalp Mask Threshold", "Scalp Root Lift", "Scalp Drape", "Scalp Cell Size" })
            Assert.Contains(problems, p => p.StartsWith(name, StringComparison.Ordinal));
        var s = new HairNodeSettings { Sheets = 12, StrandsPerSheet = 5, ParticlesPerStrand = 3, StrandLength = 0.3f, Seed = 7, ScalpDrape = 0.25f, ScalpRootLift = 0.004f };
        var g = s.ToMeshGroom();
        Assert.Equal((12, 5, 3, 0.3f, 7ul), (g.SheetCount, g.StrandsPerSheet, g.ParticlesPerStrand, g.StrandLength, g.Seed));
        Assert.Equal((0.25f, 0.004f, 0.5f), (g.Drape, g.RootLift, g.ScalpMaskThreshold));
        Assert.Equal(2, g.PinnedPerStrand);   // fewer than the 3 particles
        Assert.Throws<HairSettingsException>(() => bad.ToMeshGroom());
    }
}
