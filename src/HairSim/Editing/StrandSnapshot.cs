namespace HairSim.Editing;

/// <summary>
/// Every buffer value and the live count of some strands (their full capacity), plus the head pose: what an
/// edit needs to be undone bit for bit. Its size is what an undo step costs, so it only holds affected strands.
/// </summary>
public sealed class StrandSnapshot
{
    private readonly int[] _strands;
    private readonly int[] _counts;
    private readonly float[] _data;
    private readonly RigidTransform _head;

    private StrandSnapshot(int[] strands, int[] counts, float[] data, RigidTransform head)
    {
        _strands = strands; _counts = counts; _data = data; _head = head;
    }

    public IReadOnlyList<int> Strands => _strands;

    /// <summary>Bytes held by the snapshot's arrays.</summary>
    public long Bytes => 4L * (_strands.Length + _counts.Length + _data.Length);

    public static StrandSnapshot Capture(HairWorld w, int[] strands)
    {
        long particles = 0;
        foreach (int s in strands) particles += w.StrandCapacity[s];
        var buffers = w.Buffers();
        var data = new float[particles * buffers.Length];
        var counts = new int[strands.Length];
        int o = 0;
        foreach (var b in buffers)
            foreach (int s in strands)
            {
                Array.Copy(b, w.StrandFirst[s], data, o, w.StrandCapacity[s]);
                o += w.StrandCapacity[s];
            }
        for (int j = 0; j < strands.Length; j++) counts[j] = w.StrandParticleCount[strands[j]];
        return new StrandSnapshot((int[])strands.Clone(), counts, data, w.Head);
    }

    /// <summary>
    /// Puts the strands back. If the head has moved since the capture, positions and velocities are carried
    /// rigidly with it (so a late undo does not fling hair); with the head where it was, the restore is exact.
    /// </summary>
    public void Restore(HairWorld w)
    {
        var buffers = w.Buffers();
        int o = 0;
        foreach (var b in buffers)
            foreach (int s in _strands)
            {
                Array.Copy(_data, o, b, w.StrandFirst[s], w.StrandCapacity[s]);
                o += w.StrandCapacity[s];
            }
        for (int j = 0; j < _strands.Length; j++) w.StrandParticleCount[_strands[j]] = _counts[j];
        if (!w.Head.Equals(_head))
        {
            var delta = RigidTransform.Delta(_head, w.Head);
            foreach (int s in _strands)
                for (int i = w.StrandFirst[s], end = i + w.StrandCapacity[s]; i < end; i++)
                {
                    w.SetPosition(i, delta.TransformPoint(w.GetPosition(i)));
                    w.SetVelocity(i, delta.TransformDirection(w.GetVelocity(i)));
                }
        }
        w.MarkEdited();
    }
}
