using System.Diagnostics;
using HairSim;

namespace HairSim.Cli;

public static partial class BenchCommand
{
    /// <summary>One scene of an interleaved group: its row's name and path label, and how it is built.</summary>
    internal sealed record Contender(string Scene, string PathLabel, GroomSettings Groom, BendModel Bend = BendModel.RestShape,
        bool Styled = false, Action<SimulationSettings>? Tune = null);

    /// <summary>
    /// Whole frames of several scenes stepped in turn, in blocks of about equal time, in one process: the rows whose ratios
    /// are targets (the default model against the former default, styled against uncut, one substep against four, each
    /// strand length against the best) are timed side by side, so a slow spell of a shared machine falls on all of them
    /// alike instead of on whichever row happened to run then.
    /// </summary>
    private static List<Row> Interleaved(IReadOnlyList<Contender> group, IThreadDispatcher dispatcher, int threads, int warmup, int frames)
    {
        int n = group.Count;
        var scenes = new HairScene[n];
        var sims = new HairSimulation[n];
        for (int k = 0; k < n; k++)
        {
            var c = group[k];
            scenes[k] = Scene(c.Groom, SolverPath.Fast, c.Bend, c.Tune);
            sims[k] = new HairSimulation(scenes[k], dispatcher: dispatcher);
            if (c.Styled) new StyleCommand.Script(c.Groom).StyleAll(sims[k]);
        }
        float dt = 1f / 60f;
        var f = new int[n];
        void Step(int k) { f[k]++; sims[k].Step(dt, HairSim.Measurement.HeadMotion.Shake(f[k] * dt)); }
        // At least `warmup` frames each and 1.5 s in all, so the JIT's optimised tier is what gets timed; the last
        // warm-up frame of each scene sizes its blocks.
        var warm = Stopwatch.StartNew();
        var sw = new Stopwatch();
        var warmMs = new double[n];
        for (int i = 0; i < warmup || warm.Elapsed.TotalSeconds < 1.5; i++)
            for (int k = 0; k < n; k++) { sw.Restart(); Step(k); warmMs[k] = sw.Elapsed.TotalMilliseconds; }
        // Blocks of about equal time: 10 frames of the slowest scene, more of a faster one (up to 8 times as many), so a
        // short frame is not timed in a window a fraction as long as its neighbours' (one slow spell would decide it).
        const int Block = 10;
        int blocks = Math.Max(1, (frames + Block - 1) / Block);
        double slowest = warmMs.Max();
        var blockFrames = new int[n];
        var times = new double[n][];
        var substeps = new long[n];
        for (int k = 0; k < n; k++)
        {
            blockFrames[k] = (int)Math.Clamp(Math.Round(Block * slowest / Math.Max(1e-3, warmMs[k])), Block, 8 * Block);
            times[k] = new double[blocks * blockFrames[k]];
        }
        long bytes = GC.GetTotalAllocatedBytes(true);
        for (int b = 0; b < blocks; b++)
            for (int k = 0; k < n; k++)
                for (int i = 0; i < blockFrames[k]; i++)
                {
                    sw.Restart();
                    Step(k);
                    times[k][b * blockFrames[k] + i] = sw.Elapsed.TotalMilliseconds;
                    substeps[k] += sims[k].Pipeline.LastFrameSubsteps;
                }
        bytes = GC.GetTotalAllocatedBytes(true) - bytes; // over the whole group: each row shows its share
        var rows = new List<Row>(n);
        for (int k = 0; k < n; k++)
        {
            var c = group[k];
            if (scenes[k].World.CountNonFinite() != 0) throw new InvalidDataException($"{c.Scene} produced non-finite values.");
            var row = Summarise(c.Scene, "frame", SolverPath.Fast, threads, scenes[k], times[k], bytes / n, times[k].Length, (double)substeps[k] / times[k].Length)
                with { Path = c.PathLabel };
            rows.Add(row);
            Console.Error.WriteLine($"{c.Scene,-22} {Label(row),-18} {row.MedianMs,9:F3} ms/frame (interleaved)");
        }
        return rows;
    }
}
