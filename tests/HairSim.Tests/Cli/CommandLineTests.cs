using System.CommandLine;
using HairSim.Cli;
using HairSim.IO;

namespace HairSim.Tests.Cli;

/// <summary>
/// The console's command line: every mistake is refused with exit code 2 and a message naming the option as typed (never
/// a .NET parameter), before any work starts; --name=value works; every command has --help with a description for every
/// option; files that cannot be used exit with 5; the exit codes are the ones README documents.
/// </summary>
public sealed class CommandLineTests : IDisposable
{
    private readonly string _dir = Path.Combine(Path.GetTempPath(), $"hairsim-cli-{Guid.NewGuid():N}");

    public CommandLineTests() => Directory.CreateDirectory(_dir);

    public void Dispose() => Directory.Delete(_dir, recursive: true);

    private static readonly string[] CommandNames = ["run", "style", "report", "stability", "leave-out", "bench", "render-bench", "studio"];

    /// <summary>Runs a command line; returns its exit code, what it printed on the output and on the error writer.</summary>
    private static (int Code, string Output, string Error) Run(params string[] args)
    {
        var output = new StringWriter();
        var error = new StringWriter();
        int code = CliApp.Run(args, output, error);
        return (code, output.ToString(), error.ToString());
    }

    /// <summary>A usage error: exit code 2, the message contains <paramref name="expected"/>, and no .NET names leak.</summary>
    private static string AssertUsageError(string expected, params string[] args)
    {
        var (code, _, error) = Run(args);
        Assert.True(code == ExitCodes.Usage, $"`{string.Join(' ', args)}` exited {code}, not 2: {error}");
        Assert.Contains(expected, error);
        foreach (var leak in new[] { "Parameter '", "System.", "Actual value", "   at " })
            Assert.DoesNotContain(leak, error);
        return error;
    }

    [Fact]
    public void EveryCommandOfReadmeAndCiExists()
    {
        var names = CliApp.Build().Subcommands.Select(c => c.Name).ToHashSet();
        Assert.Equal(CommandNames.Order(), names.Order());
    }

    [Fact]
    public void AMissingValueIsAnErrorNamingTheOption()
    {
        AssertUsageError("--seconds needs a value", "run", "--seconds");
        // Followed by another option: that option is not taken as the value.
        AssertUsageError("--out needs a value (found the option --quick", "report", "--out", "--quick");
        AssertUsageError("--seconds needs a value (found the option --shake", "run", "--seconds", "--shake");
        // The issue's case: `report --quick --out` must not go on and write over the default report.
        AssertUsageError("--out needs a value", "report", "--quick", "--out");
        AssertUsageError("--head needs a value", "run", "--head");
        AssertUsageError("--groom needs a value", "studio", "--groom");
        AssertUsageError("--seconds needs a value", "run", "--seconds=");
    }

    [Fact]
    public void UnknownOptionsAndCommandsAreRefusedWithASuggestion()
    {
        string e = AssertUsageError("unknown option --sceonds for run", "run", "--sceonds", "1");
        Assert.Contains("did you mean --seconds?", e);
        Assert.Contains("hairsim run --help", e);
        foreach (var command in CommandNames)
            AssertUsageError($"unknown option --no-such-option for {command}", command, "--no-such-option");
        AssertUsageError("unknown command 'runn' (did you mean run?)", "runn");
        // Options belong after their command.
        AssertUsageError("options come after the command: `hairsim run --seconds", "--seconds", "1");
        AssertUsageError("unexpected argument 'fast'", "run", "fast");
    }

    [Fact]
    public void ASwitchTakesNoValue()
    {
        AssertUsageError("--shake is a switch and takes no value (got '3')", "run", "--shake", "3");
        AssertUsageError("--quick is a switch and takes no value (got 'yes')", "report", "--quick=yes");
    }

    [Fact]
    public void MalformedValuesAndValuesOutOfRangeNameTheOptionAndTheRange()
    {
        AssertUsageError("--seconds expects a number, got 'abc'", "run", "--seconds", "abc");
        AssertUsageError("--hz expects a whole number, got '1.5'", "run", "--hz", "1.5");
        AssertUsageError("--seconds must be more than 0 and at most 3600 seconds, got 0", "run", "--seconds", "0");
        AssertUsageError("--particles must be in 2 … 4096, got 1", "run", "--particles", "1");
        AssertUsageError("--strands must be in 1 … 4096, got 0", "style", "--strands", "0");
        AssertUsageError("--path must be one of fast, reference; got 'slow'", "run", "--path", "slow");
        AssertUsageError("--bend must be one of rest, triples, limp; got 'stiff'", "run", "--bend", "stiff");
        AssertUsageError("--port must be in 0 … 65535, got 70000", "studio", "--port", "70000");
        AssertUsageError("--groom must be one of reference", "studio", "--groom", "huge");
        AssertUsageError("--scales expects strand counts in 40 … 400000", "bench", "--scales", "1000,x");
        AssertUsageError("--frames must be in 10 … 10000, got 5", "leave-out", "--frames", "5");
        AssertUsageError("--render-ms must be in 0 … 100 ms, got 200", "render-bench", "--render-ms", "200");
        AssertUsageError("--seconds is given more than once", "run", "--seconds", "1", "--seconds", "2");
        AssertUsageError("--sheets × --strands × --particles = ", "run", "--sheets", "100000", "--strands", "4096", "--particles", "4096");
    }

    [Fact]
    public void OptionsThatDoNotGoTogetherAreRefused()
    {
        AssertUsageError("--hairstyle and --head cannot be combined", "run", "--hairstyle", "a.hairstyle", "--head", "procedural");
        AssertUsageError("--sheets, --strands and --particles do not apply with --hairstyle", "run", "--hairstyle", "a.hairstyle", "--sheets", "3");
        AssertUsageError("--sdf-cell applies only with --head", "run", "--sdf-cell", "0.01");
        AssertUsageError("--sdf-cell applies only with --head", "style", "--sdf-cell", "0.01");
        AssertUsageError("--runs applies only with --bench", "style", "--runs", "3");
    }

    [Fact]
    public void NameEqualsValueIsAcceptedAndTheValuesAreUsed()
    {
        string output = Path.Combine(_dir, "export");
        var (code, _, error) = Run("run", "--seconds=0.05", "--sheets=10", "--strands=4", "--particles=8", "--export=" + output);
        Assert.True(code == 0, error);
        var scene = HairstyleFile.Load(Path.Combine(output, "hair.hairstyle"));
        Assert.Equal(10 * 4, scene.World.StrandCount);
        Assert.Equal(10 * 4 * 8, scene.World.ParticleCount);
    }

    [Fact]
    public void EveryValueTheParticlesRangeAllowsRuns()
    {
        // The message says 2 … 4096: both ends work (2 particles: one pinned, one free).
        foreach (var particles in new[] { "2", "3", "4096" })
        {
            string output = Path.Combine(_dir, "p" + particles);
            var (code, _, error) = Run("run", "--seconds", "0.04", "--sheets", "1", "--strands", "2", "--particles", particles, "--export", output);
            Assert.True(code == 0, $"--particles {particles}: exit {code}: {error}");
            Assert.Equal(2 * int.Parse(particles), HairstyleFile.Load(Path.Combine(output, "hair.hairstyle")).World.ParticleCount);
        }
    }

    [Fact]
    public void EveryCommandHasHelpWithADescriptionForEveryOption()
    {
        foreach (var command in CliApp.Build().Subcommands)
        {
            Assert.False(string.IsNullOrWhiteSpace(command.Description), command.Name);
            var (code, output, error) = Run(command.Name, "--help");
            Assert.True(code == 0, $"{command.Name} --help: exit {code}: {error}");
            Assert.Contains($"hairsim {command.Name} [options]", output);
            Assert.Contains("Exit codes:", output);
            foreach (var option in command.Options)
            {
                Assert.False(string.IsNullOrWhiteSpace(option.Description), $"{command.Name} {option.Name} has no description");
                Assert.Contains(option.Name, output);
                Assert.Contains(Words(option.Description!), Words(output));
            }
            Assert.Equal(0, Run(command.Name, "-h").Code);
        }
        // The options README, docs and CI use are all there.
        var run = CliApp.Build().Subcommands.Single(c => c.Name == "run");
        foreach (var name in new[] { "--seconds", "--hz", "--substeps", "--path", "--shake", "--paced", "--volume", "--bend", "--head", "--sdf-cell", "--hairstyle", "--export", "--sheets", "--strands", "--particles" })
            Assert.Contains(run.Options, o => o.Name == name);
        // Reports go into out/ unless --out says otherwise: a plain run never overwrites the repository's docs.
        foreach (var (command, file) in new[] { ("report", "out/error-vs-runtime.md"), ("stability", "out/stability.md"), ("leave-out", "out/leave-out.md") })
        {
            Assert.Contains(file, Run(command, "--help").Output);
            Assert.DoesNotContain("docs/", Run(command, "--help").Output);
        }
    }

    [Fact]
    public void TheProgramHelpListsTheCommandsAndEveryExitCode()
    {
        var (code, output, _) = Run("--help");
        Assert.Equal(0, code);
        foreach (var name in CommandNames) Assert.Contains(name, output);
        foreach (var (c, meaning) in ExitCodes.Table) Assert.Contains($"  {c}  {meaning}", output);
        Assert.Contains("With no command, runs the main job", output);
    }

    [Fact]
    public void ReadmeDocumentsTheExitCodesTheProgramUses()
    {
        string readme = File.ReadAllText(Path.Combine(RepositoryRoot(), "README.md"));
        foreach (var (c, meaning) in ExitCodes.Table) Assert.Contains($"| {c} | {meaning} |", readme);
        Assert.Equal(Enumerable.Range(0, 6), ExitCodes.Table.Select(t => t.Code));
    }

    [Fact]
    public void OutputsThatCannotBeWrittenExitWithFiveBeforeAnyWork()
    {
        // A folder under a regular file can never be created, whoever runs the test (root ignores read-only bits).
        string file = Path.Combine(_dir, "a-file");
        File.WriteAllText(file, "");
        foreach (var args in new[]
        {
            new[] { "report", "--quick", "--out", Path.Combine(file, "report.md") },
            ["stability", "--quick", "--out", Path.Combine(file, "stability.md")],
            ["leave-out", "--out", Path.Combine(file, "leave-out.md")],
            ["bench", "--out", Path.Combine(file, "performance.md")],
            ["style", "--out", Path.Combine(file, "pictures")],
            ["run", "--seconds", "1", "--export", Path.Combine(file, "export")],
        })
        {
            var (code, _, error) = Run(args);
            Assert.True(code == ExitCodes.FileError, $"`{string.Join(' ', args)}` exited {code}: {error}");
            Assert.Contains($"{(args[0] == "run" ? "--export" : "--out")}: cannot write to", error);
        }
    }

    [Fact]
    public void InputFilesThatCannotBeReadExitWithFive()
    {
        var (code, _, error) = Run("run", "--hairstyle", Path.Combine(_dir, "none.hairstyle"), "--seconds", "0.1");
        Assert.Equal(ExitCodes.FileError, code);
        Assert.Contains("No hairstyle file at", error);
        string corrupt = Path.Combine(_dir, "bad.hairstyle");
        File.WriteAllText(corrupt, "not a hairstyle");
        (code, _, error) = Run("run", "--hairstyle", corrupt, "--seconds", "0.1");
        Assert.Equal(ExitCodes.FileError, code);
        Assert.Contains("Not a hairstyle file", error);
        (code, _, error) = Run("run", "--head", Path.Combine(_dir, "head.stl"), "--seconds", "0.1");
        Assert.Equal(ExitCodes.FileError, code);
        Assert.DoesNotContain("   at ", error);
    }

    [Fact]
    public void AStyleGroomWithNoFringeNamesTheGroomOptions()
    {
        AssertUsageError("use more --sheets or --strands", "style", "--sheets", "1", "--strands", "1", "--settle", "0", "--after", "0", "--out", Path.Combine(_dir, "style"));
    }

    [Fact]
    public void ExceptionsMapToOneExitCodePerKindOfFailure()
    {
        var error = new StringWriter();
        Assert.Equal(ExitCodes.Usage, CliApp.Fail(new UsageException("--a and --b"), error));
        Assert.Equal(ExitCodes.FileError, CliApp.Fail(new FileNotFoundException("no file"), error));
        Assert.Equal(ExitCodes.FileError, CliApp.Fail(new UnauthorizedAccessException("read-only"), error));
        Assert.Equal(ExitCodes.FileError, CliApp.Fail(new InvalidDataException("corrupt"), error));
        Assert.DoesNotContain("   at ", error.ToString());
        // Anything else is a bug: exit 1 with the stack trace, never an unhandled crash (134).
        Exception bug;
        try { throw new InvalidOperationException("a bug"); } catch (Exception e) { bug = e; }
        Assert.Equal(ExitCodes.InternalError, CliApp.Fail(bug, error));
        Assert.Contains("internal error", error.ToString());
        Assert.Contains("   at ", error.ToString());
    }

    [Fact]
    public void TheMainJobLeavesTheFirstFrameOutOfItsFiguresAndComparesWithTheBudget()
    {
        var lines = RunCommand.FrameTimeLines([100, 10, 12, 20], 60, 1000);
        Assert.Contains("first frame: 100.00 ms", lines[0]);
        Assert.Contains("over 3 frames: mean 14.00 ms, median 12.00 ms", lines[1]);
        Assert.Contains("budget of a 60 Hz frame: 16.7 ms", lines[2]);
        Assert.Contains("1 of 3 frames over it", lines[2]);
        Assert.DoesNotContain("not run in real time", lines[2]);
        var slow = RunCommand.FrameTimeLines([100, 40, 40], 60, 1000);
        Assert.Contains("the mean is over", slow[2]);
        // One frame only: it is the figure (nothing to leave out).
        Assert.Contains("over 1 frame: mean 7.00 ms", RunCommand.FrameTimeLines([7], 30, 1000)[0]);
        Assert.Contains("budget of a 30 Hz frame: 33.3 ms", RunCommand.FrameTimeLines([7], 30, 1000)[1]);
    }

    private static string Words(string text) => System.Text.RegularExpressions.Regex.Replace(text, @"\s+", " ");

    private static string RepositoryRoot()
    {
        for (var dir = new DirectoryInfo(AppContext.BaseDirectory); dir != null; dir = dir.Parent)
            if (File.Exists(Path.Combine(dir.FullName, "README.md")) && Directory.Exists(Path.Combine(dir.FullName, "src"))) return dir.FullName;
        throw new DirectoryNotFoundException("The repository root is not above the test directory.");
    }
}
