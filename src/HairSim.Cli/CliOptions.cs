using System.CommandLine;
using System.CommandLine.Parsing;
using System.Globalization;

namespace HairSim.Cli;

/// <summary>
/// Typed options with the console's rules: every option has a description (shown by --help, with its default), a value
/// is required where one is expected (the next option is never taken as one), numbers are read in the invariant culture
/// and checked against their range, and every message names the option as typed (--particles), never a .NET parameter.
/// </summary>
public static class CliOptions
{
    private static readonly CultureInfo Inv = CultureInfo.InvariantCulture;

    /// <summary>An integer option in <paramref name="min"/> … <paramref name="max"/>.</summary>
    public static Option<int> Int(string name, string description, int fallback, int min, int max, string? valueName = null) =>
        Int(name, description, () => fallback, min, max, valueName);

    /// <summary>An integer option whose default is computed (the machine's core count, say).</summary>
    public static Option<int> Int(string name, string description, Func<int> fallback, int min, int max, string? valueName = null) =>
        new(name)
        {
            Description = description,
            HelpName = valueName ?? "n",
            DefaultValueFactory = _ => fallback(),
            CustomParser = r =>
            {
                if (Value(r, name) is not { } s) return default;
                if (!int.TryParse(s, NumberStyles.Integer, Inv, out int v)) { r.AddError($"{name} expects a whole number, got '{s}'"); return default; }
                if (v < min || v > max) r.AddError($"{name} must be in {min} … {max}, got {v}");
                return v;
            },
        };

    /// <summary>A number option; <paramref name="inRange"/> says whether a value is allowed, <paramref name="range"/> says so in words.</summary>
    public static Option<double> Double(string name, string description, double fallback, Func<double, bool> inRange, string range, string? valueName = null) =>
        new(name)
        {
            Description = description,
            HelpName = valueName ?? "x",
            DefaultValueFactory = _ => fallback,
            CustomParser = r =>
            {
                if (Value(r, name) is not { } s) return default;
                if (!double.TryParse(s, NumberStyles.Float, Inv, out double v) || !double.IsFinite(v)) { r.AddError($"{name} expects a number, got '{s}'"); return default; }
                if (!inRange(v)) r.AddError($"{name} must be {range}, got {v.ToString(Inv)}");
                return v;
            },
        };

    /// <summary>A switch: present or not; it takes no value (--shake 3 is an error, not a 3 silently dropped).</summary>
    public static Option<bool> Switch(string name, string description) => new(name) { Description = description };

    /// <summary>A text option (a file, a host name); absent means <paramref name="fallback"/> (null: not given).</summary>
    public static Option<string?> Text(string name, string description, string? fallback, string valueName)
    {
        var option = new Option<string?>(name)
        {
            Description = description,
            HelpName = valueName,
            CustomParser = r => Value(r, name),
        };
        if (fallback != null) option.DefaultValueFactory = _ => fallback;
        return option;
    }

    /// <summary>One of a few named values (case-insensitive, given back as listed), shown in the help.</summary>
    public static Option<string> Choice(string name, string description, string fallback, params string[] choices) =>
        new(name)
        {
            Description = description,
            HelpName = string.Join('|', choices.Select(c => c.Contains(' ') ? $"'{c}'" : c)),
            DefaultValueFactory = _ => fallback,
            CustomParser = r =>
            {
                if (Value(r, name) is not { } s) return fallback;
                foreach (var c in choices)
                    if (string.Equals(c, s, StringComparison.OrdinalIgnoreCase)) return c;
                r.AddError($"{name} must be one of {string.Join(", ", choices.Select(c => c.Contains(' ') ? $"'{c}'" : c))}; got '{s}'");
                return fallback;
            },
        };

    /// <summary>--path: fast (the default) or reference.</summary>
    public static Option<string> SolverPathOption(string description =
        "solver path: fast (SIMD, all cores) or reference (scalar double precision, one thread; about 30× slower)") =>
        Choice("--path", description, "fast", "fast", "reference");

    /// <summary>The solver path a --path value names.</summary>
    public static SolverPath ToSolverPath(string? value) => value == "reference" ? SolverPath.Reference : SolverPath.Fast;

    /// <summary>A comma-separated list of integers, each in <paramref name="min"/> … <paramref name="max"/>.</summary>
    public static Option<int[]> IntList(string name, string description, int[] fallback, int min, int max, string what) =>
        new(name)
        {
            Description = description,
            HelpName = "n,n,…",
            DefaultValueFactory = _ => fallback,
            CustomParser = r =>
            {
                if (Value(r, name) is not { } s) return fallback;
                var list = new List<int>();
                foreach (var part in s.Split(',', StringSplitOptions.RemoveEmptyEntries | StringSplitOptions.TrimEntries))
                {
                    if (!int.TryParse(part, NumberStyles.Integer, Inv, out int n) || n < min || n > max)
                    {
                        r.AddError($"{name} expects {what} in {min} … {max}, separated by commas; got '{part}'");
                        return fallback;
                    }
                    list.Add(n);
                }
                if (list.Count == 0) r.AddError($"{name} needs at least one value");
                return [.. list];
            },
        };

    /// <summary>Whether the option was typed on the command line (not just its default).</summary>
    public static bool Given(this ParseResult parse, Option option) => parse.GetResult(option) is { Implicit: false };

    /// <summary>The option's single value; an option name where a value belongs means the value is missing.</summary>
    private static string? Value(ArgumentResult r, string name)
    {
        if (r.Tokens.Count == 0) return null;
        string s = r.Tokens[0].Value;
        if (s.Length == 0) { r.AddError($"{name} needs a value"); return null; }
        if (s.StartsWith("--", StringComparison.Ordinal)) { r.AddError($"{name} needs a value (found the option {s} where the value belongs)"); return null; }
        return s;
    }

    /// <summary>
    /// An output file, checked before any work starts: its folder is created if missing and a file can be written there
    /// (a run that fails only at its end, after minutes, writing to a read-only folder, is worse). Fails with exit code 5.
    /// </summary>
    /// <summary>An output path as a generated document names it: as typed, with forward slashes.</summary>
    public static string Shown(string path) => path.Replace('\\', '/');

    public static string CheckOutputFile(string path, string option)
    {
        EnsureWritable(Path.GetDirectoryName(Path.GetFullPath(path)) ?? ".", option);
        return path;
    }

    /// <summary>An output folder, checked as <see cref="CheckOutputFile"/> is.</summary>
    public static string CheckOutputFolder(string path, string option)
    {
        EnsureWritable(Path.GetFullPath(path), option);
        return path;
    }

    private static void EnsureWritable(string folder, string option)
    {
        try
        {
            Directory.CreateDirectory(folder);
            string probe = Path.Combine(folder, $".hairsim-write-test-{Environment.ProcessId}");
            File.WriteAllText(probe, "");
            File.Delete(probe);
        }
        catch (Exception e) when (e is UnauthorizedAccessException or IOException)
        {
            throw new IOException($"{option}: cannot write to {folder} ({e.Message})", e);
        }
    }
}

/// <summary>
/// --sheets, --strands and --particles: the groom's size, for run and style. Any value the help allows works: the pinned
/// particles at the root are fewer than the particles (two pinned, one on a two-particle strand), and the total is checked
/// against the world's limit with the options' names.
/// </summary>
public sealed class GroomOptions
{
    private readonly GroomSettings _reference = GroomSettings.Reference();

    public Option<int> Sheets { get; }
    public Option<int> Strands { get; }
    public Option<int> Particles { get; }

    public GroomOptions()
    {
        Sheets = CliOptions.Int("--sheets", "sheets of hair grown on the head", _reference.SheetCount, 1, 1_000_000);
        Strands = CliOptions.Int("--strands", "strands per sheet (a Skeleton and its Sub-Skeletons)", _reference.StrandsPerSheet, 1, HairWorld.MaxStrandsPerSheet);
        Particles = CliOptions.Int("--particles", "particles per strand (two are pinned at the root; one on a two-particle strand)", _reference.ParticlesPerStrand, 2, HairWorld.MaxParticlesPerStrand);
    }

    public void AddTo(Command command)
    {
        command.Options.Add(Sheets);
        command.Options.Add(Strands);
        command.Options.Add(Particles);
    }

    /// <summary>Whether any of the three was typed.</summary>
    public bool Given(ParseResult parse) => parse.Given(Sheets) || parse.Given(Strands) || parse.Given(Particles);

    /// <summary>The reference groom with the given sizes.</summary>
    public GroomSettings Read(ParseResult parse)
    {
        var g = GroomSettings.Reference();
        g.SheetCount = parse.GetValue(Sheets);
        g.StrandsPerSheet = parse.GetValue(Strands);
        g.ParticlesPerStrand = parse.GetValue(Particles);
        g.PinnedPerStrand = Math.Min(g.PinnedPerStrand, g.ParticlesPerStrand - 1);
        if (g.TotalParticles > HairWorld.MaxParticles)
            throw new UsageException($"--sheets × --strands × --particles = {g.TotalParticles:N0} particles, more than the {HairWorld.MaxParticles:N0} a world holds");
        return g;
    }
}
