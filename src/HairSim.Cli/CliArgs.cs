using System.Globalization;

namespace HairSim.Cli;

/// <summary>--name value options and --flag switches.</summary>
public sealed class CliArgs
{
    private readonly Dictionary<string, string?> _opts = new(StringComparer.Ordinal);
    private readonly HashSet<string> _used = new();

    public CliArgs(string[] args)
    {
        for (int i = 0; i < args.Length; i++)
        {
            if (!args[i].StartsWith("--", StringComparison.Ordinal))
                throw new ArgumentException($"Unexpected argument '{args[i]}' (options look like --name value).");
            string key = args[i][2..];
            string? value = i + 1 < args.Length && !args[i + 1].StartsWith("--", StringComparison.Ordinal) ? args[++i] : null;
            _opts[key] = value;
        }
    }

    public bool Flag(string name) { _used.Add(name); return _opts.ContainsKey(name); }

    public string? String(string name) { _used.Add(name); return _opts.TryGetValue(name, out var v) ? v : null; }

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

    /// <summary>Fails on options nobody asked for (typos).</summary>
    public void RejectUnknown()
    {
        foreach (var k in _opts.Keys)
            if (!_used.Contains(k)) throw new ArgumentException($"Unknown option --{k}.");
    }
}
