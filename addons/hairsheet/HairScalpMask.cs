using Godot;

namespace HairSheet;

/// <summary>
/// The scalp painted on a HairSystem3D's Scalp Mesh with the editor's Paint scalp / Erase scalp tools: one bit per
/// triangle (Logic/ScalpMask), and the key of the mesh and its place on the head it was painted on, so a mask of
/// another mesh is not used (the node then grows where the vertex colours say and tells why).
/// </summary>
[Tool]
[GlobalClass]
public partial class HairScalpMask : Resource
{
    /// <summary>Triangle t is scalp when bit t % 8 of byte t / 8 is set.</summary>
    [Export] public byte[] Triangles { get; set; } = [];
    [Export] public int TriangleCount { get; set; }
    /// <summary>The scalp's key when it was painted (Logic/ScalpGrowth.Key).</summary>
    [Export] public string ScalpKey { get; set; } = "";
}
