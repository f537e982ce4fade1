using System.Globalization;
using System.Numerics;
using System.Reflection;
using System.Text.RegularExpressions;
using HairSheet.Logic;
using HairSim;

namespace HairSheet.Addon.Tests;

/// <summary>
/// Godot's C# source generator records an exported property's default (the value the inspector reverts to, and
/// the one a scene file leaves out) from its backing field's initializer, or an auto-property's; for any other getter
/// it records default(T), so a value equal to 0 is not saved (godot #90872, #105348). The node classes cannot be
/// compiled here (no Godot packages), so their source is read: every exported property is an auto-property or
/// returns a field, every such value-type field has an initializer, and HairSystem3D's initializers equal the
/// defaults of HairNodeSettings, which is what the node simulates with until a setter runs.
/// </summary>
public class ExportDefaultsTests
{
    private static string AddonDir()
    {
        for (var dir = new DirectoryInfo(AppContext.BaseDirectory); dir != null; dir = dir.Parent)
        {
            string path = Path.Combine(dir.FullName, "addons", "hairsheet");
            if (Directory.Exists(path)) return path;
        }
        throw new DirectoryNotFoundException("addons/hairsheet not found above the test directory.");
    }

    private static readonly Regex ExportedProperty = new(
        @"\[Export[^\]]*\]\s*public\s+(?<type>[\w.?<>\[\]]+)\s+(?<name>\w+)\s*\{\s*(?<body>get\s*(=>\s*(?<field>\w+)\s*;|;)|get\s*\{\s*return\s+(?<field>\w+)\s*;\s*\})",
        RegexOptions.Compiled);

    [Fact]
    public void EveryExportedValueHasADefaultTheGeneratorCanSee()
    {
        int checkedProperties = 0;
        foreach (var file in Directory.EnumerateFiles(AddonDir(), "*.cs", SearchOption.AllDirectories))
        {
            string text = File.ReadAllText(file);
            foreach (Match m in ExportedProperty.Matches(text))
            {
                string type = m.Groups["type"].Value, name = m.Groups["name"].Value;
                checkedProperties++;
                if (!m.Groups["field"].Success) continue; // an auto-property: its initializer (or default) is the default
                string field = m.Groups["field"].Value;
                var decl = new Regex(@"private\s+(readonly\s+)?[\w.?<>\[\]]+\s+" + Regex.Escape(field) + @"\s*(=\s*(?<init>[^;]+))?;").Match(text);
                Assert.True(decl.Success, $"{Path.GetFileName(file)}: {name} returns {field}, which is not a field of the class");
                bool reference = type.EndsWith('?');
                Assert.True(reference || decl.Groups["init"].Success, $"{Path.GetFileName(file)}: {field} (behind {name}) has no initializer");
            }
        }
        Assert.True(checkedProperties >= 30, $"only {checkedProperties} exported properties found: is the pattern still right?");
    }

    [Fact]
    public void HairSystemFieldInitializersAreTheSettingsDefaults()
    {
        string text = File.ReadAllText(Path.Combine(AddonDir(), "HairSystem3D.cs"));
        var defaults = new HairNodeSettings();
        int compared = 0;
        foreach (Match m in ExportedProperty.Matches(text))
        {
            string name = m.Groups["name"].Value;
            var prop = typeof(HairNodeSettings).GetProperty(name, BindingFlags.Public | BindingFlags.Instance);
            if (prop == null || !m.Groups["field"].Success) continue;
            string field = m.Groups["field"].Value;
            string init = new Regex(@"private\s+[\w.?<>]+\s+" + Regex.Escape(field) + @"\s*=\s*(?<init>[^;]+);").Match(text).Groups["init"].Value.Trim();
            Assert.False(string.IsNullOrEmpty(init), $"{field} has no initializer");
            object expected = prop.GetValue(defaults)!;
            Assert.True(Same(Evaluate(init), expected), $"{name}: the field's initializer {init} is not HairNodeSettings' default {expected}");
            compared++;
        }
        Assert.True(compared >= 20, $"only {compared} settings compared");
    }

    /// <summary>The literal forms the fields use: numbers, enum members, new Vector3(…), new Color(…).</summary>
    private static object Evaluate(string init)
    {
        var ctor = Regex.Match(init, @"^new\s+(?<type>\w+)\((?<args>[^)]*)\)$");
        if (ctor.Success)
        {
            var a = ctor.Groups["args"].Value.Split(',').Select(x => Number(x.Trim())).ToArray();
            return ctor.Groups["type"].Value switch
            {
                "Vector3" => new Vector3(a[0], a[1], a[2]),
                "Color" => new Vector4(a[0], a[1], a[2], a.Length > 3 ? a[3] : 1f), // HairNodeSettings keeps colours as Vector4
                var t => throw new InvalidOperationException($"unknown initializer type {t}"),
            };
        }
        if (init.StartsWith("BendModel.", StringComparison.Ordinal)) return Enum.Parse<BendModel>(init["BendModel.".Length..]);
        if (init is "true" or "false") return bool.Parse(init);
        if (init.EndsWith('f')) return Number(init);
        return int.Parse(init, CultureInfo.InvariantCulture);
    }

    private static float Number(string s) => float.Parse(s.TrimEnd('f'), CultureInfo.InvariantCulture);

    private static bool Same(object a, object b) => (a, b) switch
    {
        (float x, float y) => x == y,
        (int x, int y) => x == y,
        _ => a.Equals(b),
    };
}
