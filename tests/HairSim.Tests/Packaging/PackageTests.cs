using System.Diagnostics;
using System.IO.Compression;
using System.Reflection.Metadata;
using System.Reflection.PortableExecutable;
using System.Text.RegularExpressions;
using System.Xml.Linq;

namespace HairSim.Tests.Packaging;

/// <summary>
/// HairSim as a NuGet package (issue 15): <c>dotnet pack src/HairSim -c Release</c>, run here into a temporary folder
/// (its bin/ and obj/ there too, so nothing is written into the source tree), gives a package with the library, its
/// XML documentation, the package README and the metadata, a symbol package with a deterministic, path-mapped PDB,
/// and no measurement code; samples/HairSheet.PackageSample builds against it and runs.
/// </summary>
public sealed class PackageFixture : IDisposable
{
    public string Root { get; } = RepositoryRoot();
    public string Temp { get; } = Path.Combine(Path.GetTempPath(), "hairsim-pack-" + Guid.NewGuid().ToString("N"));
    public string Feed => Path.Combine(Temp, "feed");
    /// <summary>The version the pack gave the package (from git tags, MinVer), known after <see cref="Pack"/>.</summary>
    public string Version { get; private set; } = "";
    private readonly Lazy<(int Code, string Log)> _pack;

    public PackageFixture()
    {
        _pack = new Lazy<(int, string)>(() => Dotnet(Root,
            "pack", Path.Combine("src", "HairSim", "HairSim.csproj"), "-c", "Release", "-o", Feed,
            $"-p:BaseOutputPath={Path.Combine(Temp, "bin")}/", $"-p:BaseIntermediateOutputPath={Path.Combine(Temp, "obj")}/"));
    }

    /// <summary>Packs once for the class; fails with dotnet's output if the pack failed.</summary>
    public void Pack()
    {
        var (code, log) = _pack.Value;
        Assert.True(code == 0, "dotnet pack src/HairSim failed:\n" + log);
        Version = PackedVersion(Feed);
    }

    /// <summary>The version of the one HairSim package in a folder (HairSim.{version}.nupkg).</summary>
    public static string PackedVersion(string folder)
    {
        var packages = Directory.GetFiles(folder, "HairSim.*.nupkg");
        Assert.True(packages.Length == 1, "expected one HairSim package in " + folder + ": " + string.Join(", ", packages.Select(Path.GetFileName)));
        return Path.GetFileName(packages[0])["HairSim.".Length..^".nupkg".Length];
    }

    /// <summary>Runs the dotnet CLI as a user would (CI=true: a CI build), without the test host's MSBuild variables.</summary>
    public (int Code, string Log) Dotnet(string workingDirectory, params string[] args)
    {
        var psi = new ProcessStartInfo(Environment.GetEnvironmentVariable("DOTNET_HOST_PATH") is { Length: > 0 } host && File.Exists(host) ? host : "dotnet")
        {
            WorkingDirectory = workingDirectory,
            RedirectStandardOutput = true,
            RedirectStandardError = true,
            UseShellExecute = false,
        };
        foreach (var a in args) psi.ArgumentList.Add(a);
        psi.ArgumentList.Add("-nologo");
        foreach (var key in psi.Environment.Keys.Where(k => k.StartsWith("MSBuild", StringComparison.OrdinalIgnoreCase) || k.StartsWith("VSTEST", StringComparison.OrdinalIgnoreCase)).ToList())
            psi.Environment.Remove(key);
        psi.Environment["CI"] = "true";
        psi.Environment["DOTNET_CLI_TELEMETRY_OPTOUT"] = "1";
        psi.Environment["DOTNET_NOLOGO"] = "1";
        using var p = Process.Start(psi)!;
        var stdout = p.StandardOutput.ReadToEndAsync();
        var stderr = p.StandardError.ReadToEndAsync();
        if (!p.WaitForExit(TimeSpan.FromMinutes(10))) { p.Kill(entireProcessTree: true); return (-1, "dotnet " + string.Join(' ', args) + ": no exit after 10 minutes"); }
        return (p.ExitCode, stdout.Result + stderr.Result);
    }

    /// <summary>Runs git; (exit code, standard output).</summary>
    public (int Code, string Output) Git(string workingDirectory, params string[] args)
    {
        var psi = new ProcessStartInfo("git") { WorkingDirectory = workingDirectory, RedirectStandardOutput = true, RedirectStandardError = true, UseShellExecute = false };
        foreach (var a in args) psi.ArgumentList.Add(a);
        using var p = Process.Start(psi)!;
        var stdout = p.StandardOutput.ReadToEndAsync();
        _ = p.StandardError.ReadToEndAsync();
        p.WaitForExit();
        return (p.ExitCode, stdout.Result);
    }

    public static string RepositoryRoot()
    {
        for (var dir = new DirectoryInfo(AppContext.BaseDirectory); dir != null; dir = dir.Parent)
            if (File.Exists(Path.Combine(dir.FullName, "README.md")) && File.Exists(Path.Combine(dir.FullName, "src", "HairSim", "HairSim.csproj"))) return dir.FullName;
        throw new DirectoryNotFoundException("The repository root (README.md, src/HairSim) is not above the test directory.");
    }

    public void Dispose()
    {
        try { Directory.Delete(Temp, recursive: true); } catch (IOException) { } catch (UnauthorizedAccessException) { }
    }
}

public class PackageTests(PackageFixture fixture) : IClassFixture<PackageFixture>
{
    private static readonly XNamespace Nuspec = "http://schemas.microsoft.com/packaging/2012/06/nuspec.xsd";

    [Fact]
    public void ThePackageHoldsTheLibraryItsDocumentationReadmeAndMetadata()
    {
        fixture.Pack();
        string nupkg = Path.Combine(fixture.Feed, $"HairSim.{fixture.Version}.nupkg");
        Assert.True(File.Exists(nupkg), $"no {Path.GetFileName(nupkg)} in the pack output: " + string.Join(", ", Directory.GetFiles(fixture.Feed).Select(Path.GetFileName)));
        using var zip = ZipFile.OpenRead(nupkg);
        var names = zip.Entries.Select(e => e.FullName).ToHashSet();
        Assert.Contains("lib/net8.0/HairSim.dll", names);
        Assert.Contains("lib/net8.0/HairSim.xml", names);
        Assert.Contains("PACKAGE.md", names);
        Assert.DoesNotContain(names, n => n.EndsWith(".pdb", StringComparison.Ordinal));   // symbols go to the .snupkg
        Assert.DoesNotContain(names, n => n.Contains("Measurement", StringComparison.OrdinalIgnoreCase));

        var meta = XDocument.Load(zip.GetEntry("HairSim.nuspec")!.Open()).Root!.Element(Nuspec + "metadata")!;
        Assert.Equal("HairSim", meta.Element(Nuspec + "id")!.Value);
        Assert.Equal(fixture.Version, meta.Element(Nuspec + "version")!.Value);
        var license = meta.Element(Nuspec + "license")!;
        Assert.Equal(("expression", "MIT"), ((string?)license.Attribute("type"), license.Value));
        Assert.Equal("PACKAGE.md", meta.Element(Nuspec + "readme")!.Value);
        Assert.Contains("strand hair", meta.Element(Nuspec + "description")!.Value);
        var repository = meta.Element(Nuspec + "repository")!;
        Assert.Equal("git", (string?)repository.Attribute("type"));
        if (Directory.Exists(Path.Combine(fixture.Root, ".git")) || File.Exists(Path.Combine(fixture.Root, ".git")))
            Assert.Matches("^[0-9a-f]{40}$", (string?)repository.Attribute("commit") ?? "");
        // No package dependencies: a game takes HairSim alone (SharpGLTF comes only with HairSim.Meshes).
        Assert.Empty(meta.Element(Nuspec + "dependencies")?.Descendants(Nuspec + "dependency") ?? []);

        // The README in the package is the repository's PACKAGE.md; the XML documentation documents the public API.
        using (var readme = new StreamReader(zip.GetEntry("PACKAGE.md")!.Open()))
            Assert.Equal(File.ReadAllText(Path.Combine(fixture.Root, "src", "HairSim", "PACKAGE.md")), readme.ReadToEnd());
        var doc = XDocument.Load(zip.GetEntry("lib/net8.0/HairSim.xml")!.Open());
        var members = doc.Descendants("member").Select(m => (string?)m.Attribute("name")).ToHashSet();
        Assert.Contains("T:HairSim.GroomSettings", members);
        Assert.Contains("T:HairSim.WorldMetrics", members);

        // The runtime assembly only: no measurement types, and a deterministic build (Reproducible debug entry).
        var dll = new MemoryStream();
        using (var s = zip.GetEntry("lib/net8.0/HairSim.dll")!.Open()) s.CopyTo(dll);
        dll.Position = 0;
        using var pe = new PEReader(dll);
        var md = pe.GetMetadataReader();
        var types = md.TypeDefinitions.Select(h => md.GetTypeDefinition(h)).Select(t => (Ns: md.GetString(t.Namespace), Name: md.GetString(t.Name))).ToList();
        Assert.Contains(("HairSim", "HairSimulation"), types);
        Assert.DoesNotContain(types, t => t.Ns.StartsWith("HairSim.Measurement", StringComparison.Ordinal) || t.Name == "SvgExport");
        Assert.Contains(pe.ReadDebugDirectory(), e => e.Type == DebugDirectoryEntryType.Reproducible);
    }

    [Fact]
    public void TheSymbolPackageHoldsAPathMappedPdbOfTheSameBuild()
    {
        fixture.Pack();
        string snupkg = Path.Combine(fixture.Feed, $"HairSim.{fixture.Version}.snupkg");
        Assert.True(File.Exists(snupkg), $"no {Path.GetFileName(snupkg)} in the pack output");
        using var zip = ZipFile.OpenRead(snupkg);
        var entry = zip.GetEntry("lib/net8.0/HairSim.pdb");
        Assert.NotNull(entry);
        var pdb = new MemoryStream();
        using (var s = entry.Open()) s.CopyTo(pdb);
        pdb.Position = 0;
        using var provider = MetadataReaderProvider.FromPortablePdbStream(pdb);
        var reader = provider.GetMetadataReader();
        var documents = reader.Documents.Select(h => reader.GetString(reader.GetDocument(h).Name)).ToList();
        Assert.Contains(documents, d => d.EndsWith("HairSimulation.cs", StringComparison.Ordinal));
        // ContinuousIntegrationBuild (CI=true): the repository's source paths are mapped to /_/, so the PDB does not
        // depend on the folder the package was built in (the files the SDK generates into this test's obj/, outside
        // the repository, keep their paths).
        Assert.All(documents.Where(d => !d.StartsWith(fixture.Temp, StringComparison.Ordinal)), d => Assert.StartsWith("/_/", d));
        Assert.Contains(documents, d => d == "/_/src/HairSim/HairSimulation.cs");
        Assert.DoesNotContain(documents, d => d.Contains("Measurement", StringComparison.Ordinal));
    }

    [Fact]
    public void TheSampleGameProjectBuildsAndRunsAgainstThePackage()
    {
        fixture.Pack();
        // A copy of samples/HairSheet.PackageSample (its bin/obj in the temporary folder), restored into its own
        // packages folder, so no HairSim cached from an earlier pack of the same version is used.
        string sample = Path.Combine(fixture.Temp, "game");
        Directory.CreateDirectory(sample);
        foreach (var f in new[] { "HairSheet.PackageSample.csproj", "Program.cs" })
            File.Copy(Path.Combine(fixture.Root, "samples", "HairSheet.PackageSample", f), Path.Combine(sample, f));
        // The fresh package's folder is the only source: nothing is looked up on the network.
        File.WriteAllText(Path.Combine(sample, "nuget.config"), $"""
            <?xml version="1.0" encoding="utf-8"?>
            <configuration>
              <packageSources>
                <clear />
                <add key="hairsim-test" value="{fixture.Feed}" />
              </packageSources>
            </configuration>
            """);
        var (code, log) = fixture.Dotnet(sample, "run", "-c", "Release",
            $"-p:RestoreAdditionalProjectSources={fixture.Feed}", $"-p:RestorePackagesPath={Path.Combine(fixture.Temp, "packages")}");
        Assert.True(code == 0, "the package sample failed:\n" + log);
        // Lengths held to float precision (the ratio prints as 1.0000… or 0.9999…), nothing non-finite.
        var metrics = System.Text.RegularExpressions.Regex.Match(log, @"WorldMetrics \{ LengthRatio = ([0-9.Ee+-]+), .*NonFinite = 0 \}");
        Assert.True(metrics.Success, "the sample printed no finite world metrics:\n" + log);
        Assert.InRange(double.Parse(metrics.Groups[1].Value, System.Globalization.CultureInfo.InvariantCulture), 1 - 1e-5, 1 + 1e-5);
        Assert.True(Directory.Exists(Path.Combine(fixture.Temp, "packages", "hairsim", fixture.Version)), "the sample did not restore HairSim " + fixture.Version + " from the package");
    }

    [Fact]
    public void ThePackageReadmeExampleIsThePackageSample()
    {
        string root = PackageFixture.RepositoryRoot();
        string readme = File.ReadAllText(Path.Combine(root, "src", "HairSim", "PACKAGE.md")).Replace("\r\n", "\n");
        string program = File.ReadAllText(Path.Combine(root, "samples", "HairSheet.PackageSample", "Program.cs")).Replace("\r\n", "\n");
        var block = Regex.Match(readme, "```csharp\n(.*?)```\n", RegexOptions.Singleline);
        Assert.True(block.Success, "PACKAGE.md has no C# example");
        Assert.EndsWith(block.Groups[1].Value, program);
    }

    [Fact]
    public void ThePackageVersionComesFromGitTags()
    {
        fixture.Pack();
        // Untagged (this repository has no release tag yet) or past a tag: a prerelease of the next version with the
        // commit height, e.g. 0.1.0-alpha.0.164; on a tagged commit: the tag.
        if (!Directory.Exists(Path.Combine(fixture.Root, ".git")) && !File.Exists(Path.Combine(fixture.Root, ".git"))) return;
        var (code, described) = fixture.Git(fixture.Root, "describe", "--tags", "--exact-match", "--match", "v[0-9]*");
        if (code == 0) Assert.Equal(described.Trim()[1..], fixture.Version);
        else Assert.Matches(@"^\d+\.\d+\.\d+-alpha\.0\.\d+$", fixture.Version);
        // A tag on a clone of this commit is the package's version.
        string clone = Path.Combine(fixture.Temp, "tagged");
        Assert.Equal(0, fixture.Git(fixture.Temp, "clone", "--quiet", "--local", "--no-hardlinks", fixture.Root, clone).Code);
        Assert.Equal(0, fixture.Git(clone, "-c", "user.name=test", "-c", "user.email=test@example.com", "tag", "-a", "v9.8.7", "-m", "test release").Code);
        string feed = Path.Combine(fixture.Temp, "tagged-feed");
        var (packed, log) = fixture.Dotnet(clone, "pack", Path.Combine("src", "HairSim", "HairSim.csproj"), "-c", "Release", "-o", feed);
        Assert.True(packed == 0, "pack of the tagged clone failed:\n" + log);
        Assert.Equal("9.8.7", PackageFixture.PackedVersion(feed));
    }

    [Fact]
    public void TheReadmeShowsThePackageSampleProjectAndItsVersionIsTheLibrarys()
    {
        string root = PackageFixture.RepositoryRoot();
        string readme = File.ReadAllText(Path.Combine(root, "README.md")).Replace("\r\n", "\n");
        string csproj = File.ReadAllText(Path.Combine(root, "samples", "HairSheet.PackageSample", "HairSheet.PackageSample.csproj")).Replace("\r\n", "\n");
        var block = Regex.Match(readme, "<!-- package-sample:begin -->\n```xml\n(.*?)```\n<!-- package-sample:end -->", RegexOptions.Singleline);
        Assert.True(block.Success, "README has no package-sample block");
        Assert.Equal(csproj, block.Groups[1].Value);
        // The version is git's (a prerelease between tags), so the sample takes the newest of the library's major version,
        // prereleases included; a game names the release it tested instead.
        string fallback = XDocument.Load(Path.Combine(root, "src", "HairSim", "HairSim.csproj")).Descendants("Version").Single().Value;
        var reference = XDocument.Parse(csproj).Descendants("PackageReference").Single(r => (string?)r.Attribute("Include") == "HairSim");
        Assert.Equal(fallback.Split('.')[0] + ".*-*", (string?)reference.Attribute("Version"));
    }

    [Fact]
    public void TheRuntimeAssemblyHoldsNoMeasurementCode()
    {
        // What a game does not run lives in HairSim.Measurement (canonical cases, stability map, error report, SVG).
        var runtime = typeof(HairWorld).Assembly.GetTypes();
        Assert.DoesNotContain(runtime, t => t.Namespace?.StartsWith("HairSim.Measurement", StringComparison.Ordinal) == true || t.Name == "SvgExport");
        Assert.Equal("HairSim.Measurement", typeof(HairSim.Measurement.CanonicalCases).Assembly.GetName().Name);
        Assert.Equal("HairSim.Measurement", typeof(HairSim.IO.SvgExport).Assembly.GetName().Name);
        Assert.DoesNotContain(typeof(HairWorld).Assembly.GetReferencedAssemblies(), a => a.Name == "HairSim.Measurement");
    }
}
