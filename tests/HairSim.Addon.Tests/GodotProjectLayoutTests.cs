using System.Text.RegularExpressions;

namespace HairSheet.Addon.Tests;

/// <summary>
/// The repository root is both a Godot project and the place where `dotnet test` runs. Godot's .NET editor
/// (modules/mono/editor/GodotTools: GodotSharpDirs.DetermineProjectLocation) looks for the project at
/// res://&lt;assembly_name&gt;.csproj, always next to project.godot, and for its solution in
/// project.godot's dotnet/project/solution_directory; MSBuild, given no file, takes the root's only solution when
/// the root holds one project and one solution of the same base name (MSB1011 otherwise). These tests read the
/// files both tools read, so a layout that breaks either fails here rather than in Godot or in CI.
/// </summary>
public class GodotProjectLayoutTests
{
    private static string Root()
    {
        for (var dir = new DirectoryInfo(AppContext.BaseDirectory); dir != null; dir = dir.Parent)
            if (File.Exists(Path.Combine(dir.FullName, "project.godot"))) return dir.FullName;
        throw new DirectoryNotFoundException("project.godot not found above the test directory.");
    }

    private static string ProjectSetting(string root, string section, string key)
    {
        string? current = null;
        foreach (string raw in File.ReadAllLines(Path.Combine(root, "project.godot")))
        {
            string line = raw.Trim();
            if (line.StartsWith('[')) { current = line.Trim('[', ']'); continue; }
            if (current != section || !line.StartsWith(key + "=", StringComparison.Ordinal)) continue;
            return line[(key.Length + 1)..].Trim('"');
        }
        return "";
    }

    private static readonly Regex SolutionProject = new(@"^Project\(""\{[0-9A-F-]+\}""\) = ""[^""]+"", ""(?<path>[^""]+\.\w+proj)""", RegexOptions.Multiline);

    /// <summary>Full paths of the projects a .sln lists (paths in a .sln are relative to it, with backslashes).</summary>
    private static HashSet<string> SolutionProjects(string sln) =>
        SolutionProject.Matches(File.ReadAllText(sln))
            .Select(m => Path.GetFullPath(Path.Combine(Path.GetDirectoryName(sln)!, m.Groups["path"].Value.Replace('\\', Path.DirectorySeparatorChar))))
            .ToHashSet();

    private static IEnumerable<string> RepositoryProjects(string root) =>
        Directory.EnumerateFiles(root, "*.csproj", SearchOption.AllDirectories)
            .Where(p => !Path.GetRelativePath(root, p).Split(Path.DirectorySeparatorChar)
                .Any(part => part is "bin" or "obj" or "node_modules" or ".godot" || part.StartsWith('.')));

    private static bool ReferencesTheHairSimPackage(string csproj) =>
        System.Xml.Linq.XDocument.Load(csproj).Descendants("PackageReference").Any(r => (string?)r.Attribute("Include") == "HairSim");

    [Fact]
    public void APlainDotnetTestAtTheRootBuildsTheTestSolution()
    {
        string root = Root();
        var projects = Directory.GetFiles(root, "*.*proj");
        var solutions = Directory.GetFiles(root, "*.sln").Concat(Directory.GetFiles(root, "*.slnx")).ToArray();
        // MSBuild's rule without a file argument: one project and one solution, with the same base name.
        Assert.Single(projects);
        Assert.Single(solutions);
        Assert.Equal(Path.GetFileNameWithoutExtension(projects[0]), Path.GetFileNameWithoutExtension(solutions[0]), ignoreCase: true);

        var listed = SolutionProjects(solutions[0]);
        // Without Godot's packages the Godot project cannot restore, so it must stay out of the test solution.
        Assert.DoesNotContain(Path.GetFullPath(projects[0]), listed);
        // Every other project (library, console, tests, benchmarks, sample) is built, and every test project run;
        // except a project that takes HairSim as a package (samples/HairSheet.PackageSample), which cannot restore
        // before the package is packed: HairSim.Tests' PackageTests packs it and builds that project against it.
        foreach (string project in RepositoryProjects(root).Where(p => Path.GetDirectoryName(p) != root && !ReferencesTheHairSimPackage(p)))
            Assert.True(listed.Contains(Path.GetFullPath(project)), $"{Path.GetRelativePath(root, project)} is not in {Path.GetFileName(solutions[0])}");
        Assert.Contains(listed, p => p.EndsWith("HairSim.Addon.Tests.csproj", StringComparison.Ordinal));
        Assert.Contains(listed, p => p.EndsWith("HairSim.Tests.csproj", StringComparison.Ordinal));
    }

    [Fact]
    public void GodotFindsItsProjectAndASolutionThatListsIt()
    {
        string root = Root();
        string assembly = ProjectSetting(root, "dotnet", "project/assembly_name");
        Assert.False(string.IsNullOrEmpty(assembly), "project.godot sets no dotnet/project/assembly_name");
        // GodotSharpDirs: the csproj is always res://<assembly_name>.csproj.
        string csproj = Path.Combine(root, assembly + ".csproj");
        Assert.True(File.Exists(csproj), $"{assembly}.csproj is not next to project.godot");

        // The solution: <solution_directory>/<assembly_name>.sln in older versions; current ones take the one .sln/.slnx
        // in that folder that lists the csproj. The root's solution of that name is the test solution, so Godot's must
        // be elsewhere, and both rules must lead to it.
        string solutionDir = ProjectSetting(root, "dotnet", "project/solution_directory");
        Assert.False(string.IsNullOrEmpty(solutionDir), "dotnet/project/solution_directory is empty: Godot would take the root's test solution");
        string dir = Path.GetFullPath(Path.Combine(root, solutionDir.Replace("res://", "")));
        string sln = Path.Combine(dir, assembly + ".sln");
        Assert.True(File.Exists(sln), $"{Path.GetRelativePath(root, sln)} does not exist: Godot's exporter would ship no C# assemblies");
        var inFolder = Directory.GetFiles(dir, "*.sln").Concat(Directory.GetFiles(dir, "*.slnx")).Where(s => SolutionProjects(s).Contains(csproj)).ToArray();
        Assert.Equal([sln], inFolder);
    }

    [Fact]
    public void TheGodotAssemblyCompilesNoOtherProjectsSources()
    {
        // Godot.NET.Sdk compiles every .cs under the csproj's folder; each other project's folder (sources and the
        // generated files in its obj/) must be removed, or the Godot build fails on duplicate assembly attributes.
        string root = Root();
        string assembly = ProjectSetting(root, "dotnet", "project/assembly_name");
        string text = File.ReadAllText(Path.Combine(root, assembly + ".csproj"));
        var removed = Regex.Matches(text, @"<Compile\s+Remove=""(?<globs>[^""]+)""")
            .SelectMany(m => m.Groups["globs"].Value.Split(';', StringSplitOptions.RemoveEmptyEntries))
            .Select(g => g.Trim().Replace('\\', '/'))
            .ToList();
        foreach (string project in RepositoryProjects(root).Where(p => Path.GetDirectoryName(p) != root))
        {
            string folder = Path.GetRelativePath(root, Path.GetDirectoryName(project)!).Replace('\\', '/');
            bool covered = removed.Any(g => g.EndsWith("/**", StringComparison.Ordinal) && (folder + "/").StartsWith(g[..^2], StringComparison.Ordinal));
            Assert.True(covered, $"{folder}/ (holding {Path.GetFileName(project)}) is not removed from {assembly}.csproj's Compile items");
        }
    }
}
