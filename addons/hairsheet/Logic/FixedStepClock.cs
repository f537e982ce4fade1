namespace HairSheet.Logic;

/// <summary>
/// Frame time → whole fixed hair steps. Leftover time carries to the next frame; after a hitch at most
/// MaxStepsPerFrame steps run and the rest is dropped, so a slow frame cannot snowball into slower ones.
/// </summary>
public sealed class FixedStepClock
{
    private double _accumulated;

    public FixedStepClock(double stepSeconds, int maxStepsPerFrame = 4)
    {
        if (!double.IsFinite(stepSeconds) || stepSeconds <= 0 || stepSeconds > 1)
            throw new ArgumentOutOfRangeException(nameof(stepSeconds), stepSeconds, "The hair step must be in (0, 1] s.");
        if (maxStepsPerFrame < 1) throw new ArgumentOutOfRangeException(nameof(maxStepsPerFrame), maxStepsPerFrame, "At least one step per frame.");
        Step = stepSeconds;
        MaxStepsPerFrame = maxStepsPerFrame;
    }

    public double Step { get; }
    public int MaxStepsPerFrame { get; }
    public double Accumulated => _accumulated;
    public long DroppedSteps { get; private set; }

    /// <summary>Adds elapsed time; returns how many fixed steps to run now. Negative or non-finite time counts as none.</summary>
    public int Advance(double elapsed)
    {
        if (!double.IsFinite(elapsed) || elapsed <= 0) return 0;
        _accumulated += elapsed;
        long due = (long)Math.Floor(_accumulated / Step + 1e-9);
        int run = (int)Math.Min(due, MaxStepsPerFrame);
        _accumulated = Math.Max(0, _accumulated - run * Step);
        if (due > run)
        {
            DroppedSteps += due - run;
            _accumulated -= (due - run) * Step;
            if (_accumulated < 0) _accumulated = 0;
        }
        return run;
    }

    public void Reset() => _accumulated = 0;
}
