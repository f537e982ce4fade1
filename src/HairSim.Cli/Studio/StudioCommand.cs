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
        var head = CliOptions.Text("--head", "your own head for the \"mesh head\" groom (.glb, .gltf or .obj; its vertex colours' red marks the scalp, all of it without colours), to paint its scalp and style hair on it; default: the project's head", null, "file");
        var command = new Command("studio", Description) { host, port, groom, density, seconds, head };
        command.SetAction(p => Execute(p.GetValue(host)!, p.GetValue(port), p.GetValue(groom)!, p.GetValue(density), p.GetValue(seconds), p.GetValue(head)));
        return command;
    }

    public static int Execute(string host, int port, string groom, int density, double seconds, string? headFile = null)
    {
        StudioGrooms.Create(groom, density > 0 ? density : null);   // refuse a bad groom before starting anything
        // A missing or unreadable file is reported (exit 5) before anything starts.
        var head = headFile == null ? null : HairSim.Meshes.MeshFile.Load(headFile);
        if (head != null) Console.WriteLine($"head mesh {headFile}: {head.TriangleCount:N0} triangles (the \"mesh head\" groom grows on it)");

        StudioSession session;
        try { session = new StudioSession(groom, density > 0 ? density : null, head: head); }
        catch (ArgumentException e) when (head != null && e is not ArgumentOutOfRangeException)
        {
            // The head's scalp cannot hold the groom (too few roots fit, no triangle on the scalp).
            throw new UsageException($"--head {headFile}: {e.Message}");
        }
        using var _ = session;
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
