namespace HairSim.Editing;

/// <summary>Reset (rest pose, at rest) or regrow (copy strand data from a groom, then reset) of some strands.</summary>
internal sealed class ResetCommand : EditCommand
{
    private readonly HairWorld? _groom;

    public ResetCommand(HairWorld world, int[] strands, HairWorld? groom) : base(world, groom == null ? "Reset" : "Regrow", strands)
    {
        _groom = groom;
    }

    protected override void Execute(HairWorld w)
    {
        var head = w.Head;
        float[][] dst = w.Buffers(), src = _groom?.Buffers() ?? dst;
        foreach (int s in Strands)
        {
            int first = w.StrandFirst[s], cap = w.StrandCapacity[s];
            if (_groom != null)
            {
                for (int b = 0; b < dst.Length; b++) Array.Copy(src[b], first, dst[b], first, cap);
                w.StrandParticleCount[s] = _groom.StrandParticleCount[s];
            }
            for (int i = first; i < first + cap; i++)
            {
                w.SetPosition(i, head.TransformPoint(w.GetRest(i)));
                w.VelX[i] = w.VelY[i] = w.VelZ[i] = 0f;
            }
        }
    }
}
