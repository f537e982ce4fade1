using System.Numerics;
using System.Security.Cryptography;
using HairSim;
using HairSim.Editing;
using HairSim.Meshes;

namespace HairSheet.Logic;

/// <summary>
/// The painted scalp of HairSystem3D's Scalp Mesh, engine-free: one bit per triangle of the head-space mesh (the
/// HairScalpMask resource stores the bytes), a brush stroke painted into it through the library's
/// <see cref="ScalpPaint"/> (the same camera and screen areas as cut and fit), the growth key's part, and the
/// triangles to draw as the overlay that shows what is painted.
/// </summary>
public static class ScalpMask
{
    /// <summary>Flags packed 8 to a byte, triangle t in bit t % 8 of byte t / 8.</summary>
    public static byte[] Pack(ReadOnlySpan<bool> triangles)
    {
        var bits = new byte[(triangles.Length + 7) / 8];
        for (int t = 0; t < triangles.Length; t++) if (triangles[t]) bits[t >> 3] |= (byte)(1 << (t & 7));
        return bits;
    }

    /// <summary>The flags of <paramref name="triangleCount"/> triangles; bytes of another length (another mesh, a corrupt resource) are refused.</summary>
    public static bool[] Unpack(byte[] bits, int triangleCount)
    {
        ArgumentNullException.ThrowIfNull(bits);
        if (triangleCount < 0 || bits.Length != (triangleCount + 7) / 8)
            throw new ArgumentException($"The scalp mask holds {bits.Length} bytes, but a mesh of {triangleCount} triangles needs {(triangleCount + 7) / 8}: it was painted on another mesh.", nameof(bits));
        var flags = new bool[triangleCount];
        for (int t = 0; t < triangleCount; t++) flags[t] = (bits[t >> 3] & (1 << (t & 7))) != 0;
        return flags;
    }

    /// <summary>Painted triangles.</summary>
    public static int Count(byte[] bits)
    {
        int n = 0;
        foreach (byte b in bits) n += BitOperations.PopCount(b);
        return n;
    }

    /// <summary>A short hash of the mask for the growth key: painting regrows the hair, undoing a stroke brings the earlier hair back.</summary>
    public static string Key(byte[] bits) => Convert.ToHexString(SHA256.HashData(bits), 0, 8).ToLowerInvariant();

    /// <summary>The scalp to grow on: the stored mask when there is one for this mesh, else the mesh's vertex colours (red at least <paramref name="threshold"/>).</summary>
    public static ScalpPaint Start(TriangleMesh headSpaceMesh, byte[]? bits, float threshold) =>
        bits == null ? ScalpPaint.FromVertexColours(headSpaceMesh, threshold)
            : ScalpPaint.FromMask(headSpaceMesh, Unpack(bits, headSpaceMesh.TriangleCount));

    /// <summary>
    /// One brush stroke: discs of <paramref name="radius"/> pixels along the stroke (<see cref="SelectionArea.BrushStroke"/>) mark
    /// (<see cref="ScalpPaintMode.Add"/>) or clear the triangles whose centre they cover, that face the camera and that
    /// the mesh itself does not hide (<paramref name="occluder"/>, the scalp's collider, when known). Returns the new
    /// mask, or null when the stroke changed nothing. Bad input (an empty stroke, a non-finite point, a radius that is
    /// not positive, a mask of another mesh) throws ArgumentException and changes nothing.
    /// </summary>
    public static byte[]? Paint(TriangleMesh headSpaceMesh, byte[]? bits, float threshold, IReadOnlyList<Vector2> stroke, float radius,
        ScalpPaintMode mode, in CameraMatrices camera, in RigidTransform head, MeshCollider? occluder = null)
    {
        ArgumentNullException.ThrowIfNull(headSpaceMesh);
        var dabs = SelectionArea.BrushStroke(stroke, radius);   // checks the stroke and the radius first
        var paint = Start(headSpaceMesh, bits, threshold);
        int changed = paint.Paint(StrokeCameras.From(camera), dabs, mode, head, occluder);
        return changed == 0 && bits != null ? null : Pack(paint.Triangles);
    }

    /// <summary>
    /// The painted triangles as a triangle list in head space, each lifted <paramref name="lift"/> metres along its
    /// normal so the overlay is drawn over the head's own surface (for the paint tool's view of the mask).
    /// </summary>
    public static Vector3[] Overlay(TriangleMesh headSpaceMesh, ReadOnlySpan<bool> triangles, float lift)
    {
        ArgumentNullException.ThrowIfNull(headSpaceMesh);
        int n = 0;
        foreach (bool b in triangles) if (b) n++;
        var v = new Vector3[3 * n];
        int o = 0;
        for (int t = 0; t < triangles.Length; t++)
        {
            if (!triangles[t]) continue;
            var (a, b, c) = headSpaceMesh.Triangle(t);
            var up = headSpaceMesh.FaceNormal(t) * lift;
            v[o++] = a + up; v[o++] = b + up; v[o++] = c + up;
        }
        return v;
    }
}
