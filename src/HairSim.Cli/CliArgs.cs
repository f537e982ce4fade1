using System.Globalization;

namespace HairSim.Cli;

/// <summary>
/// --name value (or --name=value) options and --flag switches. Every mistake is an ArgumentException with the option's
/// name (exit code 1): a missing value, a value given to a switch, an unknown option, an output that cannot be written.
/// </summary>
public sealed class CliArgs
{
    private readonly Dictionary<string, string?> _opts = new(StringComparer.Ordinal);
    private readonly HashSet<string> _used = new();

    public CliArgs(string[] args)
    {
        for (int i = 0; i < args.Length; i++)
        {
            if (args[i] is "-h")
            {
                _opts["help"] = null;
                continue;
            }
            if (!args[i].StartsWith("--", StringComparison.Ordinal))
                throw new ArgumentException($"Unexpected argument '{args[i]}' (options look like --name value).");
            string key = args[i][2..];
            string? value;
            int eq = key.IndexOf('=');
            if (eq >= 0) { value = key[(eq + 1)..]; key = key[..eq]; }
            else value = i + 1 < args.Length && !args[i + 1].StartsWith("--", StringComparison.Ordinal) ? args[++i] : null;
            if (key.Length == 0) throw new ArgumentException($"'{args[i]}' names no option.");
            _opts[key] = value;
        }
    }

    /// <summary>--help or -h was given (commands print their own help and exit 0).</summary>
    public bool HelpRequested => _opts.ContainsKey("help");

    /// <summary>A switch: present or not; a value after it (--shake 3) is an error, not silently dropped.</summary>
    public bool Flag(string name)
    {
        _used.Add(name);
        if (!_opts.TryGetValue(name, out var v)) return false;
        if (v != null) throw new ArgumentException($"--{name} is a switch and takes no value (got '{v}').");
        return true;
    }

    /// <summary>An option's value, or null if absent; present without a value is an error.</summary>
    public string? String(string name)
    {
        _used.Add(name);
        if (!_opts.TryGetValue(name, out var v)) return null;
        if (string.IsNullOrEmpty(v)) throw new ArgumentException($"--{name} needs a value.");
        return v;
    }

    public string String(string name, string fallback) => String(name) ?? fallback;

    public double Double(string name, double fallback)
    {
        var s = String(name);
        if (s == null) return fallback;
        if (!double.TryParse(s, NumberStyles.Float, CultureInfo.InvariantCulture, out var v) || !double.IsFinite(v))
            throw new ArgumentException($"--{name} expects a number, got '{s}'.");
        return v;
    }

    public int Int(string name, int fallback)
    {
        var s = String(name);
        if (s == null) return fallback;
        if (!int.TryParse(s, NumberStyles.Integer, CultureInfo.InvariantCulture, out var v))
            throw new ArgumentException($"--{name} expects an integer, got '{s}'.");
        return v;
    }

    /// <summary>
    /// An output file option, checked before any work starts: its folder is created if missing and a file can be
    /// written there (a run that fails only at its end, after minutes, writing to a read-only folder, is worse).
    /// </summary>
    public string OutputFile(string name, string fallback)
    {
        string path = String(name, fallback);
        EnsureWritable(Path.GetDirectoryName(Path.GetFullPath(path)) ?? ".", name);
        return path;
    }

    /// <summary>An output folder option, checked as <see cref="OutputFile"/> is.</summary>
    public string OutputFolder(string name, string fallback)
    {
        string path = String(name, fallback);
        EnsureWritable(Path.GetFullPath(path), name);
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
            throw new ArgumentException($"--{option}: cannot write to {folder} ({e.Message}).");
        }
    }

    /// <summary>Fails on options nobody asked for (typos).</summary>
    public void RejectUnknown()
    {
        foreach (var k in _opts.Keys)
            if (!_used.Contains(k) && k != "help") throw new ArgumentException($"Unknown option --{k}.");
    }
}
