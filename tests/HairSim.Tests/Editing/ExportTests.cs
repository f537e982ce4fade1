using System.Globalization;
using System.Numerics;
using System.Text.RegularExpressions;
using HairSim;
using HairSim.Editing;
using HairSim.IO;

namespace HairSim.Tests.Editing;

/// <summary>Exports are read back by small independent readers written here from the formats' descriptions.</summary>
public sealed class ExportTests : IDisposable
{
    private readonly string _dir = Path.Combine(Path.GetTempPath(), "hairsheet-export-" + Guid.NewGuid().ToString("N"));
    public ExportTests() => Directory.CreateDirectory(_dir);
    public void Dispose() { try { Directory.Delete(_dir, true); } catch (IOException) { } }

    private static StrandCurves CutCurves()
    {
        var scene = GroomBuilder.BuildScene(new GroomSettings { SheetCount = 7, StrandsPerSheet = 4, ParticlesPerStrand = 9 });
        var cam = StrokeCamera.LookAtOrthographic(new Vector3(0, 0, 1), Vector3.Zero, Vector3.UnitY, 0.6f, new Vector2(600, 600));
        HairEditor.Cut(scene, new Stroke([new Vector2(0, 200), new Vector2(600, 230)], cam), new CutOptions { Reach = CutReach.AllThrough }).Apply();
        var curves = StrandCurves.FromWorld(scene.World);
        Assert.Contains(curves.Counts, c => c < 9); // strands of different lengths
        return curves;
    }

    private static void AssertSame(StrandCurves expected, List<Vector3[]> strands)
    {
        Assert.Equal(expected.StrandCount, strands.Count);
        int o = 0;
        for (int s = 0; s < strands.Count; s++)
        {
            Assert.Equal(expected.Counts[s], strands[s].Length);
            foreach (var p in strands[s]) Assert.Equal(expected.Points[o++], p);
        }
    }

    [Fact]
    public void CyHairFileReadsBackWithAnIndependentReader()
    {
        var curves = CutCurves();
        var path = Path.Combine(_dir, "a.hair");
        CurveExport.WriteCyHair(path, curves);
        using var r = new BinaryReader(File.OpenRead(path));
        Assert.Equal("HAIR", new string(r.ReadChars(4)));
        uint strands = r.ReadUInt32(), points = r.ReadUInt32(), flags = r.ReadUInt32(), defaultSegments = r.ReadUInt32();
        float thickness = r.ReadSingle(), transparency = r.ReadSingle();
        r.ReadBytes(12); // default colour
        r.ReadBytes(88); // info
        Assert.Equal(128, r.BaseStream.Position);
        Assert.True(thickness > 0 && transparency >= 0);
        Assert.Equal(3u, flags & 3u); // segments and points arrays present
        Assert.Equal(0u, flags & ~3u); // no thickness/transparency/colour arrays
        var segs = new int[strands];
        for (int s = 0; s < strands; s++) segs[s] = (flags & 1) != 0 ? r.ReadUInt16() : (int)defaultSegments;
        var list = new List<Vector3[]>();
        long used = 0;
        foreach (int n in segs)
        {
            var pts = new Vector3[n + 1];
            for (int k = 0; k <= n; k++) pts[k] = new Vector3(r.ReadSingle(), r.ReadSingle(), r.ReadSingle());
            list.Add(pts);
            used += n + 1;
        }
        Assert.Equal(points, (uint)used);
        Assert.Equal(r.BaseStream.Length, r.BaseStream.Position);
        AssertSame(curves, list);
    }

    [Fact]
    public void ObjPolylinesReadBack()
    {
        var curves = CutCurves();
        var path = Path.Combine(_dir, "a.obj");
        CurveExport.WriteObj(path, curves);
        var verts = new List<Vector3>();
        var list = new List<Vector3[]>();
        foreach (var line in File.ReadLines(path))
        {
            var f = line.Split(' ', StringSplitOptions.RemoveEmptyEntries);
            if (f.Length == 0 || f[0] == "#" || f[0] == "o") continue;
            if (f[0] == "v") verts.Add(new Vector3(float.Parse(f[1], CultureInfo.InvariantCulture), float.Parse(f[2], CultureInfo.InvariantCulture), float.Parse(f[3], CultureInfo.InvariantCulture)));
            else if (f[0] == "l") list.Add(f.Skip(1).Select(i => verts[int.Parse(i, CultureInfo.InvariantCulture) - 1]).ToArray());
            else Assert.Fail($"unexpected OBJ line: {line}");
        }
        AssertSame(curves, list);
    }

    [Fact]
    public void UsdaBasisCurvesReadBack()
    {
        var curves = CutCurves();
        var path = Path.Combine(_dir, "a.usda");
        CurveExport.WriteUsda(path, curves);
        var text = File.ReadAllText(path);
        Assert.StartsWith("#usda 1.0", text);
        Assert.Contains("def BasisCurves", text);
        var counts = Regex.Match(text, @"int\[\] curveVertexCounts = \[([^\]]*)\]").Groups[1].Value
            .Split(',', StringSplitOptions.TrimEntries).Select(c => int.Parse(c, CultureInfo.InvariantCulture)).ToArray();
        var pts = Regex.Matches(Regex.Match(text, @"point3f\[\] points = \[([^\]]*)\]").Groups[1].Value, @"\(([^)]*)\)")
            .Select(m => m.Groups[1].Value.Split(',', StringSplitOptions.TrimEntries).Select(v => float.Parse(v, CultureInfo.InvariantCulture)).ToArray())
            .Select(v => new Vector3(v[0], v[1], v[2])).ToArray();
        var list = new List<Vector3[]>();
        int o = 0;
        foreach (int c in counts) { list.Add(pts[o..(o + c)]); o += c; }
        Assert.Equal(pts.Length, o);
        AssertSame(curves, list);
    }

    [Fact]
    public void SvgPictureHasOnePolylinePerStrandAndHighlightsTheSelection()
    {
        var scene = GroomBuilder.BuildScene(new GroomSettings { SheetCount = 5, StrandsPerSheet = 3, ParticlesPerStrand = 5 });
        var mask = new bool[scene.World.StrandCount];
        mask[2] = mask[7] = true;
        var path = Path.Combine(_dir, "a.svg");
        SvgExport.Write(path, scene, SvgExport.View.Side, highlight: mask, title: "side <test>");
        var text = File.ReadAllText(path);
        // Strands are split where they pass behind the head's centre plane (drawn under the head) and in front of it,
        // each piece keeping the crossing segment: every particle is drawn, in one piece or two.
        var groups = Regex.Matches(text, "<g [^>]*stroke=\"(?<colour>#[0-9a-f]+)\"[^>]*>(?<body>.*?)</g>", RegexOptions.Singleline);
        int Points(string colour) => groups.Where(g => g.Groups["colour"].Value == colour)
            .Sum(g => Regex.Matches(g.Groups["body"].Value, @"-?\d+\.\d,-?\d+\.\d").Count);
        int plain = 0;
        for (int s = 0; s < scene.World.StrandCount; s++) if (!mask[s]) plain += scene.World.StrandParticleCount[s];
        int lit = scene.World.StrandParticleCount[2] + scene.World.StrandParticleCount[7];
        int polylines = Regex.Matches(text, "<polyline").Count;
        Assert.InRange(polylines, scene.World.StrandCount, 2 * scene.World.StrandCount);
        // Each extra piece repeats the two ends of its crossing segment.
        Assert.Equal(plain + lit + 2 * (polylines - scene.World.StrandCount), Points("#5a3b24") + Points("#d2452b"));
        Assert.InRange(Points("#d2452b"), lit, lit + 4);
        Assert.Contains("&lt;test&gt;", text);
    }

    [Fact]
    public void SvgFrontViewDrawsHairBehindTheHeadUnderIt()
    {
        // Two strands hanging across the face in the picture: one 15 cm behind the head's centre, one 15 cm in front.
        var world = new HairWorld(1, 2, 4);
        for (int s = 0; s < 2; s++)
        {
            float z = s == 0 ? -0.15f : 0.15f;
            world.SetStrand(s, [new(0.01f * s, 0.05f, z), new(0.01f * s, 0f, z), new(0.01f * s, -0.05f, z), new(0.01f * s, -0.1f, z)]);
        }
        world.ResetToRest();
        var scene = new HairScene(world);
        scene.AddCollider(Collider.Ellipsoid(Vector3.Zero, new Vector3(0.08f, 0.1f, 0.09f)));
        var o = new StringWriter();
        SvgExport.Write(o, scene, SvgExport.View.Front, extent: 0.4f);
        string text = o.ToString();
        int head = text.IndexOf("<ellipse", StringComparison.Ordinal);
        Assert.True(head > 0);
        var before = Regex.Matches(text[..head], "<polyline").Count;
        var after = Regex.Matches(text[head..], "<polyline").Count;
        // The strand behind is painted first, so the head covers it; the one in front is painted over the head.
        Assert.Equal(1, before);
        Assert.Equal(1, after);
        // The one painted under the head is the one behind it: its x is the first strand's (0), the other's is 1 cm right.
        string under = Regex.Match(text[..head], "<polyline points=\"(?<x>[0-9.]+),").Groups["x"].Value;
        string over = Regex.Match(text[head..], "<polyline points=\"(?<x>[0-9.]+),").Groups["x"].Value;
        Assert.True(float.Parse(under, CultureInfo.InvariantCulture) < float.Parse(over, CultureInfo.InvariantCulture));
    }

    [Fact]
    public void Crc32MatchesTheStandardCheckValue()
    {
        Assert.Equal(0xCBF43926u, Crc32.Compute("123456789"u8));
        Assert.Equal(Crc32.Compute("hello world"u8), Crc32.Append(Crc32.Compute("hello "u8), "world"u8));
    }
}
