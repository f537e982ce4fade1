using System.Text.RegularExpressions;

namespace HairSheet.Addon.Tests;

/// <summary>
/// Godot 4.4+ refers to resources by UID: a scene's header and each ext_resource carry `uid="uid://…"`, and a script
/// or shader (which has no header of its own) keeps its UID in a `&lt;file&gt;.uid` file beside it. Without them the
/// editor invents UIDs on first open and rewrites the scene; with a wrong one it warns and falls back to the path.
/// The text form is Godot's ResourceUID::id_to_text (core/io/resource_uid.cpp): "uid://" then the id, at most
/// 0x7FFFFFFFFFFFFFFF, in base 34 with the digits a…y then 0…8, most significant first.
/// </summary>
public class GodotUidTests
{
    private const string Digits = "abcdefghijklmnopqrstuvwxy012345678";

    private static string Root()
    {
        for (var dir = new DirectoryInfo(AppContext.BaseDirectory); dir != null; dir = dir.Parent)
            if (File.Exists(Path.Combine(dir.FullName, "project.godot"))) return dir.FullName;
        throw new DirectoryNotFoundException("project.godot not found above the test directory.");
    }

    /// <summary>Godot's text_to_id, refusing what Godot would not write back the same way (so the text is canonical).</summary>
    private static bool TryParseUid(string text, out ulong id)
    {
        id = 0;
        if (!text.StartsWith("uid://", StringComparison.Ordinal) || text.Length < 7 || text.Length > 6 + 13) return false;
        foreach (char c in text[6..])
        {
            int d = Digits.IndexOf(c);
            if (d < 0) return false;
            UInt128 next = (UInt128)id * 34 + (uint)d;
            if (next > long.MaxValue) return false;
            id = (ulong)next;
        }
        return text[6] != 'a' || text.Length == 7; // no leading zero digit
    }

    /// <summary>Files Godot's file system sees (folders with a .gdignore are skipped, as the editor skips them).</summary>
    private static IEnumerable<string> GodotFiles(string root, string pattern)
    {
        var stack = new Stack<string>([root]);
        while (stack.Count > 0)
        {
            string dir = stack.Pop();
            if (File.Exists(Path.Combine(dir, ".gdignore"))) continue;
            foreach (var f in Directory.EnumerateFiles(dir, pattern)) yield return f;
            foreach (var d in Directory.EnumerateDirectories(dir))
                if (!Path.GetFileName(d).StartsWith('.') && Path.GetFileName(d) is not ("bin" or "obj")) stack.Push(d);
        }
    }

    [Fact]
    public void EveryScriptAndShaderHasItsOwnValidUid()
    {
        string root = Root();
        var seen = new Dictionary<ulong, string>();
        var files = GodotFiles(root, "*.cs").Concat(GodotFiles(root, "*.gdshader")).ToList();
        Assert.True(files.Count >= 30, $"only {files.Count} scripts and shaders found: is the scan still right?");
        foreach (var file in files)
        {
            string rel = Path.GetRelativePath(root, file);
            Assert.True(File.Exists(file + ".uid"), $"{rel} has no {Path.GetFileName(file)}.uid (Godot 4.4+ writes one for every script and shader)");
            string text = File.ReadAllText(file + ".uid").Trim();
            Assert.True(TryParseUid(text, out ulong id), $"{rel}.uid holds \"{text}\", not a UID as Godot writes it");
            Assert.False(seen.TryGetValue(id, out var other), $"{rel} and {other} share {text}");
            seen[id] = rel;
        }
    }

    /// <summary>
    /// A file's UID as Godot keeps it: in `&lt;file&gt;.uid` for scripts and shaders, in the `uid=` line of the [remap]
    /// section of `&lt;file&gt;.import` for imported files (a mesh, a texture), which the editor keeps when it reimports.
    /// </summary>
    private static string UidOf(string file)
    {
        if (File.Exists(file + ".uid")) return File.ReadAllText(file + ".uid").Trim();
        Assert.True(File.Exists(file + ".import"), $"{file} has neither a .uid nor a .import file");
        var m = Regex.Match(File.ReadAllText(file + ".import"), @"^\[remap\][^\[]*?^uid=""(?<uid>[^""]+)""", RegexOptions.Multiline | RegexOptions.Singleline);
        Assert.True(m.Success, $"{file}.import has no uid in its [remap] section");
        return m.Groups["uid"].Value;
    }

    [Fact]
    public void EveryShippedImportedFileKeepsItsUidInItsImportFile()
    {
        string root = Root();
        var seen = new Dictionary<ulong, string>();
        foreach (var file in GodotFiles(root, "*.cs").Concat(GodotFiles(root, "*.gdshader")).Concat(GodotFiles(root, "*.obj")))
        {
            Assert.True(TryParseUid(UidOf(file), out ulong id), $"{Path.GetRelativePath(root, file)}: bad uid");
            Assert.False(seen.TryGetValue(id, out var other), $"{Path.GetRelativePath(root, file)} and {other} share a uid");
            seen[id] = Path.GetRelativePath(root, file);
        }
        var obj = GodotFiles(root, "*.obj").ToList();
        Assert.NotEmpty(obj);
        foreach (var file in obj)
        {
            // Imported as a Mesh (ResourceImporterOBJ, "wavefront_obj"), not as a scene, so a MeshInstance3D can use it.
            string import = File.ReadAllText(file + ".import");
            Assert.Contains("importer=\"wavefront_obj\"", import);
            Assert.Contains("type=\"Mesh\"", import);
            Assert.Contains($"source_file=\"res://{Path.GetRelativePath(root, file).Replace('\\', '/')}\"", import);
        }
    }

    [Fact]
    public void ScenesReferToTheirResourcesByUid()
    {
        string root = Root();
        var scenes = GodotFiles(root, "*.tscn").ToList();
        Assert.NotEmpty(scenes);
        var sceneUids = new HashSet<ulong>();
        foreach (var scene in scenes)
        {
            string rel = Path.GetRelativePath(root, scene);
            var lines = File.ReadAllLines(scene);
            var header = Regex.Match(lines[0], @"^\[gd_scene [^\]]*\buid=""(?<uid>[^""]+)""");
            Assert.True(header.Success, $"{rel}: the [gd_scene] header has no uid");
            Assert.True(TryParseUid(header.Groups["uid"].Value, out ulong sceneUid) && sceneUids.Add(sceneUid), $"{rel}: bad or repeated scene uid");
            int ext = 0;
            foreach (var line in lines.Where(l => l.StartsWith("[ext_resource", StringComparison.Ordinal)))
            {
                ext++;
                var m = Regex.Match(line, @"\buid=""(?<uid>[^""]+)"" path=""res://(?<path>[^""]+)""");
                Assert.True(m.Success, $"{rel}: {line} has no uid before its path (Godot writes type, uid, path, id)");
                string target = Path.Combine(root, m.Groups["path"].Value);
                Assert.True(File.Exists(target), $"{rel}: {m.Groups["path"].Value} does not exist");
                Assert.Equal(UidOf(target), m.Groups["uid"].Value);
            }
            Assert.True(ext > 0, $"{rel} has no ext_resource lines: is the pattern still right?");
        }
    }
}
