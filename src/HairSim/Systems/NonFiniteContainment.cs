using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;

namespace HairSim;

/// <summary>
/// A system that keeps per-strand state from one frame to the next (friction's start positions): told when the
/// pipeline resets a strand, so the state of the strand before the reset (possibly NaN) is not used again.
/// Called on the job thread that owns the strand.
/// </summary>
internal interface IStrandResetListener
{
    void StrandReset(HairWorld world, int strand);
}

/// <summary>
/// A system that keeps per-particle state from one substep to the next (friction's start positions), told when a
/// system outside the substeps moved a strand (strand contacts at the end of a pass), so it takes the new positions as
/// where the strand now is rather than as motion of the next substep.
/// </summary>
internal interface IStrandMovedListener
{
    void StrandMoved(HairWorld world, int strand);
}

/// <summary>
/// The end-of-frame containment of non-finite values (issue 15): every substep job scans the positions and velocities of
/// its own strands right after stepping them (still in its core's cache), a SIMD pass over the six buffers that looks
/// strand by strand only when the pass finds something. A strand holding a NaN or ±∞ is put back at its rest pose
/// under the frame's final head pose, at rest, and marked; the marks become the frame's <see cref="FrameReport"/> on the
/// stepping thread. Other strands are untouched, so they step on bit for bit as if nothing had happened. Nothing is
/// allocated per frame.
/// </summary>
internal sealed class NonFiniteContainment
{
    private readonly byte[] _marks;
    private readonly IStrandResetListener[] _listeners;
    private int _found;

    public NonFiniteContainment(HairWorld world, IReadOnlyList<IHairSystem> systems)
    {
        _marks = new byte[world.StrandCount];
        var listeners = new List<IStrandResetListener>();
        foreach (var s in systems) if (s is IStrandResetListener l) listeners.Add(l);
        _listeners = listeners.ToArray();
    }

    /// <summary>Scans strands [begin, end) and resets those holding a non-finite value (any thread; jobs own disjoint strands).</summary>
    public void Scan(HairWorld w, in RigidTransform head, int begin, int end)
    {
        if (begin >= end) return;
        // Strands are laid out back to back, so a range of strands is one range of particles.
        int from = w.StrandFirst[begin], to = w.StrandFirst[end - 1] + w.StrandCapacity[end - 1];
        if (AllFinite(w.PosX, from, to) && AllFinite(w.PosY, from, to) && AllFinite(w.PosZ, from, to) &&
            AllFinite(w.VelX, from, to) && AllFinite(w.VelY, from, to) && AllFinite(w.VelZ, from, to)) return;
        ResetNonFinite(w, head, begin, end);
    }

    /// <summary>
    /// Resets the strands of [begin, end) that hold a non-finite value, strand by strand: after a scan found one (the
    /// chunk runner scans a chunk's rows itself, in L1, before storing them; <see cref="Scan"/> the world's buffers).
    /// </summary>
    public void ResetNonFinite(HairWorld w, in RigidTransform head, int begin, int end)
    {
        for (int s = begin; s < end; s++)
        {
            var reason = Check(w, s);
            if (reason == StrandResetReason.None) continue;
            Reset(w, s, head);
            foreach (var l in _listeners) l.StrandReset(w, s);
            _marks[s] |= (byte)reason;
            Volatile.Write(ref _found, 1);
        }
    }

    /// <summary>Fills <paramref name="report"/> with the strands marked since the last call (stepping thread, after the join).</summary>
    public void Collect(FrameReport report)
    {
        report.Clear();
        if (Volatile.Read(ref _found) == 0) return;
        _found = 0;
        for (int s = 0; s < _marks.Length; s++)
        {
            if (_marks[s] == 0) continue;
            report.Add(s, (StrandResetReason)_marks[s]);
            _marks[s] = 0;
        }
    }

    /// <summary>Why strand s must be reset: a non-finite position or velocity among its particles (all of its capacity: particles past a cut come back with an undo).</summary>
    private static StrandResetReason Check(HairWorld w, int s)
    {
        int from = w.StrandFirst[s], to = from + w.StrandCapacity[s];
        var reason = StrandResetReason.None;
        if (!AllFinite(w.PosX, from, to) || !AllFinite(w.PosY, from, to) || !AllFinite(w.PosZ, from, to)) reason |= StrandResetReason.NonFinitePosition;
        if (!AllFinite(w.VelX, from, to) || !AllFinite(w.VelY, from, to) || !AllFinite(w.VelZ, from, to)) reason |= StrandResetReason.NonFiniteVelocity;
        return reason;
    }

    /// <summary>Strand s at its rest pose under <paramref name="head"/>, at rest (what <see cref="HairWorld.ResetToRest"/> does for one strand).</summary>
    internal static void Reset(HairWorld w, int s, in RigidTransform head)
    {
        int first = w.StrandFirst[s], cap = w.StrandCapacity[s];
        for (int i = first; i < first + cap; i++)
        {
            w.PutPosition(i, head.TransformPoint(new Vector3(w.RestX[i], w.RestY[i], w.RestZ[i])));
            w.VelX[i] = w.VelY[i] = w.VelZ[i] = 0f;
        }
    }

    /// <summary>
    /// Whether a[from..to) holds only finite values: x − x is 0 for every finite x and NaN for NaN and ±∞, and a NaN
    /// stays NaN through the sums, so one comparison per block of four vectors decides.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    internal static bool AllFinite(float[] a, int from, int to)
    {
        var span = a.AsSpan(from, to - from);
        int width = Vector<float>.Count, i = 0, n = span.Length;
        ref float r = ref MemoryMarshal.GetReference(span);
        var acc0 = Vector<float>.Zero; var acc1 = Vector<float>.Zero;
        for (; i <= n - 4 * width; i += 4 * width)
        {
            var x0 = Load(ref r, i); var x1 = Load(ref r, i + width); var x2 = Load(ref r, i + 2 * width); var x3 = Load(ref r, i + 3 * width);
            acc0 += (x0 - x0) + (x1 - x1);
            acc1 += (x2 - x2) + (x3 - x3);
        }
        for (; i <= n - width; i += width) { var x = Load(ref r, i); acc0 += x - x; }
        acc0 += acc1;
        if (!Vector.EqualsAll(acc0, acc0)) return false; // NaN ≠ NaN
        for (; i < n; i++) if (!float.IsFinite(Unsafe.Add(ref r, i))) return false;
        return true;
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static Vector<float> Load(ref float r, int i) => Unsafe.ReadUnaligned<Vector<float>>(ref Unsafe.As<float, byte>(ref Unsafe.Add(ref r, i)));
}
