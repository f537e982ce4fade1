using System.Diagnostics;
using System.Runtime.CompilerServices;
using System.Runtime.Intrinsics;

namespace HairSim.Cli;

/// <summary>
/// What the machine gives at the moment of a bench run, measured without HairSim: arithmetic throughput and memory
/// bandwidth on one thread and on every thread. On a shared virtual machine both move from run to run (two virtual
/// cores may land on one physical core, a neighbour may fill the memory bus), and the bench's rows move with them; the
/// check taken before and after the rows says which kind of run a table came from.
/// </summary>
internal static class MachineCheck
{
    /// <param name="ComputeGain">Arithmetic done per second on every thread against one thread (2 = two full cores).</param>
    /// <param name="Gbps1">Memory read bandwidth of one thread, GB/s.</param>
    /// <param name="GbpsAll">Memory read bandwidth of every thread together, GB/s.</param>
    public readonly record struct Result(double ComputeGain, double Gbps1, double GbpsAll, int Threads);

    /// <summary>Where the results go, so the JIT keeps the loops.</summary>
    public static volatile float Sink;

    // 64 MB: far beyond the caches, so the sums stream from memory.
    private const int StreamFloats = 16 * 1024 * 1024;

    public static Result Measure(int threads)
    {
        threads = Math.Max(1, threads);
        var data = GC.AllocateUninitializedArray<float>(StreamFloats);
        Array.Fill(data, 1f);
        // One thread and every thread alternate, so a passing disturbance meets both; the best of each is kept.
        double one = double.MaxValue, all = double.MaxValue, bw1 = double.MaxValue, bwAll = double.MaxValue;
        for (int i = 0; i < 7; i++)
        {
            one = Math.Min(one, Parallel(1, _ => Sink = Compute(3_000_000)));
            all = Math.Min(all, Parallel(threads, _ => Sink = Compute(3_000_000)));
            bw1 = Math.Min(bw1, Parallel(1, _ => Sink = Sum(data, 0, StreamFloats)));
            bwAll = Math.Min(bwAll, Parallel(threads, t => Sink = Sum(data, (int)((long)StreamFloats * t / threads), (int)((long)StreamFloats * (t + 1) / threads))));
        }
        double bytes = StreamFloats * (double)sizeof(float);
        return new Result(threads * one / all, bytes / bw1 / 1e9, bytes / bwAll / 1e9, threads);
    }

    /// <summary>
    /// A quick reading of the arithmetic gain alone (every thread against one, best of three each, about 10 ms): taken
    /// between the rounds of a timed row, it says what the machine gave every thread at that moment.
    /// </summary>
    public static double QuickGain(int threads)
    {
        threads = Math.Max(1, threads);
        double one = double.MaxValue, all = double.MaxValue;
        for (int i = 0; i < 3; i++)
        {
            one = Math.Min(one, Parallel(1, _ => Sink = Compute(1_000_000)));
            all = Math.Min(all, Parallel(threads, _ => Sink = Compute(1_000_000)));
        }
        return threads * one / all;
    }

    /// <summary>One line for the bench's document.</summary>
    public static string Describe(Result r) => string.Create(System.Globalization.CultureInfo.InvariantCulture,
        $"arithmetic on {r.Threads} threads {r.ComputeGain:F2}× one thread's, memory reads {r.Gbps1:F1} GB/s on 1 thread and {r.GbpsAll:F1} GB/s on {r.Threads}");

    private static double Parallel(int threads, Action<int> work)
    {
        var sw = Stopwatch.StartNew();
        if (threads == 1) work(0);
        else
        {
            var others = new Thread[threads - 1];
            for (int t = 1; t < threads; t++) { int k = t; others[t - 1] = new Thread(() => work(k)); others[t - 1].Start(); }
            work(0);
            foreach (var th in others) th.Join();
        }
        return sw.Elapsed.TotalSeconds;
    }

    // Eight independent fused chains: bound by the core's arithmetic throughput, not by latency, so two threads on one
    // physical core (sharing its units) show as a gain well below the thread count.
    [MethodImpl(MethodImplOptions.AggressiveOptimization)] // optimised from the first call: no tiering inside the check
    private static float Compute(int n)
    {
        var m = Vector256.Create(0.99999994f);
        Vector256<float> a0 = Vector256.Create(1f), a1 = a0, a2 = a0, a3 = a0, a4 = a0, a5 = a0, a6 = a0, a7 = a0;
        var c = Vector256.Create(1e-7f);
        for (int i = 0; i < n; i++)
        {
            a0 = a0 * m + c; a1 = a1 * m + c; a2 = a2 * m + c; a3 = a3 * m + c;
            a4 = a4 * m + c; a5 = a5 * m + c; a6 = a6 * m + c; a7 = a7 * m + c;
        }
        return (a0 + a1 + a2 + a3 + a4 + a5 + a6 + a7).GetElement(0);
    }

    [MethodImpl(MethodImplOptions.AggressiveOptimization)]
    private static float Sum(float[] data, int from, int to)
    {
        Vector256<float> s0 = Vector256<float>.Zero, s1 = s0, s2 = s0, s3 = s0;
        int i = from;
        for (; i + 32 <= to; i += 32)
        {
            s0 += Vector256.LoadUnsafe(ref data[i]); s1 += Vector256.LoadUnsafe(ref data[i + 8]);
            s2 += Vector256.LoadUnsafe(ref data[i + 16]); s3 += Vector256.LoadUnsafe(ref data[i + 24]);
        }
        float tail = 0f;
        for (; i < to; i++) tail += data[i];
        return (s0 + s1 + s2 + s3).GetElement(0) + tail;
    }
}
