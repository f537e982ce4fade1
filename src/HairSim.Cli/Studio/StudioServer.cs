using System.Text.Json;
using Microsoft.AspNetCore.Builder;
using Microsoft.AspNetCore.Hosting;
using Microsoft.AspNetCore.Hosting.Server;
using Microsoft.AspNetCore.Hosting.Server.Features;
using Microsoft.AspNetCore.Http;
using Microsoft.Extensions.DependencyInjection;
using Microsoft.Extensions.FileProviders;
using Microsoft.Extensions.Logging;

namespace HairSim.Cli.Studio;

/// <summary>
/// The studio's web server: the page and three.js as static files, and a small HTTP API over a
/// <see cref="StudioSession"/>. Commands answer JSON ({ message } or { error } with status 400); frames and
/// topology are binary (see <see cref="FrameEncoder"/>); save and export are downloads.
/// </summary>
public static class StudioServer
{
    /// <summary>Where the page's files are copied by the build (the CLI's output folder).</summary>
    public static string WebRoot => Path.Combine(AppContext.BaseDirectory, "wwwroot");

    /// <summary>Starts listening on host:port (port 0 = any free port) and returns the app and the address it got.</summary>
    public static async Task<(WebApplication App, string Url)> StartAsync(StudioSession session, string host, int port)
    {
        if (!File.Exists(Path.Combine(WebRoot, "index.html")))
            throw new IOException($"The studio's page is missing from {WebRoot}: rebuild the CLI (dotnet build -c Release src/HairSim.Cli).");
        var builder = WebApplication.CreateSlimBuilder(new WebApplicationOptions { ContentRootPath = AppContext.BaseDirectory, WebRootPath = WebRoot });
        builder.Logging.ClearProviders();
        builder.WebHost.UseUrls($"http://{(host.Contains(':') ? $"[{host}]" : host)}:{port}");
        builder.WebHost.ConfigureKestrel(k => k.Limits.MaxRequestBodySize = Math.Min(HairSim.IO.HairstyleFile.MaxFileBytes, 1L << 30));
        builder.Services.ConfigureHttpJsonOptions(o => o.SerializerOptions.PropertyNamingPolicy = JsonNamingPolicy.CamelCase);
        var app = builder.Build();
        app.UseDefaultFiles();
        app.UseStaticFiles(new StaticFileOptions
        {
            FileProvider = new PhysicalFileProvider(WebRoot),
            OnPrepareResponse = c => c.Context.Response.Headers.CacheControl = "no-cache",
        });
        Map(app, session);
        await app.StartAsync();
        var address = app.Services.GetRequiredService<IServer>().Features.Get<IServerAddressesFeature>()!.Addresses.First();
        return (app, address.Replace("[::]", "localhost").TrimEnd('/') + "/");
    }

    private static void Map(WebApplication app, StudioSession s)
    {
        app.MapGet("/api/state", () => Results.Json(s.State()));
        app.MapGet("/api/frame", () => Results.Bytes(s.Frame(), "application/octet-stream"));
        app.MapGet("/api/topology", () => Results.Bytes(s.Topology(), "application/octet-stream"));
        app.MapGet("/api/mesh", () => s.Mesh() is { } m ? Results.Bytes(m, "application/octet-stream") : Results.NotFound());
        app.MapPost("/api/cut", (StrokeRequest r) => Run(() => s.Cut(r)));
        app.MapPost("/api/select", (SelectRequest r) => Run(() => s.Select(r)));
        app.MapPost("/api/select/clear", () => Run(s.ClearSelection));
        app.MapPost("/api/fit", (StrokeRequest r) => Run(() => s.Fit(r)));
        app.MapPost("/api/undo", () => Run(s.Undo));
        app.MapPost("/api/redo", () => Run(s.Redo));
        app.MapPost("/api/regrow", () => Run(s.Regrow));
        app.MapPost("/api/reset", () => Run(s.ResetPose));
        app.MapGet("/api/scalp", () => s.ScalpMask() is { } m ? Results.Bytes(m, "application/octet-stream") : Results.NotFound());
        app.MapPost("/api/scalp/paint", (ScalpPaintRequest r) => Run(() => s.PaintScalp(r)));
        app.MapPost("/api/scalp/fill", (ScalpFillRequest r) => Run(() => s.FillScalp(r)));
        app.MapPost("/api/scalp/undo", () => Run(s.UndoScalp));
        app.MapPost("/api/scalp/redo", () => Run(s.RedoScalp));
        app.MapPost("/api/scalp/grow", () => Run(s.GrowOnScalp));
        app.MapPost("/api/settings", (SettingsRequest r) => Run(() => s.ApplySettings(r)));
        app.MapPost("/api/groom", (GroomRequest r) => Run(() => s.SetGroom(r)));
        app.MapPost("/api/head", (HeadRequest r) => Run(() => s.SetHead(r)));
        app.MapPost("/api/pause", (bool paused) => Run(() => s.SetPaused(paused)));
        app.MapGet("/api/save", () => Results.File(s.Save(), "application/octet-stream", "haircut.hairstyle"));
        app.MapGet("/api/export/{format}", (string format) =>
        {
            try { var (data, name, type) = s.Export(format); return Results.File(data, type, name); }
            catch (ArgumentException e) { return Results.BadRequest(new { error = e.Message }); }
        });
        app.MapPost("/api/load", async (HttpRequest request) =>
        {
            using var m = new MemoryStream();
            await request.Body.CopyToAsync(m);
            return Run(() => s.Load(m.GetBuffer().AsSpan(0, (int)m.Length)));
        });
    }

    private static IResult Run(Func<string> command)
    {
        try { return Results.Json(new { message = command() }); }
        catch (ArgumentException e) { return Results.BadRequest(new { error = e.Message }); }
    }
}
