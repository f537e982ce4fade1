using System.CommandLine;
using System.CommandLine.Help;
using System.CommandLine.Invocation;
using System.CommandLine.Parsing;
using HairSim.Cli.Studio;

namespace HairSim.Cli;

/// <summary>
/// The console's exit codes, the same for the same kind of failure in every command (README, "Exit codes", shows this
/// table; `hairsim --help` prints it).
/// </summary>
public static class ExitCodes
{
    /// <summary>Done (for report: its checks passed too).</summary>
    public const int Ok = 0;
    /// <summary>An unexpected error inside the program (a bug): the error and where it happened are printed.</summary>
    public const int InternalError = 1;
    /// <summary>The command line is wrong: unknown command or option, missing or malformed value, value out of range, options that do not go together.</summary>
    public const int Usage = 2;
    /// <summary>A simulation produced non-finite values (NaN or infinity).</summary>
    public const int NonFinite = 3;
    /// <summary>A check the command makes on its own result failed (report: the defaults off the Pareto front; style: the saved hairstyle does not reload bit-exact, or the scripted cut cut nothing).</summary>
    public const int CheckFailed = 4;
    /// <summary>A file, folder or port named on the command line cannot be used: an input missing, unreadable or not in its format, an output folder that cannot be written, a port already taken.</summary>
    public const int FileError = 5;

    public static readonly IReadOnlyList<(int Code, string Meaning)> Table =
    [
        (Ok, "done"),
        (InternalError, "unexpected error inside the program (a bug; the error and its stack trace are printed)"),
        (Usage, "wrong command line: unknown command or option, missing or malformed value, value out of range, options that do not go together"),
        (NonFinite, "the simulation produced non-finite values (run, style, stability)"),
        (CheckFailed, "a check on the result failed (report: defaults off the Pareto front or hanging length error ≥ 0.5 %; style: the saved hairstyle does not reload bit-exact, or the cut cut nothing)"),
        (FileError, "a file, folder or port named on the command line cannot be used (input missing, unreadable or corrupt; output not writable; port taken)"),
    ];
}

/// <summary>A mistake on the command line found after parsing (options that do not go together, …): exit code 2.</summary>
public sealed class UsageException(string message) : Exception(message);

/// <summary>
/// The console's command line (System.CommandLine): every command with typed options, per-command --help, errors that
/// name the option, and one exit code per kind of failure (<see cref="ExitCodes"/>).
/// </summary>
public static class CliApp
{
    /// <summary>The name the help and error messages use for the program.</summary>
    public const string Name = "hairsim";

    /// <summary>All commands; `run` is the main job and the default when no argument is given.</summary>
    public static Command Build()
    {
        var root = new Command(Name, "HairSheet's headless console: simulate the reference scene, style, measure and benchmark, serve the studio.")
        {
            RunCommand.Create(),
            StyleCommand.Create(),
            ReportCommand.Create(),
            StabilityCommand.Create(),
            LeaveOutCommand.Create(),
            BenchCommand.Create(),
            RenderBenchCommand.Create(),
            StudioCommand.Create(),
        };
        var help = new HelpOption();
        help.Action = new HelpWithExitCodes((HelpAction)help.Action!);
        root.Options.Add(help);
        return root;
    }

    /// <summary>
    /// Parses and runs a command line; returns the exit code. Parse errors, usage errors and files that cannot be used are
    /// reported on <paramref name="error"/> in one line each, never as a stack trace.
    /// </summary>
    public static int Run(string[] args, TextWriter? output = null, TextWriter? error = null)
    {
        output ??= Console.Out;
        error ??= Console.Error;
        if (args.Length == 0)
        {
            // The main job: the reference scene, without printing the help first.
            output.WriteLine($"{Name}: the main job (run: the reference scene for 10 s); `--help` lists the commands and options.");
            args = ["run"];
        }
        var root = Build();
        var parse = root.Parse(args, new ParserConfiguration { ResponseFileTokenReplacer = null });
        var config = new InvocationConfiguration { Output = output, Error = error, EnableDefaultExceptionHandler = false };
        if (parse.Action is HelpWithExitCodes) return parse.Invoke(config);
        if (parse.Errors.Count > 0)
        {
            foreach (var message in Messages(parse)) error.WriteLine($"error: {message}");
            var command = parse.CommandResult.Command;
            error.WriteLine(command == root
                ? $"`{Name} --help` lists the commands."
                : $"`{Name} {command.Name} --help` lists its options.");
            return ExitCodes.Usage;
        }
        try
        {
            return parse.Invoke(config);
        }
        catch (Exception e)
        {
            return Fail(e, error);
        }
    }

    /// <summary>The exit code for an exception out of a command, with its message (and stack trace for a bug).</summary>
    public static int Fail(Exception e, TextWriter error)
    {
        switch (e)
        {
            case UsageException:
                error.WriteLine($"error: {e.Message}");
                return ExitCodes.Usage;
            case IOException or UnauthorizedAccessException or InvalidDataException:
                error.WriteLine($"error: {e.Message}");
                return ExitCodes.FileError;
            default:
                error.WriteLine($"internal error (please report it): {e}");
                return ExitCodes.InternalError;
        }
    }

    /// <summary>
    /// Parse errors in words that name options: "--seconds needs a value", "unknown option --sceonds for run (did you
    /// mean --seconds?)", "--shake is a switch and takes no value".
    /// </summary>
    private static List<string> Messages(ParseResult parse)
    {
        var messages = new List<string>();
        var command = parse.CommandResult.Command;
        var tokens = parse.Tokens;
        var unmatched = new HashSet<string>(parse.UnmatchedTokens, StringComparer.Ordinal);
        var skip = new HashSet<string>(StringComparer.Ordinal);
        // Unmatched tokens in command-line order, each explained by what stands before it.
        for (int i = 0; i < tokens.Count; i++)
        {
            string t = tokens[i].Value;
            if (!unmatched.Contains(t) || skip.Contains(t)) continue;
            skip.Add(t);
            var before = i > 0 ? tokens[i - 1] : null;
            if (t.StartsWith('-'))
            {
                string name = t.Split('=', ':')[0];
                if (command.Parents.Any())
                {
                    string? near = Nearest(name, command.Options.SelectMany(o => o.Aliases.Prepend(o.Name)));
                    messages.Add($"unknown option {name} for {command.Name}{(near != null ? $" (did you mean {near}?)" : "")}");
                }
                else
                {
                    var owner = command.Subcommands.FirstOrDefault(c => FindOption(c, name) != null);
                    messages.Add($"unknown option {name}{(owner != null ? $" (options come after the command: `{Name} {owner.Name} {name} …`)" : "")}");
                }
                // A value right after an unknown option belongs to it: one message is enough.
                if (i + 1 < tokens.Count && !tokens[i + 1].Value.StartsWith('-')) skip.Add(tokens[i + 1].Value);
            }
            else if (before != null && before.Type == TokenType.Option && FindOption(command, before.Value) is { ValueType: var type } && type == typeof(bool))
                messages.Add($"{before.Value} is a switch and takes no value (got '{t}')");
            else if (command.Parents.Any())
                messages.Add($"unexpected argument '{t}' (options look like --name value or --name=value)");
            else
            {
                string? near = Nearest(t, command.Subcommands.Select(c => c.Name));
                messages.Add($"unknown command '{t}'{(near != null ? $" (did you mean {near}?)" : "")}");
            }
        }
        foreach (var e in parse.Errors)
        {
            string m = e.Message;
            if (m.StartsWith("Unrecognized command or argument", StringComparison.Ordinal)) continue;
            if (m.StartsWith("Required command was not provided", StringComparison.Ordinal))
            {
                if (messages.Count == 0) messages.Add($"no command given (commands: {string.Join(", ", command.Subcommands.Select(c => c.Name))})");
                continue;
            }
            if (m.StartsWith("Required argument missing for option", StringComparison.Ordinal) && e.SymbolResult is OptionResult o)
                m = $"{o.IdentifierToken?.Value ?? o.Option.Name} needs a value";
            else if (m.Contains("expects a single argument but", StringComparison.Ordinal) && e.SymbolResult is OptionResult many)
                m = $"{many.IdentifierToken?.Value ?? many.Option.Name} is given more than once";
            messages.Add(m.TrimEnd('.'));
        }
        return messages;
    }

    private static Option? FindOption(Command command, string token)
    {
        string name = token.Split('=', ':')[0];
        return command.Options.FirstOrDefault(o => o.Name == name || o.Aliases.Contains(name));
    }

    /// <summary>The closest name within two edits, for "did you mean".</summary>
    private static string? Nearest(string given, IEnumerable<string> names)
    {
        string? best = null;
        int bestDistance = 3;
        foreach (var n in names)
        {
            int d = Distance(given, n);
            if (d < bestDistance) { best = n; bestDistance = d; }
        }
        return best;
    }

    private static int Distance(string a, string b)
    {
        var row = new int[b.Length + 1];
        for (int j = 0; j <= b.Length; j++) row[j] = j;
        for (int i = 1; i <= a.Length; i++)
        {
            int diagonal = row[0];
            row[0] = i;
            for (int j = 1; j <= b.Length; j++)
            {
                int up = row[j];
                row[j] = Math.Min(Math.Min(row[j] + 1, row[j - 1] + 1), diagonal + (a[i - 1] == b[j - 1] ? 0 : 1));
                diagonal = up;
            }
        }
        return row[b.Length];
    }

    /// <summary>The library's help, then the exit codes (all of them for the program, one line for a command).</summary>
    private sealed class HelpWithExitCodes(HelpAction inner) : SynchronousCommandLineAction
    {
        public override bool ClearsParseErrors => true;

        public override int Invoke(ParseResult parse)
        {
            inner.Invoke(parse);
            var output = parse.InvocationConfiguration.Output;
            if (parse.CommandResult.Command.Parents.Any())
            {
                output.WriteLine($"Exit codes: 0 done, 2 wrong command line, 3 non-finite values, 4 a check on the result failed, 5 a file, folder or port cannot be used, 1 internal error (`{Name} --help` explains them).");
                return ExitCodes.Ok;
            }
            output.WriteLine("With no command, runs the main job: `run` with its defaults (the reference scene for 10 s).");
            output.WriteLine();
            output.WriteLine("Exit codes:");
            foreach (var (code, meaning) in ExitCodes.Table) output.WriteLine($"  {code}  {meaning}");
            return ExitCodes.Ok;
        }
    }
}
