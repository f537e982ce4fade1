namespace HairSim;

/// <summary>Why a strand was put back at its rest pose at the end of a frame (flags: both may hold).</summary>
[Flags]
public enum StrandResetReason : byte
{
    None = 0,
    /// <summary>A particle's position was NaN or ±∞.</summary>
    NonFinitePosition = 1,
    /// <summary>A particle's velocity was NaN or ±∞.</summary>
    NonFiniteVelocity = 2,
}

/// <summary>
/// What the last frame had to contain: the strands that held a non-finite position or velocity when the step ended
/// (a custom system or a bug wrote one) and were reset to their rest pose on the head, at rest, so the value could not
/// spread and the rest of the scene stepped on. Owned and reused by the pipeline: nothing is allocated per frame, and
/// the next frame overwrites it (copy what you keep). <see cref="HairSimulation.LastFrameReport"/> gives the last one.
/// </summary>
public sealed class FrameReport
{
    /// <summary>At most this many reset strands are named per frame (the count is always exact).</summary>
    public const int MaxListed = 64;

    private readonly int[] _strands = new int[MaxListed];
    private readonly StrandResetReason[] _reasons = new StrandResetReason[MaxListed];

    /// <summary>An empty report (before the first frame).</summary>
    public static FrameReport Empty { get; } = new();

    /// <summary>Strands reset in the frame (each counted once, however many of its particles were non-finite).</summary>
    public int StrandsReset { get; private set; }

    /// <summary>The union of the reasons of every reset strand.</summary>
    public StrandResetReason Reasons { get; private set; }

    /// <summary>The first <see cref="MaxListed"/> reset strands, in increasing order.</summary>
    public ReadOnlySpan<int> ResetStrands => _strands.AsSpan(0, Math.Min(StrandsReset, MaxListed));

    /// <summary>Why each strand of <see cref="ResetStrands"/> was reset (same order).</summary>
    public ReadOnlySpan<StrandResetReason> ResetReasons => _reasons.AsSpan(0, Math.Min(StrandsReset, MaxListed));

    /// <summary>Whether more strands were reset than <see cref="ResetStrands"/> names.</summary>
    public bool Truncated => StrandsReset > MaxListed;

    internal void Clear() { StrandsReset = 0; Reasons = StrandResetReason.None; }

    internal void Add(int strand, StrandResetReason reason)
    {
        if (StrandsReset < MaxListed) { _strands[StrandsReset] = strand; _reasons[StrandsReset] = reason; }
        StrandsReset++;
        Reasons |= reason;
    }

    public override string ToString() => StrandsReset == 0 ? "FrameReport { no strand reset }"
        : $"FrameReport {{ {StrandsReset} strand(s) reset ({Reasons}): {string.Join(", ", ResetStrands.ToArray())}{(Truncated ? ", …" : "")} }}";
}
