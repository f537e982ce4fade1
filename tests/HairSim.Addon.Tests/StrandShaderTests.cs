using System.Text.RegularExpressions;

namespace HairSheet.Addon.Tests;

/// <summary>
/// The strand shader's light() against Godot's lighting convention: LIGHT_COLOR is colour × energy × PI (Godot's
/// spatial shader reference), so every term built from it divides by PI, as Godot's own Lambert example does;
/// otherwise hair is ≈ 3.14× too bright next to Godot's materials.
/// </summary>
public class StrandShaderTests
{
    private static string ShaderText()
    {
        for (var dir = new DirectoryInfo(AppContext.BaseDirectory); dir != null; dir = dir.Parent)
        {
            string path = Path.Combine(dir.FullName, "addons", "hairsheet", "shaders", "hair_strand.gdshader");
            if (File.Exists(path)) return File.ReadAllText(path);
        }
        throw new FileNotFoundException("addons/hairsheet/shaders/hair_strand.gdshader not found above the test directory.");
    }

    [Fact]
    public void EveryLightTermDividesGodotsPiOut()
    {
        string text = ShaderText();
        var statements = Regex.Matches(text, @"(DIFFUSE_LIGHT|SPECULAR_LIGHT)\s*\+=[^;]*;").Select(m => m.Value).ToList();
        Assert.Equal(2, statements.Count);
        foreach (var s in statements)
        {
            Assert.Contains("LIGHT_COLOR", s);
            Assert.Matches(@"/\s*PI\s*;$", s.Trim());
        }
    }
}
