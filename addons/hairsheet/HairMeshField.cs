using Godot;
using HairSim.Meshes;

namespace HairSheet;

/// <summary>
/// A baked signed distance field of a head or body mesh (head space), stored with the scene or as a .tres so the
/// bake is done once in the editor, not at every run. Made by HairMeshCollider3D's "Bake distance field" button.
/// </summary>
[Tool]
[GlobalClass]
public partial class HairMeshField : Resource
{
    [Export] public Vector3 Origin { get; set; }
    [Export(PropertyHint.Range, "0.0001,0.1,0.0001,suffix:m")] public float CellSize { get; set; } = 0.0025f;
    [Export] public Vector3I Cells { get; set; }
    [Export] public float[] Distances { get; set; } = [];
    /// <summary>How long the bake took (shown in the inspector; informative only).</summary>
    [Export] public float BakeMilliseconds { get; set; }
    /// <summary>
    /// What the field was baked relative to (Logic/ColliderFollowMath.FrameName): "head", or the node (and bone) a
    /// HairMeshCollider3D follows. A collider refuses a field baked in another frame. Fields baked before this was
    /// recorded were all baked in head space, which is the default.
    /// </summary>
    [Export] public string Frame { get; set; } = "head";
    /// <summary>For a scalp's field: the key of the mesh and cell size it was baked from (Logic/ScalpGrowth.FieldKey); empty otherwise.</summary>
    [Export] public string SourceKey { get; set; } = "";

    public static HairMeshField From(SignedDistanceField f, string frame = "head", string sourceKey = "") => new()
    {
        Origin = new Vector3(f.Origin.X, f.Origin.Y, f.Origin.Z), CellSize = f.CellSize, Cells = new Vector3I(f.Nx, f.Ny, f.Nz),
        Distances = f.CopyDistances(), BakeMilliseconds = (float)f.BakeTime.TotalMilliseconds, Frame = frame, SourceKey = sourceKey,
    };

    /// <summary>The stored field, checked (a corrupt resource raises ArgumentException with the reason).</summary>
    public SignedDistanceField ToField() =>
        SignedDistanceField.FromData(Origin.ToNumerics(), CellSize, Cells.X, Cells.Y, Cells.Z, Distances);
}
