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
    public const string Help = "time render-buffer filling for both MultiMesh layouts: --density 1 --frames 30 --warmup 10 --repeats 200";

    public static int Execute(CliArgs a)
    {
        int density = a.Int("density", 1);
        int frames = a.Int("frames", 30);
        int warmup = a.Int("warmup", 10);
        int repeats = a.Int("repeats", 200);
        a.RejectUnknown();
        if (frames < 1 || warmup < 0 || repeats < 1 || repeats > 100_000) throw new ArgumentException("--frames ≥ 1, --warmup ≥ 0, --repeats in 1 … 100000.");

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
        return 0;
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
