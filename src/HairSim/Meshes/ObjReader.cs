using System.Globalization;
using System.Numerics;

namespace HairSim.Meshes;

/// <summary>
/// Wavefront OBJ, the geometry part only: `v x y z [r g b]` (vertex colours as many tools write them) and `f` with
/// polygons fanned into triangles and `v/vt/vn` or negative (relative) indices; other statements are ignored.
/// </summary>
public static class ObjReader
{
    public static TriangleMesh Read(string path)
    {
        using var reader = new StreamReader(path);
        try { return Read(reader); }
        catch (FormatException e) { throw new InvalidDataException($"{path}: {e.Message}", e); }
        catch (ArgumentException e) { throw new InvalidDataException($"{path}: {e.Message}", e); }
    }

    public static TriangleMesh Read(TextReader reader)
    {
        var pos = new List<Vector3>();
        var col = new List<Vector4>();
        var idx = new List<int>();
        bool colours = false;
        var face = new List<int>();
        string? line;
        int lineNo = 0;
        while ((line = reader.ReadLine()) != null)
        {
            lineNo++;
            var t = line.AsSpan().Trim();
            if (t.IsEmpty || t[0] == '#') continue;
            var parts = t.ToString().Split((char[]?)null, StringSplitOptions.RemoveEmptyEntries);
            if (parts[0] == "v")
            {
                if (parts.Length < 4) throw new FormatException($"line {lineNo}: a vertex needs x y z.");
                pos.Add(new Vector3(Num(parts[1], lineNo), Num(parts[2], lineNo), Num(parts[3], lineNo)));
                if (parts.Length >= 7) { colours = true; col.Add(new Vector4(Num(parts[4], lineNo), Num(parts[5], lineNo), Num(parts[6], lineNo), 1f)); }
                else col.Add(Vector4.One);
            }
            else if (parts[0] == "f")
            {
                face.Clear();
                for (int k = 1; k < parts.Length; k++)
                {
                    var first = parts[k].Split('/')[0];
                    if (!int.TryParse(first, NumberStyles.Integer, CultureInfo.InvariantCulture, out int v) || v == 0)
                        throw new FormatException($"line {lineNo}: '{parts[k]}' is not a vertex index.");
                    int i = v > 0 ? v - 1 : pos.Count + v;
                    if (i < 0 || i >= pos.Count) throw new FormatException($"line {lineNo}: vertex {v} is not defined before this face.");
                    face.Add(i);
                }
                if (face.Count < 3) throw new FormatException($"line {lineNo}: a face needs at least three vertices.");
                for (int k = 1; k + 1 < face.Count; k++) { idx.Add(face[0]); idx.Add(face[k]); idx.Add(face[k + 1]); }
            }
        }
        if (idx.Count == 0) throw new FormatException("no faces.");
        return new TriangleMesh(pos.ToArray(), idx.ToArray(), colours ? col.ToArray() : null);
    }

    private static float Num(string s, int line) =>
        float.TryParse(s, NumberStyles.Float, CultureInfo.InvariantCulture, out float v) && float.IsFinite(v)
            ? v : throw new FormatException($"line {line}: '{s}' is not a finite number.");

    /// <summary>
    /// Writes a mesh as OBJ rounded to <paramref name="decimals"/> places (5 = 10 µm in metres), with vertex colours
    /// when it has them: a small file to ship (the Godot demo's head). Faces keep the mesh's counter-clockwise winding.
    /// </summary>
    public static void Write(TextWriter o, TriangleMesh mesh, int decimals)
    {
        if (decimals < 1 || decimals > 9) throw new ArgumentOutOfRangeException(nameof(decimals), decimals, "Decimals must be 1 … 9.");
        var ci = CultureInfo.InvariantCulture;
        string f = "0." + new string('#', decimals);
        // Rounded, then + 0 so that a tiny negative value is written "0", never "-0".
        string N(float v) => (MathF.Round(v, decimals) + 0f).ToString(f, ci);
        for (int i = 0; i < mesh.Positions.Length; i++)
        {
            var p = mesh.Positions[i];
            o.Write("v " + N(p.X) + " " + N(p.Y) + " " + N(p.Z));
            if (mesh.Colors != null) { var c = mesh.Colors[i]; o.Write(" " + N(c.X) + " " + N(c.Y) + " " + N(c.Z)); }
            o.Write('\n');
        }
        for (int t = 0; t < mesh.TriangleCount; t++)
            o.Write("f " + (mesh.Indices[3 * t] + 1).ToString(ci) + " " + (mesh.Indices[3 * t + 1] + 1).ToString(ci) + " " + (mesh.Indices[3 * t + 2] + 1).ToString(ci) + "\n");
    }

    /// <summary>Writes a mesh as OBJ (with vertex colours when it has them).</summary>
    public static void Write(TextWriter o, TriangleMesh mesh)
    {
        var ci = CultureInfo.InvariantCulture;
        for (int i = 0; i < mesh.Positions.Length; i++)
        {
            var p = mesh.Positions[i];
            o.Write(string.Format(ci, "v {0:R} {1:R} {2:R}", p.X, p.Y, p.Z));
            if (mesh.Colors != null) { var c = mesh.Colors[i]; o.Write(string.Format(ci, " {0:R} {1:R} {2:R}", c.X, c.Y, c.Z)); }
            o.WriteLine();
        }
        for (int t = 0; t < mesh.TriangleCount; t++)
            o.WriteLine(string.Format(ci, "f {0} {1} {2}", mesh.Indices[3 * t] + 1, mesh.Indices[3 * t + 1] + 1, mesh.Indices[3 * t + 2] + 1));
    }
}
