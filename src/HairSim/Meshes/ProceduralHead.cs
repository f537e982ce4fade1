using System.Numerics;

namespace HairSim.Meshes;

/// <summary>
/// A head made by the project (licence-clean, no file needed): the reference groom's head ellipsoid with ears,
/// a nose and a neck as separate closed parts, its scalp painted red in the vertex colours (the crown and the back,
/// down to the ears, not the face). About 34k triangles. For the demo, the studio and tests of mesh heads.
/// </summary>
public static class ProceduralHead
{
    public static readonly Vector3 CraniumRadii = new(0.078f, 0.1f, 0.095f);

    public static TriangleMesh Create(int detail = 1)
    {
        if (detail < 1 || detail > 4) throw new ArgumentOutOfRangeException(nameof(detail), detail, "Detail must be 1 … 4.");
        return Build(72 * detail, 16 * detail);
    }

    /// <summary>
    /// The same head with fewer triangles (9,048: a 40-ring cranium, 12-ring ears and nose), small enough to ship as a
    /// file: the Godot demo's head (scenes/head.obj). The cranium's chords stay within 0.08 mm of its ellipsoid.
    /// </summary>
    public static TriangleMesh CreateLowPoly() => Build(40, 12);

    // Ellipsoids of `rings` rings and 2 × rings segments; the neck has 1.5 × the ears' rings.
    private static TriangleMesh Build(int craniumRings, int partRings)
    {
        var cranium = Paint(TriangleMesh.Ellipsoid(Vector3.Zero, CraniumRadii, craniumRings, 2 * craniumRings), OnScalp);
        var parts = new List<TriangleMesh> { cranium };
        foreach (float side in new[] { -1f, 1f })   // ears: 8 mm thick, standing slightly off the head
            parts.Add(Paint(TriangleMesh.Ellipsoid(new Vector3(side * 0.079f, -0.008f, -0.006f), new Vector3(0.004f, 0.03f, 0.017f), partRings, 2 * partRings), _ => false));
        parts.Add(Paint(TriangleMesh.Ellipsoid(new Vector3(0, -0.022f, 0.094f), new Vector3(0.011f, 0.022f, 0.016f), partRings, 2 * partRings), _ => false));
        parts.Add(Paint(TriangleMesh.Ellipsoid(new Vector3(0, -0.14f, -0.012f), new Vector3(0.05f, 0.08f, 0.05f), partRings * 3 / 2, 3 * partRings), _ => false));
        return TriangleMesh.Combine(parts);
    }

    /// <summary>The scalp: above the ears all round, receding from the forehead (as the ellipsoid groom's scalp does).</summary>
    public static bool OnScalp(Vector3 p)
    {
        var u = Vector3.Normalize(p / CraniumRadii);
        float fromTop = MathF.Acos(Math.Clamp(u.Y, -1f, 1f));
        float front = MathF.Max(0f, u.Z);   // 0 at the sides and back, 1 at the face
        return fromTop < 1.95f - (1.95f - 0.95f) * front;
    }

    private static TriangleMesh Paint(TriangleMesh m, Func<Vector3, bool> scalp) =>
        new(m.Positions, m.Indices, m.Positions.Select(p => scalp(p) ? new Vector4(1, 0, 0, 1) : new Vector4(0, 0, 0, 1)).ToArray());
}
