using System.Numerics;
using SharpGLTF.Schema2;

namespace HairSim.Meshes;

/// <summary>
/// Loads a head or body mesh: glTF 2.0 (.glb/.gltf, through SharpGLTF: every triangle primitive of every node in the
/// default scene, placed by the node's world matrix, with COLOR_0 when present) or Wavefront OBJ (<see cref="ObjReader"/>).
/// Units are the file's (glTF: metres). A file that cannot be read raises InvalidDataException naming it.
/// </summary>
public static class MeshFile
{
    public static TriangleMesh Load(string path)
    {
        ArgumentNullException.ThrowIfNull(path);
        if (!File.Exists(path)) throw new FileNotFoundException($"No mesh file at {path}.", path);
        string ext = Path.GetExtension(path).ToLowerInvariant();
        return ext switch
        {
            ".glb" or ".gltf" => LoadGltf(path),
            ".obj" => ObjReader.Read(path),
            _ => throw new InvalidDataException($"{path}: unknown mesh format '{ext}' (use .glb, .gltf or .obj)."),
        };
    }

    public static TriangleMesh LoadGltf(string path)
    {
        ModelRoot model;
        try { model = ModelRoot.Load(path); }
        catch (Exception e) when (e is not (OutOfMemoryException or StackOverflowException))
        {
            throw new InvalidDataException($"{path}: not a readable glTF file ({e.Message}).", e);
        }
        var parts = new List<TriangleMesh>();
        var scene = model.DefaultScene ?? model.LogicalScenes.FirstOrDefault();
        var nodes = scene != null ? Flatten(scene.VisualChildren) : model.LogicalNodes;
        foreach (var node in nodes)
        {
            if (node.Mesh == null) continue;
            foreach (var prim in node.Mesh.Primitives)
            {
                if (prim.DrawPrimitiveType != PrimitiveType.TRIANGLES) continue;
                var pos = prim.GetVertexAccessor("POSITION")?.AsVector3Array();
                if (pos == null || pos.Count == 0) continue;
                var indices = prim.IndexAccessor != null ? prim.GetIndices().Select(i => checked((int)i)).ToArray() : Enumerable.Range(0, pos.Count).ToArray();
                var colours = prim.GetVertexAccessor("COLOR_0") is { } c ? ReadColours(c, pos.Count) : null;
                var part = new TriangleMesh(pos.ToArray(), indices, colours);
                parts.Add(part.Transformed(node.WorldMatrix));
            }
        }
        if (parts.Count == 0) throw new InvalidDataException($"{path}: no triangle meshes in the file.");
        return TriangleMesh.Combine(parts);
    }

    private static Vector4[] ReadColours(Accessor a, int count)
    {
        var c = a.Dimensions == DimensionType.VEC3 ? a.AsVector3Array().Select(v => new Vector4(v, 1f)).ToArray() : a.AsVector4Array().ToArray();
        if (c.Length != count) throw new InvalidDataException("COLOR_0 has a different count from POSITION.");
        return c;
    }

    private static IEnumerable<Node> Flatten(IEnumerable<Node> roots)
    {
        foreach (var n in roots)
        {
            yield return n;
            foreach (var c in Flatten(n.VisualChildren)) yield return c;
        }
    }
}
