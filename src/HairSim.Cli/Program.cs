using HairSim.Cli;
using HairSim.Cli.Studio;

// hairsim <command> [options]: each command lives in its own file (RunCommand.cs, …).
var commands = new Dictionary<string, (string Help, Func<CliArgs, int> Run)>
{
    ["run"] = (RunCommand.Help, RunCommand.Execute),
    ["render-bench"] = (RenderBenchCommand.Help, RenderBenchCommand.Execute),
    ["style"] = (StyleCommand.Help, StyleCommand.Execute),
    ["report"] = (ReportCommand.Help, ReportCommand.Execute),
    ["stability"] = (StabilityCommand.Help, StabilityCommand.Execute),
    ["bench"] = (BenchCommand.Help, BenchCommand.Execute),
    ["leave-out"] = (LeaveOutCommand.Help, LeaveOutCommand.Execute),
    ["studio"] = (StudioCommand.Help, StudioCommand.Execute),
};

if (args.Length == 0 || args[0] is "-h" or "--help" or "help")
{
    Console.WriteLine("hairsim: HairSheet's headless console.\n\nCommands:");
    foreach (var (name, c) in commands) Console.WriteLine($"  {name,-10} {c.Help}");
    Console.WriteLine("\nWith no command: run (the reference scene, 10 s). `<command> --help` shows one command's options.");
    Console.WriteLine("Exit codes: 0 done; 1 bad option or value, or an output that cannot be written; 2 unknown command;");
    Console.WriteLine("           3 the run produced non-finite values.");
    if (args.Length == 0) return RunCommand.Execute(new CliArgs([]));
    return 0;
}
if (!commands.TryGetValue(args[0], out var cmd))
{
    Console.Error.WriteLine($"Unknown command '{args[0]}'. Try --help.");
    return 2;
}
try
{
    var cli = new CliArgs(args[1..]);
    if (cli.HelpRequested)
    {
        Console.WriteLine($"hairsim {args[0]}: {cmd.Help}");
        return 0;
    }
    return cmd.Run(cli);
}
catch (Exception e) when (e is ArgumentException or InvalidDataException or IOException or FormatException or UnauthorizedAccessException)
{
    Console.Error.WriteLine($"error: {e.Message}");
    return 1;
}
