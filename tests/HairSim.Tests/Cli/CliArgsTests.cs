using HairSim.Cli;

namespace HairSim.Tests.Cli;

/// <summary>
/// The console's option parsing: every mistake is an ArgumentException naming the option (the console prints it
/// and exits with 1) instead of being ignored, and outputs are checked before any work starts.
/// </summary>
public class CliArgsTests
{
    [Fact]
    public void AnOptionWithoutItsValueIsAnError()
    {
        var a = new CliArgs(["--seconds"]);
        var e = Assert.Throws<ArgumentException>(() => a.Double("seconds", 10));
        Assert.Contains("--seconds needs a value", e.Message);
        // Followed by another option, too.
        Assert.Throws<ArgumentException>(() => new CliArgs(["--out", "--quick"]).String("out"));
    }

    [Fact]
    public void ASwitchGivenAValueIsAnError()
    {
        var e = Assert.Throws<ArgumentException>(() => new CliArgs(["--shake", "3"]).Flag("shake"));
        Assert.Contains("--shake", e.Message);
        Assert.True(new CliArgs(["--shake"]).Flag("shake"));
    }

    [Fact]
    public void NameEqualsValueIsAccepted()
    {
        var a = new CliArgs(["--seconds=1.5", "--hz", "30"]);
        Assert.Equal(1.5, a.Double("seconds", 10));
        Assert.Equal(30, a.Int("hz", 60));
        a.RejectUnknown();
    }

    [Fact]
    public void HelpIsRecognisedAndNotAnUnknownOption()
    {
        var a = new CliArgs(["--help"]);
        Assert.True(a.HelpRequested);
        a.RejectUnknown();
        Assert.True(new CliArgs(["-h"]).HelpRequested);
        Assert.Throws<ArgumentException>(() => new CliArgs(["--sceonds", "1"]).RejectUnknown());
    }

    [Fact]
    public void AnOutputThatCannotBeWrittenIsRefusedBeforeAnyWork()
    {
        // A folder under a regular file can never be created, whoever runs the test (root ignores read-only bits).
        string file = Path.GetTempFileName();
        try
        {
            var e = Assert.Throws<ArgumentException>(() => new CliArgs(["--out", Path.Combine(file, "report.md")]).OutputFile("out", "x.md"));
            Assert.Contains("--out", e.Message);
            Assert.Throws<ArgumentException>(() => new CliArgs(["--out", Path.Combine(file, "pictures")]).OutputFolder("out", "out"));
            // A writable place passes and leaves nothing behind.
            string dir = Path.Combine(Path.GetTempPath(), "hairsim-cli-" + Guid.NewGuid().ToString("N"));
            Assert.Equal(Path.Combine(dir, "r.md"), new CliArgs(["--out", Path.Combine(dir, "r.md")]).OutputFile("out", "x.md"));
            Assert.Empty(Directory.GetFiles(dir));
            Directory.Delete(dir);
        }
        finally { File.Delete(file); }
    }
}
