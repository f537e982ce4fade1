using System.Numerics;

namespace HairSim.Editing;

/// <summary>Which strands a cut reaches.</summary>
public enum CutReach
{
    /// <summary>Only strand points not hidden behind the head's colliders (what the user sees).</summary>
    VisibleOnly,
    /// <summary>Every strand under the stroke, through the head (front and back layers).</summary>
    AllThrough,
}

public sealed class CutOptions
{
    public CutReach Reach { get; set; } = CutReach.VisibleOnly;
    /// <summary>A strand keeps at least this much rest length from its root (metres); crossings nearer the root are skipped.</summary>
    public float MinRemainingLength { get; set; } = 0.01f;

    public void Validate()
    {
        if (!Enum.IsDefined(Reach)) throw new ArgumentOutOfRangeException(nameof(Reach));
        if (!float.IsFinite(MinRemainingLength) || MinRemainingLength < 0f || MinRemainingLength > 100f)
            throw new ArgumentOutOfRangeException(nameof(MinRemainingLength), MinRemainingLength, "Minimum remaining length must be in 0 … 100 m.");
    }
}

/// <summary>One strand's cut: its new live count and the new tip (world position, head-space rest point, rest length).</summary>
public readonly record struct StrandCut(int Strand, int NewCount, Vector3 Tip, Vector3 TipVelocity, Vector3 TipRest, float TipRestLength);

/// <summary>
/// A planned cut (SPEC A.5, Algorithm 2). Applying it lowers each cut strand's live count, puts the new tip at
/// the crossing, sets its rest length and rest point so it is at rest, and refreshes the strand's rest shape.
/// Particles beyond the tip stay in the buffers (capacity), so undo and regrow can bring them back.
/// </summary>
public sealed class CutCommand : EditCommand
{
    private readonly StrandCut[] _cuts;

    internal CutCommand(HairWorld world, StrandCut[] cuts) : base(world, "Cut", Array.ConvertAll(cuts, c => c.Strand))
    {
        _cuts = cuts;
    }

    public IReadOnlyList<StrandCut> Cuts => _cuts;
    protected override long PlanBytes => _cuts.Length * 64L;

    protected override void Execute(HairWorld w)
    {
        foreach (var c in _cuts)
        {
            int s = c.Strand, tip = w.StrandFirst[s] + c.NewCount - 1;
            bool straight = IsStraight(w, s);
            w.StrandParticleCount[s] = c.NewCount;
            w.SetPosition(tip, c.Tip);
            w.SetVelocity(tip, c.TipVelocity);
            w.RestX[tip] = c.TipRest.X; w.RestY[tip] = c.TipRest.Y; w.RestZ[tip] = c.TipRest.Z;
            w.RestLength[tip] = c.TipRestLength;
            if (straight) RestShape.SetStraight(w, s);
            else RestShape.SetFromRestPose(w, s);
        }
    }

    /// <summary>A strand whose rest shape has no bend anywhere keeps the source's straight (bit-exact) model.</summary>
    internal static bool IsStraight(HairWorld w, int s)
    {
        int first = w.StrandFirst[s];
        for (int k = 0; k < w.StrandParticleCount[s]; k++) if (w.ShapeBend[first + k] != 0f) return false;
        return true;
    }
}
