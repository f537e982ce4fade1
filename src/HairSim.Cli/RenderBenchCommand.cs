using System.CommandLine;
using System.Diagnostics;
using System.Globalization;
using HairSheet.Logic;
using HairSim;

namespace HairSim.Cli;

/// <summary>
/// CPU side of the Godot renderer: times filling the MultiMesh data for both layouts on the reference scene
/// (after warm-up, over repeats) and reports bytes uploaded per frame. The GPU side is discussed in docs/godot.md.
/// </summary>
public static class RenderBenchCommand
{
    public const string Description = "CPU cost of filling the Godot renderer's buffers for both MultiMesh layouts, and the main thread's frame with the hair stepped in place or on a worker thread.";

    public static Command Create()
    {
        var density = CliOptions.Int("--density", "render strands drawn between two neighbouring simulated strands", 1, 0, RenderSettings.MaxStrandsPerGap);
        var frames = CliOptions.Int("--frames", "60 Hz frames simulated first, so the hair is at rest as in a running game", 30, 1, 100_000);
        var warmup = CliOptions.Int("--warmup", "untimed fills before the timed ones", 10, 0, 100_000);
        var repeats = CliOptions.Int("--repeats", "timed fills (the median is reported)", 200, 1, 100_000);
        var renderMs = CliOptions.Double("--render-ms", "milliseconds the main thread stays busy per frame, standing in for the engine's own work", 5, v => v >= 0 && v <= 100, "in 0 … 100 ms", "ms");
        var command = new Command("render-bench", Description) { density, frames, warmup, repeats, renderMs };
        command.SetAction(p => Execute(p.GetValue(density), p.GetValue(frames), p.GetValue(warmup), p.GetValue(repeats), p.GetValue(renderMs)));
        return command;
    }

    public static int Execute(int density, int frames, int warmup, int repeats, double renderMs)
    {

        var scene = GroomBuilder.BuildScene(GroomSettings.Reference(), new SimulationSettings { Path = SolverPath.Fast });
        scene.Render = new RenderSettings { StrandsPerGap = density };
        using var dispatcher = ThreadDispatchers.CreateDefault();
        var sim = new HairSimulation(scene, dispatcher: dispatcher);
        for (int f = 0; f < frames; f++) sim.Step(1f / 60f);   // hair at rest-ish, as in a running game
        var rs = scene.RenderOutput!;
        Console.WriteLine($"reference scene, render density {density}: {rs.StrandCount:N0} render strands × {rs.Stride} points ({rs.TotalPoints:N0} live points)");

        var seg12 = new SegmentInstanceBuffer(rs, false, false, StrandLook.Default);
        var seg16 = new SegmentInstanceBuffer(rs, false, true, StrandLook.Default);
        var tex = new PositionTextureBuffer(rs, StrandLook.Default);
        Report("segments, 12 floats (transform)", warmup, repeats, () => seg12.Fill(rs), () => seg12.BytesPerUpload, $"{seg12.MaxInstances:N0} instances × 8 vertices");
        Report("segments, 16 floats (+custom)", warmup, repeats, () => seg16.Fill(rs), () => seg16.BytesPerUpload, $"{seg16.MaxInstances:N0} instances × 8 vertices");
        Report("position texture (RGBAF)", warmup, repeats, () => tex.Fill(rs), () => tex.BytesPerUpload,
            $"{tex.InstanceCount:N0} instances × {rs.Stride * 2} vertices, texture {tex.Width} × {tex.Height}");
        MainThread(sim, tex, warmup, repeats, renderMs);
        return 0;
    }

    /// <summary>
    /// The main thread's share of a 60 Hz frame, HairSystem3D's two modes on the same simulation: in place (step,
    /// then fill the position texture) and on a worker (wait for last frame's step, fill, start the next: one frame
    /// of latency). Between frames the main thread is kept busy for <paramref name="renderMs"/> (spinning), standing in
    /// for the engine's own work while the worker steps.
    /// </summary>
    private static void MainThread(HairSimulation sim, PositionTextureBuffer tex, int warmup, int repeats, double renderMs)
    {
        var rs = sim.Scene.RenderOutput!;
        var inPlace = new double[repeats];
        var onWorker = new double[repeats];
        var sw = new Stopwatch();
        int f = 0;
        for (int i = -warmup; i < repeats; i++, f++)
        {
            sw.Restart();
            sim.Step(1f / 60f, HairSim.Measurement.HeadMotion.Shake(f / 60f));
            tex.Fill(rs);
            if (i >= 0) inPlace[i] = sw.Elapsed.TotalMilliseconds;
            Spin(renderMs);
        }
        using (var stepper = new BackgroundStepper(sim))
        {
            for (int i = -warmup; i < repeats; i++, f++)
            {
                sw.Restart();
                stepper.Wait();
                tex.Fill(rs);
                stepper.Start(1f / 60f, 1, HairSim.Measurement.HeadMotion.Shake(f / 60f));
                if (i >= 0) onWorker[i] = sw.Elapsed.TotalMilliseconds;
                Spin(renderMs);
            }
            stepper.Wait();
        }
        Array.Sort(inPlace); Array.Sort(onWorker);
        Console.WriteLine(string.Create(CultureInfo.InvariantCulture,
            $"main thread per frame (step + position-texture fill; {renderMs:F1} ms of other main-thread work between frames): in place median {inPlace[repeats / 2]:F3} ms, p95 {inPlace[(int)(repeats * 0.95)]:F3} ms; on a worker median {onWorker[repeats / 2]:F3} ms, p95 {onWorker[(int)(repeats * 0.95)]:F3} ms (one frame of latency)"));
    }

    private static void Spin(double ms)
    {
        var t = Stopwatch.StartNew();
        while (t.Elapsed.TotalMilliseconds < ms) Thread.SpinWait(64);
    }

    private static void Report(string name, int warmup, int repeats, Func<int> fill, Func<long> bytes, string shape)
    {
        for (int i = 0; i < warmup; i++) fill();
        var times = new double[repeats];
        var sw = new Stopwatch();
        for (int i = 0; i < repeats; i++)
        {
            sw.Restart();
            fill();
            times[i] = sw.Elapsed.TotalMilliseconds;
        }
        Array.Sort(times);
        double mean = 0;
        foreach (var t in times) mean += t;
        mean /= repeats;
        Console.WriteLine(string.Create(CultureInfo.InvariantCulture,
            $"{name,-34} fill: median {times[repeats / 2]:F3} ms, mean {mean:F3} ms, p95 {times[(int)(repeats * 0.95)]:F3} ms; upload {bytes() / 1048576.0:F2} MiB/frame ({shape})"));
    }
}
