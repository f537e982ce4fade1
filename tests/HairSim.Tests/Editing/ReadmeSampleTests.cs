using HairSim;

namespace HairSim.Tests.Editing;

/// <summary>
/// README's library example is samples/HairSheet.Sample/Program.cs, verbatim (so it is compiled with the solution),
/// and it runs: on a smaller groom here, writing into a temporary folder.
/// </summary>
public class ReadmeSampleTests
{
    private static string Root()
    {
        for (var dir = new DirectoryInfo(AppContext.BaseDirectory); dir != null; dir = dir.Parent)
            if (File.Exists(Path.Combine(dir.FullName, "README.md")) && Directory.Exists(Path.Combine(dir.FullName, "samples"))) return dir.FullName;
        throw new DirectoryNotFoundException("The repository root (README.md, samples/) is not above the test directory.");
    }

    [Fact]
    public void TheReadmeExampleIsTheSampleFile()
    {
        string root = Root();
        string readme = File.ReadAllText(Path.Combine(root, "README.md")).Replace("\r\n", "\n");
        string sample = File.ReadAllText(Path.Combine(root, "samples", "HairSheet.Sample", "Program.cs")).Replace("\r\n", "\n");
        int begin = readme.IndexOf("<!-- sample:begin -->\n```csharp\n", StringComparison.Ordinal);
        int end = readme.IndexOf("```\n<!-- sample:end -->", StringComparison.Ordinal);
        Assert.True(begin >= 0 && end > begin, "README has no sample block");
        string block = readme[(begin + "<!-- sample:begin -->\n```csharp\n".Length)..end];
        Assert.Equal(sample, block);
    }

    [Fact]
    public void TheSampleRunsCutsFitsAndSaves()
    {
        string dir = Path.Combine(Path.GetTempPath(), "hairsheet-sample-" + Guid.NewGuid().ToString("N"));
        var log = new StringWriter();
        try
        {
            int code = HairSheetSample.Run(log, new GroomSettings { SheetCount = 60, StrandsPerSheet = 6, ParticlesPerStrand = 12 }, dir);
            Assert.Equal(0, code);
            Assert.Matches(@"cut [1-9]\d* strands, fitted [1-9]\d* fringe strands", log.ToString());
            var saved = HairSim.IO.HairstyleFile.Load(Path.Combine(dir, "style.hairstyle"));
            Assert.Equal(0, saved.World.CountNonFinite());
            Assert.True(new FileInfo(Path.Combine(dir, "style.hair")).Length > 128);
        }
        finally { if (Directory.Exists(dir)) Directory.Delete(dir, recursive: true); }
    }
}
