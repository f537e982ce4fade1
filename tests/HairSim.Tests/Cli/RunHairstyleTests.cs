using HairSim.Cli;
using HairSim.IO;
using Xunit;

namespace HairSim.Tests.Cli;

/// <summary>`run --hairstyle` simulates a saved haircut and `--export` writes it out with pictures.</summary>
public sealed class RunHairstyleTests : IDisposable
{
    private readonly string _dir = Path.Combine(Path.GetTempPath(), $"hairsim-run-{Guid.NewGuid():N}");

    public RunHairstyleTests() => Directory.CreateDirectory(_dir);

    public void Dispose() => Directory.Delete(_dir, recursive: true);

    [Fact]
    public void RunsASavedHaircutAndExportsItWithPictures()
    {
        var scene = GroomBuilder.BuildScene(new GroomSettings { SheetCount = 12, StrandsPerSheet = 4, ParticlesPerStrand = 8 });
        string style = Path.Combine(_dir, "in.hairstyle");
        HairstyleFile.Save(scene, style);
        string output = Path.Combine(_dir, "out");
        int code = CliApp.Run(["run", "--hairstyle", style, "--seconds", "0.25", "--export", output]);
        Assert.Equal(0, code);
        foreach (var f in new[] { "hair.hair", "hair.obj", "hair.usda", "hair.hairstyle", "front.svg", "side.svg" })
            Assert.True(new FileInfo(Path.Combine(output, f)).Length > 100, $"{f} missing or empty");
        var back = HairstyleFile.Load(Path.Combine(output, "hair.hairstyle"));
        Assert.Equal(scene.World.StrandCount, back.World.StrandCount);
        Assert.Equal(scene.World.TotalRestLength(), back.World.TotalRestLength(), 6);
    }

    [Fact]
    public void RefusesAMissingOrCorruptFileAndCombiningWithAHeadMesh()
    {
        var error = new StringWriter();
        Assert.Equal(ExitCodes.FileError, CliApp.Run(["run", "--hairstyle", Path.Combine(_dir, "none.hairstyle"), "--seconds", "0.1"], TextWriter.Null, error));
        string corrupt = Path.Combine(_dir, "bad.hairstyle");
        File.WriteAllText(corrupt, "not a hairstyle");
        Assert.Equal(ExitCodes.FileError, CliApp.Run(["run", "--hairstyle", corrupt, "--seconds", "0.1"], TextWriter.Null, error));
        Assert.Equal(ExitCodes.Usage, CliApp.Run(["run", "--hairstyle", corrupt, "--head", "procedural"], TextWriter.Null, error));
        Assert.Contains("--hairstyle and --head cannot be combined", error.ToString());
    }
}
