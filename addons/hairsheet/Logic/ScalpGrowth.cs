using System.Globalization;
using System.Numerics;
using System.Runtime.InteropServices;
using System.Security.Cryptography;
using HairSim;
using HairSim.Meshes;

namespace HairSheet.Logic;

/// <summary>
/// Hair grown on a scalp mesh in Godot (HairSystem3D's Scalp Mesh), engine-free: the Godot surfaces in head space
/// (winding reversed, <see cref="MeshSurfaces"/>), a key that says when that mesh has changed (for the growth key, so
/// the editor's regrow and undo machinery sees a new scalp as a new input, and to recognise a stored distance field),
/// and the growth itself through <see cref="MeshScalp.BuildScene"/>.
/// </summary>
public static class ScalpGrowth
{
    /// <summary>
    /// The scalp's key: a hash of the surfaces as Godot holds them (vertices, indices, colours) and the mesh's transform
    /// to the head, rounded to 10 µm and 1e-5 so float noise in the transform (the same scene computed after a head
    /// moved) does not count as a new scalp.
    /// </summary>
    public static string Key(IReadOnlyList<MeshSurfaces.Surface> surfaces, in Matrix4x4 meshToHead)
    {
        ArgumentNullException.ThrowIfNull(surfaces);
        using var hash = IncrementalHash.CreateHash(HashAlgorithmName.SHA256);
        Span<byte> count = stackalloc byte[12];
        foreach (var s in surfaces)
        {
            BitConverter.TryWriteBytes(count, s.Vertices.Length);
            BitConverter.TryWriteBytes(count[4..], s.Indices?.Length ?? -1);
            BitConverter.TryWriteBytes(count[8..], s.Colors?.Length ?? -1);
            hash.AppendData(count);
            hash.AppendData(MemoryMarshal.AsBytes(s.Vertices.AsSpan()));
            if (s.Indices != null) hash.AppendData(MemoryMarshal.AsBytes(s.Indices.AsSpan()));
            if (s.Colors != null) hash.AppendData(MemoryMarshal.AsBytes(s.Colors.AsSpan()));
        }
        var sb = new System.Text.StringBuilder(Convert.ToHexString(hash.GetHashAndReset(), 0, 12).ToLowerInvariant());
        sb.Append('@');
        var m = meshToHead;
        foreach (float v in new[] { m.M11, m.M12, m.M13, m.M21, m.M22, m.M23, m.M31, m.M32, m.M33, m.M41, m.M42, m.M43 })
            sb.Append((MathF.Round(v, 5) + 0f).ToString("F5", CultureInfo.InvariantCulture)).Append(',');
        return sb.ToString();
    }

    /// <summary>The key a stored distance field must carry to be reused for this scalp: the scalp's key and the cell size.</summary>
    public static string FieldKey(string scalpKey, float cellSize) =>
        scalpKey + "/cell=" + cellSize.ToString("R", CultureInfo.InvariantCulture);

    /// <summary>
    /// What a haircut styled on scalp-grown hair was styled on: the scalp's key, the painted mask's key (or none: the
    /// vertex colours) and every value that decides which strands grow where (groom counts, length, seed, the Scalp
    /// values), and nothing else, so changing damping or substeps keeps a Hairstyle's style, while a style cut on other
    /// strands is never applied to these.
    /// </summary>
    public static string StyleKey(HairNodeSettings settings, string scalpKey, byte[]? paintedMask)
    {
        ArgumentNullException.ThrowIfNull(settings);
        ArgumentNullException.ThrowIfNull(scalpKey);
        var c = CultureInfo.InvariantCulture;
        return string.Create(c, $"{scalpKey}|mask={(paintedMask == null ? "colours" : ScalpMask.Key(paintedMask))}|{settings.Sheets}x{settings.StrandsPerSheet}x{settings.ParticlesPerStrand}|length={settings.StrandLength:R}|seed={settings.Seed}|threshold={settings.ScalpMaskThreshold:R}|lift={settings.ScalpRootLift:R}|drape={settings.ScalpDrape:R}|cell={settings.ScalpCellSize:R}");
    }

    /// <summary>The scalp in head space (Godot's clockwise winding reversed; colours kept for the mask).</summary>
    public static TriangleMesh HeadSpaceMesh(IReadOnlyList<MeshSurfaces.Surface> surfaces, in Matrix4x4 meshToHead) =>
        MeshSurfaces.ToHeadSpace(surfaces, meshToHead);

    /// <summary>The scalp's distance field at the node's Scalp Cell Size.</summary>
    public static SignedDistanceField BakeField(TriangleMesh headSpaceMesh, HairNodeSettings settings) =>
        SignedDistanceField.Bake(headSpaceMesh, settings.ScalpCellSize);

    /// <summary>
    /// Grows the node's groom on the scalp: its Sheets, Strands Per Sheet, Particles Per Strand, Strand Length and Seed,
    /// the scalp's mask threshold, root lift and drape. The scene holds the mesh collider of that field (head space).
    /// With <paramref name="paintedMask"/> (a HairScalpMask's bytes, <see cref="ScalpMask"/>) the hair grows where it is
    /// painted instead of where the vertex colours say. Throws ArgumentException with the reason (no triangle on the
    /// scalp, too few roots fit, a mask painted on another mesh) for the node to show.
    /// </summary>
    public static HairScene Grow(TriangleMesh headSpaceMesh, SignedDistanceField field, HairNodeSettings settings, byte[]? paintedMask = null)
    {
        var groom = settings.ToMeshGroom();
        if (paintedMask != null) groom.Scalp = ScalpMask.Start(headSpaceMesh, paintedMask, settings.ScalpMaskThreshold);
        return MeshScalp.BuildScene(headSpaceMesh, field, groom, settings.ToSimulation());
    }
}
