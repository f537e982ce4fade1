namespace HairSim.Cli.Studio;

/// <summary>`hairsim studio`: serves HairSheet Studio on loopback until Ctrl+C (or --seconds).</summary>
public static class StudioCommand
{
    public const string Help = "style hair in a browser: serves HairSheet Studio on http://127.0.0.1:5088/ (--port N, 0 = any free port; " +
        "--host 127.0.0.1; --groom reference|medium|long|short|small; --density strands per sheet; --seconds N to stop after N s)";

    public static int Execute(CliArgs a)
    {
        string host = a.String("host", "127.0.0.1");
        int port = a.Int("port", 5088);
        string groom = a.String("groom", StudioGrooms.Default);
        int density = a.Int("density", 0);
        double seconds = a.Double("seconds", 0);
        a.RejectUnknown();
        if (port < 0 || port > 65535) throw new ArgumentException("--port must be 0 … 65535 (0 = any free port).");
        if (seconds < 0) throw new ArgumentException("--seconds must be 0 (run until Ctrl+C) or more.");
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
