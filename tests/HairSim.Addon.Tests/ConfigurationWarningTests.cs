using System.Text.RegularExpressions;

namespace HairSheet.Addon.Tests;

/// <summary>
/// Godot asks a tool script for its configuration warnings only to show them in the editor's Scene dock, so a warning
/// that tests Engine.IsEditorHint() either never shows (`!IsEditorHint()`) or shows on every node. The node classes
/// cannot be compiled here (no Godot packages), so their source is read.
/// </summary>
public class ConfigurationWarningTests
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

    /// <summary>The body of the first method named <paramref name="name"/>, by brace matching.</summary>
    private static string? MethodBody(string text, string name)
    {
        var m = Regex.Match(text, @"\b" + Regex.Escape(name) + @"\s*\([^)]*\)\s*\{");
        if (!m.Success) return null;
        int depth = 0;
        for (int i = m.Index + m.Length - 1; i < text.Length; i++)
        {
            if (text[i] == '{') depth++;
            else if (text[i] == '}' && --depth == 0) return text[(m.Index + m.Length)..i];
        }
        throw new InvalidDataException($"{name}: unbalanced braces");
    }

    [Fact]
    public void NoConfigurationWarningDependsOnRunningInTheEditor()
    {
        int checkedMethods = 0;
        foreach (var file in Directory.EnumerateFiles(AddonDir(), "*.cs", SearchOption.AllDirectories))
        {
            string? body = MethodBody(File.ReadAllText(file), "_GetConfigurationWarnings");
            if (body == null) continue;
            checkedMethods++;
            Assert.False(body.Contains("IsEditorHint", StringComparison.Ordinal),
                $"{Path.GetFileName(file)}: _GetConfigurationWarnings tests IsEditorHint, but Godot only asks for warnings in the editor");
        }
        Assert.True(checkedMethods >= 1, "no _GetConfigurationWarnings found: is the pattern still right?");
    }
}
