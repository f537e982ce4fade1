using System.Numerics;
using HairSim.Meshes;

namespace HairSheet.Logic;

/// <summary>
/// A Godot mesh's surfaces (vertex, index and colour arrays, as Mesh.SurfaceGetArrays gives them) as one HairSim
/// triangle mesh in head space. Godot's front faces wind clockwise; HairSim's (as glTF's) counter-clockwise, so every
/// triangle's winding is reversed, or the distance field would be inside out.
/// </summary>
public static class MeshSurfaces
{
    public readonly record struct Surface(Vector3[] Vertices, int[]? Indices, Vector4[]? Colors);

    public static TriangleMesh ToHeadSpace(IReadOnlyList<Surface> surfaces, Matrix4x4 meshToHead)
    {
        var parts = new List<TriangleMesh>();
        foreach (var s in surfaces)
        {
            if (s.Vertices.Length == 0) continue;
            var idx = s.Indices is { Length: > 0 } i ? (int[])i.Clone() : Enumerable.Range(0, s.Vertices.Length).ToArray();
            if (idx.Length % 3 != 0) throw new ArgumentException($"A surface has {idx.Length} indices: only triangle surfaces can be hair colliders.");
            for (int t = 0; t < idx.Length; t += 3) (idx[t + 1], idx[t + 2]) = (idx[t + 2], idx[t + 1]);
            var colors = s.Colors is { Length: > 0 } c && c.Length == s.Vertices.Length ? c : null;
            parts.Add(new TriangleMesh(s.Vertices, idx, colors).Transformed(meshToHead));
        }
        if (parts.Count == 0) throw new ArgumentException("The mesh has no triangles.");
        return TriangleMesh.Combine(parts);
    }
}
