using System.CommandLine;

namespace HairSim.Cli.Studio;

/// <summary>`hairsim studio`: serves HairSheet Studio on loopback until Ctrl+C (or --seconds).</summary>
public static class StudioCommand
{
    public const string Description = "Style hair in a browser: serves HairSheet Studio on http://127.0.0.1:5088/ until Ctrl+C.";

    public static Command Create()
    {
        var host = CliOptions.Text("--host", "address to listen on (anything but loopback lets other machines use the studio)", "127.0.0.1", "address");
        var port = CliOptions.Int("--port", "port to listen on; 0 picks a free one", 5088, 0, 65535);
        var groom = CliOptions.Choice("--groom", "the hair the studio starts with", StudioGrooms.Default, [.. StudioGrooms.All.Select(g => g.Name)]);
        var density = CliOptions.Int("--density", "strands per sheet, overriding the groom's (0 keeps the groom's)", 0, 0, 64);
        var seconds = CliOptions.Double("--seconds", "stop after this many seconds (0 = run until Ctrl+C)", 0, v => v >= 0, "0 or more seconds", "seconds");
        var command = new Command("studio", Description) { host, port, groom, density, seconds };
        command.SetAction(p => Execute(p.GetValue(host)!, p.GetValue(port), p.GetValue(groom)!, p.GetValue(density), p.GetValue(seconds)));
        return command;
    }

    public static int Execute(string host, int port, string groom, int density, double seconds)
    {
        StudioGrooms.Create(groom, density > 0 ? density : null);   // refuse a bad groom before starting anything

        using var session = new StudioSession(groom, density > 0 ? density : null);
        var (app, url) = StudioServer.StartAsync(session, host, port).GetAwaiter().GetResult();
        session.Start();
        if (host is not ("127.0.0.1" or "localhost" or "::1"))
            Console.WriteLine($"warning: listening on {host}: anyone who can reach this machine can use the studio.");
        Console.WriteLine($"HairSheet Studio: {url}");
        Console.WriteLine("Open it in a browser. Ctrl+C stops the server.");
        Console.Out.Flush();

        using var stop = new CancellationTokenSource();
        Console.CancelKeyPress += (_, e) => { e.Cancel = true; stop.Cancel(); };
        if (seconds > 0) stop.CancelAfter(TimeSpan.FromSeconds(seconds));
        try { Task.Delay(Timeout.Infinite, stop.Token).Wait(); } catch (AggregateException) { }
        app.StopAsync().GetAwaiter().GetResult();
        Console.WriteLine("HairSheet Studio stopped.");
        return 0;
    }
}
