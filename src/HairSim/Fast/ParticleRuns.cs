using System.Numerics;
using System.Runtime.CompilerServices;

namespace HairSim.Fast;

/// <summary>A per-particle kernel over one SIMD chunk of Width particles, given refs to the chunk's first element.</summary>
internal interface IParticleKernel
{
    void Chunk(ref float px, ref float py, ref float pz, ref float vx, ref float vy, ref float vz,
               ref float invMass, ref float rx, ref float ry, ref float rz);
}

/// <summary>
/// A kernel that also has a 16-lane (AVX-512) chunk doing the same arithmetic in the same order as
/// <see cref="IParticleKernel.Chunk"/>, so results do not depend on which one ran.
/// </summary>
internal interface IWideParticleKernel : IParticleKernel
{
    void Chunk16(ref float px, ref float py, ref float pz, ref float vx, ref float vy, ref float vz,
                 ref float invMass, ref float rx, ref float ry, ref float rz);
}

/// <summary>
/// Runs a per-particle kernel over the live particles of strands [begin, end). Strands that are not cut are
/// contiguous with the next strand, so consecutive whole strands are merged into one run and only the end of a
/// run needs a partial chunk. That partial chunk is copied into a padded stack buffer (padding lanes have
/// InvMass 0, so kernels leave them alone) and only its live lanes are copied back: a run never writes past its
/// last live particle, which may belong to another thread's block.
/// </summary>
internal static class ParticleRuns
{
    /// <summary>Whether this CPU runs <see cref="IWideParticleKernel.Chunk16"/> natively.</summary>
    public static bool WideAvailable => FastPathInfo.Avx512;

    /// <summary>
    /// As <see cref="ForEachLive{TKernel}(HairWorld, int, int, ref TKernel)"/>, but whole 16-particle chunks go through the kernel's 16-lane chunk
    /// when <paramref name="wide"/> (the rest of a run through the 8-lane one).
    /// </summary>
    public static void ForEachLiveWide<TKernel>(HairWorld w, int begin, int end, ref TKernel kernel, bool wide) where TKernel : struct, IWideParticleKernel =>
        ForEachLiveWide(w, begin, end, ref kernel, wide, w.RestX, w.RestY, w.RestZ);

    /// <summary>
    /// As above, with the kernel's last three inputs (rx, ry, rz) taken from other per-particle arrays than the rest
    /// positions (friction: each particle's position at the substep's start).
    /// </summary>
    public static void ForEachLiveWide<TKernel>(HairWorld w, int begin, int end, ref TKernel kernel, bool wide, float[] auxX, float[] auxY, float[] auxZ)
        where TKernel : struct, IWideParticleKernel
    {
        if (!wide) { ForEachLive(w, begin, end, ref kernel, auxX, auxY, auxZ); return; }
        int width = Vector<float>.Count;
        Span<float> tail = stackalloc float[10 * width];
        for (int s = begin; NextRun(w, ref s, end, out int start, out int stop);)
        {
            int i = start;
            ref float px = ref Simd.At(w.PosX, 0), py = ref Simd.At(w.PosY, 0), pz = ref Simd.At(w.PosZ, 0);
            ref float vx = ref Simd.At(w.VelX, 0), vy = ref Simd.At(w.VelY, 0), vz = ref Simd.At(w.VelZ, 0);
            ref float m = ref Simd.At(w.InvMass, 0), rx = ref Simd.At(auxX, 0), ry = ref Simd.At(auxY, 0), rz = ref Simd.At(auxZ, 0);
            for (; i <= stop - 16; i += 16)
                kernel.Chunk16(ref Unsafe.Add(ref px, i), ref Unsafe.Add(ref py, i), ref Unsafe.Add(ref pz, i),
                    ref Unsafe.Add(ref vx, i), ref Unsafe.Add(ref vy, i), ref Unsafe.Add(ref vz, i),
                    ref Unsafe.Add(ref m, i), ref Unsafe.Add(ref rx, i), ref Unsafe.Add(ref ry, i), ref Unsafe.Add(ref rz, i));
            if (i < stop) RunNarrow(w, i, stop, ref kernel, tail, auxX, auxY, auxZ);
        }
    }

    /// <summary>The 8-lane remainder of a run (not inlined: it keeps the 16-lane loop's inlining budget free).</summary>
    [MethodImpl(MethodImplOptions.NoInlining)]
    private static void RunNarrow<TKernel>(HairWorld w, int start, int stop, ref TKernel kernel, Span<float> tail, float[] auxX, float[] auxY, float[] auxZ)
        where TKernel : struct, IParticleKernel =>
        Run(w, start, stop, ref kernel, tail, auxX, auxY, auxZ);

    public static void ForEachLive<TKernel>(HairWorld w, int begin, int end, ref TKernel kernel) where TKernel : struct, IParticleKernel =>
        ForEachLive(w, begin, end, ref kernel, w.RestX, w.RestY, w.RestZ);

    private static void ForEachLive<TKernel>(HairWorld w, int begin, int end, ref TKernel kernel, float[] auxX, float[] auxY, float[] auxZ)
        where TKernel : struct, IParticleKernel
    {
        int width = Vector<float>.Count;
        Span<float> tail = stackalloc float[10 * width];
        for (int s = begin; NextRun(w, ref s, end, out int start, out int stop);) Run(w, start, stop, ref kernel, tail, auxX, auxY, auxZ);
    }

    /// <summary>
    /// The next run of live particles from strand <paramref name="s"/> (advanced past it): a strand and the uncut
    /// strands before it, which are contiguous with their successors. False when no strands are left.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static bool NextRun(HairWorld w, ref int s, int end, out int start, out int stop)
    {
        start = stop = 0;
        if (s >= end) return false;
        int[] firsts = w.StrandFirst, counts = w.StrandParticleCount, caps = w.StrandCapacity;
        start = firsts[s];
        stop = start + counts[s];
        while (counts[s] == caps[s] && s + 1 < end)
        {
            s++;
            stop = firsts[s] + counts[s];
        }
        s++;
        return true;
    }

    private static void Run<TKernel>(HairWorld w, int start, int stop, ref TKernel kernel, Span<float> tail, float[] auxX, float[] auxY, float[] auxZ)
        where TKernel : struct, IParticleKernel
    {
        int width = Vector<float>.Count;
        int i = start;
        ref float px = ref Simd.At(w.PosX, 0), py = ref Simd.At(w.PosY, 0), pz = ref Simd.At(w.PosZ, 0);
        ref float vx = ref Simd.At(w.VelX, 0), vy = ref Simd.At(w.VelY, 0), vz = ref Simd.At(w.VelZ, 0);
        ref float m = ref Simd.At(w.InvMass, 0), rx = ref Simd.At(auxX, 0), ry = ref Simd.At(auxY, 0), rz = ref Simd.At(auxZ, 0);
        for (; i <= stop - width; i += width)
            kernel.Chunk(ref Unsafe.Add(ref px, i), ref Unsafe.Add(ref py, i), ref Unsafe.Add(ref pz, i),
                ref Unsafe.Add(ref vx, i), ref Unsafe.Add(ref vy, i), ref Unsafe.Add(ref vz, i),
                ref Unsafe.Add(ref m, i), ref Unsafe.Add(ref rx, i), ref Unsafe.Add(ref ry, i), ref Unsafe.Add(ref rz, i));
        int r = stop - i;
        if (r <= 0) return;
        tail.Clear();
        CopyIn(w.PosX, i, r, tail, 0); CopyIn(w.PosY, i, r, tail, 1); CopyIn(w.PosZ, i, r, tail, 2);
        CopyIn(w.VelX, i, r, tail, 3); CopyIn(w.VelY, i, r, tail, 4); CopyIn(w.VelZ, i, r, tail, 5);
        CopyIn(w.InvMass, i, r, tail, 6); CopyIn(auxX, i, r, tail, 7); CopyIn(auxY, i, r, tail, 8); CopyIn(auxZ, i, r, tail, 9);
        kernel.Chunk(ref tail[0], ref tail[width], ref tail[2 * width], ref tail[3 * width], ref tail[4 * width], ref tail[5 * width],
            ref tail[6 * width], ref tail[7 * width], ref tail[8 * width], ref tail[9 * width]);
        CopyOut(tail, 0, w.PosX, i, r); CopyOut(tail, 1, w.PosY, i, r); CopyOut(tail, 2, w.PosZ, i, r);
        CopyOut(tail, 3, w.VelX, i, r); CopyOut(tail, 4, w.VelY, i, r); CopyOut(tail, 5, w.VelZ, i, r);
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void CopyIn(float[] a, int i, int r, Span<float> tail, int field) =>
        a.AsSpan(i, r).CopyTo(tail.Slice(field * Vector<float>.Count, r));

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void CopyOut(Span<float> tail, int field, float[] a, int i, int r) =>
        tail.Slice(field * Vector<float>.Count, r).CopyTo(a.AsSpan(i, r));
}
