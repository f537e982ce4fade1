using System.Numerics;

namespace HairSim.Meshes;

/// <summary>
/// A triangle mesh in head space (metres): the character's head or body, for growing hair on it
/// (<see cref="MeshScalp"/>) and colliding with it (<see cref="SignedDistanceField"/>). Vertex colours, when the
/// file has them, can mark where hair grows. Checked on construction: finite positions, indices in range,
/// at most <see cref="MaxTriangles"/> triangles.
/// </summary>
public sealed class TriangleMesh
{
    public const int MaxTriangles = 10_000_000;

    public TriangleMesh(Vector3[] positions, int[] indices, Vector4[]? colors = null)
    {
        ArgumentNullException.ThrowIfNull(positions);
        ArgumentNullException.ThrowIfNull(indices);
        if (positions.Length == 0 || indices.Length == 0) throw new ArgumentException("The mesh has no triangles.");
        if (indices.Length % 3 != 0) throw new ArgumentException($"Triangle indices come in threes; got {indices.Length}.", nameof(indices));
        if (indices.Length / 3 > MaxTriangles) throw new ArgumentException($"{indices.Length / 3:N0} triangles exceed the limit of {MaxTriangles:N0}.", nameof(indices));
        for (int i = 0; i < positions.Length; i++)
        {
            var p = positions[i];
            if (!float.IsFinite(p.X) || !float.IsFinite(p.Y) || !float.IsFinite(p.Z) || p.LengthSquared() > 1e8f)
                throw new ArgumentException($"Vertex {i} is not finite or lies beyond 10 km ({p}).", nameof(positions));
        }
        foreach (int k in indices)
            if ((uint)k >= (uint)positions.Length) throw new ArgumentException($"Triangle index {k} is outside the {positions.Length} vertices.", nameof(indices));
        if (colors != null && colors.Length != positions.Length) throw new ArgumentException("One colour per vertex.", nameof(colors));
        Positions = positions; Indices = indices; Colors = colors;
        var min = new Vector3(float.MaxValue); var max = new Vector3(float.MinValue);
        foreach (var p in positions) { min = Vector3.Min(min, p); max = Vector3.Max(max, p); }
        BoundsMin = min; BoundsMax = max;
    }

    public Vector3[] Positions { get; }
    public int[] Indices { get; }
    public Vector4[]? Colors { get; }
    public int TriangleCount => Indices.Length / 3;
    public Vector3 BoundsMin { get; }
    public Vector3 BoundsMax { get; }

    public (Vector3 A, Vector3 B, Vector3 C) Triangle(int t) => (Positions[Indices[3 * t]], Positions[Indices[3 * t + 1]], Positions[Indices[3 * t + 2]]);

    /// <summary>Unit face normal (counter-clockwise winding faces out, as glTF and OBJ define it); zero for a degenerate triangle.</summary>
    public Vector3 FaceNormal(int t)
    {
        var (a, b, c) = Triangle(t);
        var n = Vector3.Cross(b - a, c - a);
        float l = n.Length();
        return l > 0f ? n / l : Vector3.Zero;
    }

    public float TriangleArea(int t)
    {
        var (a, b, c) = Triangle(t);
        return 0.5f * Vector3.Cross(b - a, c - a).Length();
    }

    /// <summary>The same mesh with every vertex moved by a transform (for example a node's world matrix).</summary>
    public TriangleMesh Transformed(Matrix4x4 m)
    {
        var p = new Vector3[Positions.Length];
        for (int i = 0; i < p.Length; i++) p[i] = Vector3.Transform(Positions[i], m);
        // A mirroring transform turns the triangles inside out: swap two corners to keep them facing out.
        var idx = (int[])Indices.Clone();
        if (m.GetDeterminant() < 0) for (int t = 0; t < idx.Length; t += 3) (idx[t + 1], idx[t + 2]) = (idx[t + 2], idx[t + 1]);
        return new TriangleMesh(p, idx, Colors);
    }

    /// <summary>Several meshes as one (a head and its ears exported as separate parts).</summary>
    public static TriangleMesh Combine(IReadOnlyList<TriangleMesh> parts)
    {
        if (parts.Count == 0) throw new ArgumentException("No mesh parts.");
        if (parts.Count == 1) return parts[0];
        int nv = 0, ni = 0;
        bool colours = parts.Any(p => p.Colors != null);
        foreach (var p in parts) { nv += p.Positions.Length; ni += p.Indices.Length; }
        var pos = new Vector3[nv]; var idx = new int[ni]; var col = colours ? new Vector4[nv] : null;
        int v = 0, k = 0;
        foreach (var p in parts)
        {
            p.Positions.CopyTo(pos, v);
            if (col != null) { if (p.Colors != null) p.Colors.CopyTo(col, v); else col.AsSpan(v, p.Positions.Length).Fill(Vector4.One); }
            foreach (int i in p.Indices) idx[k++] = i + v;
            v += p.Positions.Length;
        }
        return new TriangleMesh(pos, idx, col);
    }

    /// <summary>A closed ellipsoid (UV sphere scaled by radii): the reference head as a mesh, for tests and comparisons.</summary>
    public static TriangleMesh Ellipsoid(Vector3 center, Vector3 radii, int rings = 48, int segments = 96)
    {
        if (rings < 3 || segments < 3) throw new ArgumentOutOfRangeException(nameof(rings), "At least 3 rings and 3 segments.");
        var pos = new List<Vector3> { center + new Vector3(0, radii.Y, 0) };
        for (int r = 1; r < rings; r++)
        {
            float phi = MathF.PI * r / rings;
            for (int s = 0; s < segments; s++)
            {
                float th = 2 * MathF.PI * s / segments;
                pos.Add(center + radii * new Vector3(MathF.Sin(phi) * MathF.Sin(th), MathF.Cos(phi), MathF.Sin(phi) * MathF.Cos(th)));
            }
        }
        pos.Add(center - new Vector3(0, radii.Y, 0));
        int bottom = pos.Count - 1;
        var idx = new List<int>();
        int Ring(int r, int s) => 1 + (r - 1) * segments + (s % segments);
        for (int s = 0; s < segments; s++) idx.AddRange([0, Ring(1, s), Ring(1, s + 1)]);
        for (int r = 1; r < rings - 1; r++)
            for (int s = 0; s < segments; s++)
                idx.AddRange([Ring(r, s), Ring(r + 1, s), Ring(r + 1, s + 1), Ring(r, s), Ring(r + 1, s + 1), Ring(r, s + 1)]);
        for (int s = 0; s < segments; s++) idx.AddRange([bottom, Ring(rings - 1, s + 1), Ring(rings - 1, s)]);
        return new TriangleMesh(pos.ToArray(), idx.ToArray());
    }

    /// <summary>A closed box (an ear-like slab in tests).</summary>
    public static TriangleMesh Box(Vector3 min, Vector3 max)
    {
        var p = new Vector3[8];
        for (int i = 0; i < 8; i++) p[i] = new Vector3((i & 1) != 0 ? max.X : min.X, (i & 2) != 0 ? max.Y : min.Y, (i & 4) != 0 ? max.Z : min.Z);
        int[] idx =
        [
            0, 2, 1, 1, 2, 3,   4, 5, 6, 5, 7, 6,   // −z, +z
            0, 1, 4, 1, 5, 4,   2, 6, 3, 3, 6, 7,   // −y, +y
            0, 4, 2, 2, 4, 6,   1, 3, 5, 3, 7, 5,   // −x, +x
        ];
        return new TriangleMesh(p, idx);
    }
}
