using Godot;
using HairSheet.Logic;
using HairSim.Meshes;

namespace HairSheet;

/// <summary>
/// The hair collides with a mesh (a character's head or body) through a baked distance field. Child of a
/// HairSystem3D; point <see cref="Source"/> at the MeshInstance3D and press "Bake distance field" in the inspector.
/// The field is in head space: it moves with the hair node, as the other colliders do.
/// </summary>
[Tool]
[GlobalClass]
public partial class HairMeshCollider3D : Node3D
{
    private HairMeshField? _field;
    private float _margin = 0.001f;

    /// <summary>The mesh to collide with (its surfaces are read at bake time).</summary>
    [Export] public MeshInstance3D? Source { get; set; }

    /// <summary>Grid cell of the bake: about a quarter of the thinnest part the hair must feel (2.5 mm for 1 cm ears).</summary>
    [Export(PropertyHint.Range, "0.0005,0.05,0.0005,suffix:m")] public float CellSize { get; set; } = 0.0025f;

    /// <summary>Hair keeps at least this far from the surface.</summary>
    [Export(PropertyHint.Range, "0,0.01,0.0001,suffix:m")]
    public float Margin
    {
        get => _margin;
        set { _margin = value; NotifyHair(); }
    }

    /// <summary>The baked field (save it as a .tres to share it between scenes).</summary>
    [Export]
    public HairMeshField? Field
    {
        get => _field;
        set { _field = value; NotifyHair(); }
    }

    [ExportToolButton("Bake distance field")]
    public Callable BakeButton => Callable.From(Bake);

    /// <summary>Reads the source mesh in the hair node's head space and bakes its field (an editor action; undo by re-baking).</summary>
    public void Bake()
    {
        if (Source?.Mesh is not Mesh mesh || GetParent() is not HairSystem3D hair)
        {
            GD.PushError($"{Name}: set Source to a MeshInstance3D with a mesh, and make this node a child of a HairSystem3D.");
            return;
        }
        try
        {
            var surfaces = new List<MeshSurfaces.Surface>();
            for (int i = 0; i < mesh.GetSurfaceCount(); i++)
            {
                var arrays = mesh.SurfaceGetArrays(i);
                var vertices = arrays[(int)Mesh.ArrayType.Vertex].AsVector3Array().Select(v => v.ToNumerics()).ToArray();
                var indices = arrays[(int)Mesh.ArrayType.Index].AsInt32Array();
                var colors = arrays[(int)Mesh.ArrayType.Color].AsColorArray().Select(c => c.ToNumerics()).ToArray();
                surfaces.Add(new MeshSurfaces.Surface(vertices, indices, colors));
            }
            var toHead = (hair.GlobalTransform.AffineInverse() * Source.GlobalTransform).ToNumericsMatrix();
            var field = SignedDistanceField.Bake(MeshSurfaces.ToHeadSpace(surfaces, toHead), CellSize);
            Field = HairMeshField.From(field);
            GD.Print($"{Name}: distance field {field.Nx}×{field.Ny}×{field.Nz} baked in {field.BakeTime.TotalMilliseconds:F0} ms.");
        }
        catch (ArgumentException e)
        {
            GD.PushError($"{Name}: {e.Message}");
        }
    }

    /// <summary>The collider component for the hair's scene, or null (no field yet, or a corrupt one: reported).</summary>
    public MeshCollider? ToComponent()
    {
        if (_field == null || _field.Distances.Length == 0) return null;
        try { return new MeshCollider(_field.ToField(), _margin); }
        catch (ArgumentException e) { GD.PushError($"{Name}: the stored field is unusable ({e.Message}); bake it again."); return null; }
    }

    private void NotifyHair()
    {
        if (GetParent() is HairSystem3D hair) hair.CollidersChanged();
    }
}
