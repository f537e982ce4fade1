using HairSheet.Logic;
using Godot;
using NVector2 = System.Numerics.Vector2;
using NVector3 = System.Numerics.Vector3;
using NVector4 = System.Numerics.Vector4;

namespace HairSheet;

/// <summary>Godot value types ↔ System.Numerics (HairSim's API), and a Camera3D → stroke camera matrices.</summary>
public static class GodotConvert
{
    public static NVector3 ToNumerics(this Vector3 v) => new(v.X, v.Y, v.Z);

    /// <summary>A Godot transform as a System.Numerics matrix (row vectors: p' = p · M, so the basis columns become rows).</summary>
    public static System.Numerics.Matrix4x4 ToNumericsMatrix(this Transform3D t) => new(
        t.Basis.Column0.X, t.Basis.Column0.Y, t.Basis.Column0.Z, 0f,
        t.Basis.Column1.X, t.Basis.Column1.Y, t.Basis.Column1.Z, 0f,
        t.Basis.Column2.X, t.Basis.Column2.Y, t.Basis.Column2.Z, 0f,
        t.Origin.X, t.Origin.Y, t.Origin.Z, 1f);
    public static NVector2 ToNumerics(this Vector2 v) => new(v.X, v.Y);
    public static NVector4 ToNumerics(this Color c) => new(c.R, c.G, c.B, c.A);
    public static Vector3 ToGodot(this NVector3 v) => new(v.X, v.Y, v.Z);
    public static Vector2 ToGodot(this NVector2 v) => new(v.X, v.Y);

    public static HairSim.RigidTransform ToRigid(this Transform3D t) =>
        HeadPoseMath.ToRigid(t.Basis.Column0.ToNumerics(), t.Basis.Column1.ToNumerics(), t.Basis.Column2.ToNumerics(), t.Origin.ToNumerics());

    /// <summary>A head pose with scale and any reflection stripped (<see cref="HeadPoseMath.HeadPose"/>).</summary>
    public static HairSim.RigidTransform ToHeadPose(this Transform3D t, out bool mirrored) =>
        HeadPoseMath.HeadPose(t.Basis.Column0.ToNumerics(), t.Basis.Column1.ToNumerics(), t.Basis.Column2.ToNumerics(), t.Origin.ToNumerics(), out mirrored);

    /// <summary>
    /// A mesh's triangle surfaces as Mesh.SurfaceGetArrays gives them (vertices, indices, colours; in the mesh's own
    /// space and Godot's clockwise winding: <see cref="MeshSurfaces"/> turns them into a HairSim mesh). Surfaces of lines
    /// or points are refused: a distance field or a scalp needs closed triangle surfaces.
    /// </summary>
    public static List<MeshSurfaces.Surface> ReadSurfaces(this Mesh mesh)
    {
        var surfaces = new List<MeshSurfaces.Surface>();
        for (int i = 0; i < mesh.GetSurfaceCount(); i++)
        {
            // Only ArrayMesh says what its surfaces are; PrimitiveMesh (SphereMesh, BoxMesh…) surfaces are triangles.
            if (mesh is ArrayMesh am && am.SurfaceGetPrimitiveType(i) != Mesh.PrimitiveType.Triangles)
                throw new ArgumentException($"surface {i} of the mesh is made of {am.SurfaceGetPrimitiveType(i)}, not triangles.");
            var arrays = mesh.SurfaceGetArrays(i);
            var vertices = arrays[(int)Mesh.ArrayType.Vertex].AsVector3Array().Select(v => v.ToNumerics()).ToArray();
            var indices = arrays[(int)Mesh.ArrayType.Index].AsInt32Array();
            var colors = arrays[(int)Mesh.ArrayType.Color].AsColorArray().Select(c => c.ToNumerics()).ToArray();
            surfaces.Add(new MeshSurfaces.Surface(vertices, indices, colors));
        }
        return surfaces;
    }

    public static Aabb ToAabb(this StrandBounds b) =>
        b.IsEmpty ? new Aabb(Vector3.Zero, Vector3.Zero) : new Aabb(b.Min.ToGodot(), b.Size.ToGodot());

    /// <summary>
    /// The camera as the stroke code needs it: view from the camera's global transform, projection from its
    /// lens, viewport = the size of the viewport the events' positions are measured in.
    /// </summary>
    public static CameraMatrices StrokeCamera(Camera3D camera, Vector2 viewportSize)
    {
        var t = camera.GlobalTransform;
        var view = StrokeCameraMath.View(t.Basis.Column0.ToNumerics(), t.Basis.Column1.ToNumerics(), t.Basis.Column2.ToNumerics(), t.Origin.ToNumerics());
        var size = viewportSize.ToNumerics();
        var keep = camera.KeepAspect == Camera3D.KeepAspectEnum.Width ? KeepAspect.Width : KeepAspect.Height;
        System.Numerics.Matrix4x4 projection = camera.Projection switch
        {
            Camera3D.ProjectionType.Orthogonal => StrokeCameraMath.Orthographic(camera.Size, camera.Near, camera.Far, size, keep),
            Camera3D.ProjectionType.Perspective => StrokeCameraMath.Perspective(camera.Fov, camera.Near, camera.Far, size, keep),
            // Frustum (and anything newer): take the engine's own matrix.
            _ => FromGodot(camera.GetCameraProjection()),
        };
        return new CameraMatrices(view, projection, size);
    }

    private static System.Numerics.Matrix4x4 FromGodot(Projection p) => StrokeCameraMath.FromGodotProjection(
        new NVector4(p.X.X, p.X.Y, p.X.Z, p.X.W), new NVector4(p.Y.X, p.Y.Y, p.Y.Z, p.Y.W),
        new NVector4(p.Z.X, p.Z.Y, p.Z.Z, p.Z.W), new NVector4(p.W.X, p.W.Y, p.W.Z, p.W.W));
}
