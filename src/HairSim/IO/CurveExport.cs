using System.Buffers.Binary;
using System.Globalization;
using System.Numerics;
using System.Text;

namespace HairSim.IO;

/// <summary>
/// Exports strands for other tools (Blender, Houdini, renderers): Cem Yuksel's binary .hair format, Wavefront
/// OBJ polylines and USD BasisCurves (.usda). Coordinates are written as they are (metres, +Y up); each file is
/// written to a temporary name and renamed.
/// </summary>
public static class CurveExport
{
    public const int CyHairHeaderBytes = 128;
    private const uint CySegmentsBit = 1, CyPointsBit = 2;

    /// <summary>
    /// Cem Yuksel's .hair: a 128-byte header ("HAIR", strand count, point count, array flags, default segment
    /// count, default thickness, transparency and colour, 88 bytes of text), then one u16 segment count per
    /// strand and 3 floats per point. Thickness, transparency and colour are left to the defaults.
    /// </summary>
    public static void WriteCyHair(Stream stream, StrandCurves curves, float thickness = 0.0001f, string info = "HairSheet")
    {
        ArgumentNullException.ThrowIfNull(stream);
        ArgumentNullException.ThrowIfNull(curves);
        var header = new byte[CyHairHeaderBytes];
        "HAIR"u8.CopyTo(header);
        BinaryPrimitives.WriteUInt32LittleEndian(header.AsSpan(4), (uint)curves.StrandCount);
        BinaryPrimitives.WriteUInt32LittleEndian(header.AsSpan(8), (uint)curves.Points.Length);
        BinaryPrimitives.WriteUInt32LittleEndian(header.AsSpan(12), CySegmentsBit | CyPointsBit);
        BinaryPrimitives.WriteUInt32LittleEndian(header.AsSpan(16), (uint)(curves.Counts.Length > 0 ? curves.Counts[0] - 1 : 0));
        BinaryPrimitives.WriteSingleLittleEndian(header.AsSpan(20), thickness);
        BinaryPrimitives.WriteSingleLittleEndian(header.AsSpan(24), 0f); // transparency
        BinaryPrimitives.WriteSingleLittleEndian(header.AsSpan(28), 0.3f); // colour r, g, b
        BinaryPrimitives.WriteSingleLittleEndian(header.AsSpan(32), 0.2f);
        BinaryPrimitives.WriteSingleLittleEndian(header.AsSpan(36), 0.1f);
        var text = Encoding.ASCII.GetBytes(info ?? "");
        text.AsSpan(0, Math.Min(text.Length, 87)).CopyTo(header.AsSpan(40));
        stream.Write(header);

        var seg = new byte[2 * curves.StrandCount];
        for (int s = 0; s < curves.StrandCount; s++)
        {
            int n = curves.Counts[s] - 1;
            if (n > ushort.MaxValue) throw new ArgumentException($"Strand {s} has {n} segments; .hair allows at most {ushort.MaxValue}.", nameof(curves));
            BinaryPrimitives.WriteUInt16LittleEndian(seg.AsSpan(2 * s), (ushort)n);
        }
        stream.Write(seg);
        var buf = new byte[12 * 4096];
        for (int i = 0; i < curves.Points.Length; i += 4096)
        {
            int n = Math.Min(4096, curves.Points.Length - i);
            for (int k = 0; k < n; k++)
            {
                var p = curves.Points[i + k];
                BinaryPrimitives.WriteSingleLittleEndian(buf.AsSpan(12 * k), p.X);
                BinaryPrimitives.WriteSingleLittleEndian(buf.AsSpan(12 * k + 4), p.Y);
                BinaryPrimitives.WriteSingleLittleEndian(buf.AsSpan(12 * k + 8), p.Z);
            }
            stream.Write(buf, 0, 12 * n);
        }
    }

    /// <summary>OBJ: one "v x y z" per point and one "l i j k …" polyline (1-based) per strand.</summary>
    public static void WriteObj(TextWriter o, StrandCurves curves)
    {
        ArgumentNullException.ThrowIfNull(o);
        ArgumentNullException.ThrowIfNull(curves);
        var ci = CultureInfo.InvariantCulture;
        o.Write("# HairSheet strands: "); o.Write(curves.StrandCount.ToString(ci)); o.Write(" polylines\no hair\n");
        foreach (var p in curves.Points)
        {
            o.Write("v "); o.Write(p.X.ToString("R", ci)); o.Write(' '); o.Write(p.Y.ToString("R", ci)); o.Write(' '); o.Write(p.Z.ToString("R", ci)); o.Write('\n');
        }
        int index = 1;
        foreach (int c in curves.Counts)
        {
            o.Write('l');
            for (int k = 0; k < c; k++) { o.Write(' '); o.Write((index++).ToString(ci)); }
            o.Write('\n');
        }
    }

    /// <summary>USD ASCII: one linear BasisCurves prim with curveVertexCounts and points (metres, Y up).</summary>
    public static void WriteUsda(TextWriter o, StrandCurves curves, float width = 0.0001f)
    {
        ArgumentNullException.ThrowIfNull(o);
        ArgumentNullException.ThrowIfNull(curves);
        var ci = CultureInfo.InvariantCulture;
        o.Write("#usda 1.0\n(\n    defaultPrim = \"Hair\"\n    metersPerUnit = 1\n    upAxis = \"Y\"\n)\n\n");
        o.Write("def BasisCurves \"Hair\"\n{\n    uniform token type = \"linear\"\n    uniform token wrap = \"nonperiodic\"\n");
        o.Write("    int[] curveVertexCounts = [");
        for (int s = 0; s < curves.StrandCount; s++) { if (s > 0) o.Write(", "); o.Write(curves.Counts[s].ToString(ci)); }
        o.Write("]\n    point3f[] points = [");
        for (int i = 0; i < curves.Points.Length; i++)
        {
            var p = curves.Points[i];
            if (i > 0) o.Write(", ");
            o.Write('('); o.Write(p.X.ToString("R", ci)); o.Write(", "); o.Write(p.Y.ToString("R", ci)); o.Write(", "); o.Write(p.Z.ToString("R", ci)); o.Write(')');
        }
        o.Write("]\n    float[] widths = ["); o.Write(width.ToString("R", ci)); o.Write("] (\n        interpolation = \"constant\"\n    )\n}\n");
    }

    public static void WriteCyHair(string path, StrandCurves curves) => SafeFile.Write(path, s => WriteCyHair(s, curves));
    public static void WriteObj(string path, StrandCurves curves) => WriteText(path, o => WriteObj(o, curves));
    public static void WriteUsda(string path, StrandCurves curves) => WriteText(path, o => WriteUsda(o, curves));

    internal static void WriteText(string path, Action<TextWriter> write) => SafeFile.Write(path, s =>
    {
        using var o = new StreamWriter(s, new UTF8Encoding(false), 1 << 16, leaveOpen: true);
        write(o);
    });
}
