namespace HairSim.Measurement;

/// <summary>Every canonical case measured for one solver configuration, plus its run time.</summary>
public sealed record ReportRow(
    SolverConfiguration Config,
    HangingResult Hanging,
    CatenaryResult Catenary,
    PendulumResult Pendulum,
    CollisionResult Collision,
    MotionResult Shake,
    ConvergedError ShakeConverged,
    MotionResult Teleport,
    HeldShapeResult Held,
    Timing Timing)
{
    /// <summary>Length error of the settled hanging strand: the figure the defaults must keep under 0.5 %.</summary>
    public double LengthError => Hanging.LengthError;

    /// <summary>
    /// The error the Pareto front ranks by, for hair with free tips: the worst of the relative errors of the hanging
    /// strand (length, straightness), the shake and the teleport (peak stretch), the pendulum period (where a
    /// pendulum exists) and the held shapes (a straight horizontal, an upward arc and a curl: farthest particle from
    /// its rest place, share of the length; a style that does not hold is an error of a styling tool). Reported beside it but not ranked: the catenary (a second pin, which hair does not have and
    /// follow-the-leader cannot hold), the pendulum's energy loss (small next to the default damping), the converged
    /// shake. NaN if any case went non-finite.
    /// </summary>
    public double Error
    {
        get
        {
            double e = Max(Hanging.LengthError, Hanging.Straightness);
            e = Max(e, Shake.PeakStretch);
            e = Max(e, Teleport.PeakStretch);
            if (Pendulum.Defined) e = Max(e, Pendulum.PeriodError);
            e = Max(e, Held.WorstError);
            if (NonFinite > 0) return double.NaN;
            return e;
        }
    }

    public int NonFinite => Collision.NonFinite + Shake.NonFinite + Teleport.NonFinite + Held.NonFinite +
        (double.IsFinite(Hanging.LengthError) ? 0 : 1) + (double.IsFinite(Catenary.ShapeError) ? 0 : 1);

    private static double Max(double a, double b) => double.IsNaN(a) || double.IsNaN(b) ? double.NaN : Math.Max(a, b);
}

/// <summary>The configurations compared and the measurement of one of them.</summary>
public static class ErrorReport
{
    public const int Hz = 60;

    /// <summary>
    /// The default bend model and limp hair over substeps and length pass; the source's triple shape matching with
    /// Müller integration over α, substeps and length pass, and with the literal force over its spring rate (1/s²),
    /// substeps and length pass. <paramref name="quick"/> keeps a handful for a fast check.
    /// </summary>
    public static List<SolverConfiguration> Configurations(bool quick)
    {
        var list = new List<SolverConfiguration>();
        foreach (int n in quick ? [1, 4] : new[] { 1, 2, 4, 8, 16 })
        {
            list.Add(SolverConfiguration.RestShape(n, LengthMode.FollowTheLeader));
            if (!quick) list.Add(SolverConfiguration.Limp(n, LengthMode.FollowTheLeader));
        }
        float[] alphas = quick ? [1f] : [0.25f, 0.5f, 1f];
        int[] substeps = quick ? [1, 4, 16] : [1, 2, 4, 8, 16];
        (LengthMode, int)[] lengths = quick
            ? [(LengthMode.None, 4), (LengthMode.FollowTheLeader, 4), (LengthMode.Pbd, 4)]
            : [(LengthMode.None, 4), (LengthMode.FollowTheLeader, 4), (LengthMode.Pbd, 1), (LengthMode.Pbd, 4)];
        foreach (float a in alphas)
            foreach (int n in substeps)
                foreach (var (len, it) in lengths)
                    list.Add(new SolverConfiguration(ShapeMatchMode.Muller, a, n, len, it));
        float[] rates = quick ? [1000f] : [10f, 100f, 1000f];
        int[] literalSubsteps = quick ? [4] : [1, 4, 16];
        foreach (float a in rates)
            foreach (int n in literalSubsteps)
                foreach (var len in quick ? new[] { LengthMode.None } : [LengthMode.None, LengthMode.FollowTheLeader])
                    list.Add(new SolverConfiguration(ShapeMatchMode.LiteralForce, a, n, len));
        return list;
    }

    /// <summary>
    /// Runs every canonical case for one configuration (settings = defaults with the configuration applied), without
    /// timing it (see <see cref="Time"/>): these runs are deterministic and may run in parallel.
    /// <paramref name="shakeCache"/> keeps the shake's tip drop per configuration across calls (the convergence series).
    /// </summary>
    public static ReportRow MeasureErrors(SolverConfiguration config, SolverPath path, System.Collections.Concurrent.ConcurrentDictionary<SolverConfiguration, double> shakeCache)
    {
        var st = Settings(config, path);
        return new ReportRow(
            config,
            CanonicalCases.Hanging(st, Hz),
            CanonicalCases.Catenary(st, Hz),
            CanonicalCases.Pendulum(st, Hz),
            CanonicalCases.CollisionSweep(st, Hz),
            CanonicalCases.Shake(st, Hz),
            // Configurations differing only in substeps share the runs of the convergence series.
            CanonicalCases.ShakeAgainstConverged(st, Hz, 1e-3, n => shakeCache.GetOrAdd(config with { Substeps = n }, key =>
            {
                var s = st.Clone();
                s.Substeps = n;
                return CanonicalCases.Shake(s, Hz).MeanTipDrop;
            })),
            CanonicalCases.Teleport(st, Hz),
            HeldShapeCases.Worst(st, Hz),
            default);
    }

    /// <summary>Times one configuration (run this alone on the machine, one configuration after another).</summary>
    public static Timing Time(SolverConfiguration config, SolverPath path, IThreadDispatcher? dispatcher, bool quick) =>
        CanonicalCases.Time(Settings(config, path), Hz, dispatcher, frames: quick ? 10 : 20);

    private static SimulationSettings Settings(SolverConfiguration config, SolverPath path)
    {
        var st = config.ToSettings(null, path);
        st.Guards = false; // measure exactly this configuration (the guards would raise 1 or 2 substeps to 4 at 60 Hz)
        return st;
    }
}
