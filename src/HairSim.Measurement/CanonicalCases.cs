using System.Diagnostics;
using System.Numerics;

namespace HairSim.Measurement;

/// <summary>Settled hanging strand: length drift and how far it is from hanging straight down (both relative to L).</summary>
public readonly record struct HangingResult(double LengthError, double MaxEdgeStretch, double Straightness);

/// <summary>Chain pinned at both ends: largest particle distance to the analytic catenary, relative to L.</summary>
public readonly record struct CatenaryResult(double ShapeError, double LengthError);

/// <summary>Small-amplitude pendulum: measured period and energy decay against the analytic ones (NaN without a length pass).</summary>
public readonly record struct PendulumResult(double Period, double AnalyticPeriod, double EnergyRatio, double AnalyticEnergyRatio)
{
    public double PeriodError => Math.Abs(Period / AnalyticPeriod - 1);
    public double EnergyError => Math.Abs(EnergyRatio / AnalyticEnergyRatio - 1);
    public bool Defined => double.IsFinite(Period);
}

/// <summary>Head collision: deepest penetration (m) and most free particles inside the head after any frame.</summary>
public readonly record struct CollisionResult(double MaxPenetration, int MaxInside, int NonFinite);

/// <summary>A moving-head run: worst edge stretch of any frame, non-finite values, mean tip drop below the root (m).</summary>
public readonly record struct MotionResult(double PeakStretch, int NonFinite, double MeanTipDrop);

/// <summary>Distance (m) of a metric to the same case converged by halving the substep; the last change seen.</summary>
public readonly record struct ConvergedError(double Error, int ReferenceSubsteps, double LastChange);

/// <summary>Run time of one frame of a batch of strands.</summary>
public readonly record struct Timing(double MicrosecondsPerFrame, double ParticleStepsPerSecond, int Particles);

/// <summary>
/// The canonical cases of the error-vs-run-time report, built on HairWorld directly (one or a few strands),
/// each measured against an analytic answer or a converged run. All lengths in metres, times in seconds.
/// </summary>
public static class CanonicalCases
{
    /// <summary>Strand length and particle count of the single-strand cases (the reference scene's strands).</summary>
    public const float StrandLength = 0.25f;
    public const int StrandParticles = 16;
    /// <summary>Pin distance of the catenary (its chain is <see cref="StrandLength"/> long).</summary>
    public const float CatenarySpan = 0.2f;
    /// <summary>Release angle of the pendulum (radians).</summary>
    public const double PendulumAmplitude = 0.1;

    // ---------------- hanging strand ----------------

    /// <summary>
    /// <paramref name="copies"/> independent 16-particle strands, roots pinned, whose rest pose hangs straight down
    /// (straight rest shape, the source's model) but which start horizontal (+x), so they swing down.
    /// </summary>
    public static HairScene HangingScene(SimulationSettings settings, int copies = 1, int particles = StrandParticles)
    {
        var w = new HairWorld(1, copies, particles);
        var pts = new Vector3[particles];
        float segment = StrandLength / (particles - 1);
        for (int s = 0; s < copies; s++)
        {
            for (int k = 0; k < particles; k++) pts[k] = new Vector3(0f, -segment * k, 0.01f * s);
            w.SetStrand(s, pts, pinned: 1, straightRestShape: true);
            for (int k = 0; k < particles; k++) w.SetPosition(w.StrandFirst[s] + k, new Vector3(segment * k, 0f, 0.01f * s));
        }
        return new HairScene(w, settings);
    }

    /// <summary>Releases a horizontal strand and measures it after <paramref name="seconds"/> (settled: the answer is a vertical line of length L).</summary>
    public static HangingResult Hanging(SimulationSettings settings, int hz, float seconds = 5f, int particles = StrandParticles)
    {
        var scene = HangingScene(settings, 1, particles);
        Run(scene, hz, seconds, null);
        var w = scene.World;
        double total = 0, maxStretch = 0, maxOff = 0;
        var root = w.GetPosition(0);
        for (int k = 1; k < particles; k++)
        {
            var p = w.GetPosition(k);
            double l = Vector3.Distance(p, w.GetPosition(k - 1));
            total += l;
            maxStretch = Max(maxStretch, Math.Abs(l / w.RestLength[k] - 1));
            double ox = p.X - root.X, oz = p.Z - root.Z;
            maxOff = Max(maxOff, Math.Sqrt(ox * ox + oz * oz));
        }
        return new HangingResult(Math.Abs(total / StrandLength - 1), maxStretch, maxOff / StrandLength);
    }

    // ---------------- catenary ----------------

    /// <summary>
    /// A chain pinned at both ends (tip pinned through InvMass = 0) whose rest pose is the analytic discrete
    /// catenary, so bending is at rest at the answer and only gravity against the length constraint shapes it.
    /// It starts with half the sag (links compressed) and must find the answer.
    /// </summary>
    public static CatenaryResult Catenary(SimulationSettings settings, int hz, float seconds = 5f)
    {
        var answer = AnalyticReferences.DiscreteCatenary(StrandParticles - 1, StrandLength, CatenarySpan);
        var w = new HairWorld(1, 1, StrandParticles);
        w.SetStrand(0, answer, pinned: 1);
        w.InvMass[StrandParticles - 1] = 0f;
        w.MarkEdited();
        for (int k = 0; k < StrandParticles; k++) w.PosY[k] *= 0.5f;
        var scene = new HairScene(w, settings);
        Run(scene, hz, seconds, null);
        double err = 0, total = 0;
        for (int k = 0; k < StrandParticles; k++)
        {
            err = Max(err, Vector3.Distance(w.GetPosition(k), answer[k]));
            if (k > 0) total += Vector3.Distance(w.GetPosition(k), w.GetPosition(k - 1));
        }
        return new CatenaryResult(err / StrandLength, Math.Abs(total / StrandLength - 1));
    }

    // ---------------- pendulum ----------------

    /// <summary>
    /// A 2-particle strand (pinned root, free tip, L = 0.25 m from pivot to mass) released at 0.1 rad, with velocity damping off
    /// so the analytic energy stays constant. Its rest pose hangs straight down. Under <see cref="BendModel.RestShape"/> the
    /// root holds the strand's direction, so it is no free pendulum and the result is undefined (NaN). The period is
    /// the mean spacing of upward zero crossings over <paramref name="periods"/> swings; energy is compared at the first
    /// and last crossing (same phase). Without a length pass nothing holds the tip: the result is undefined (NaN).
    /// </summary>
    public static PendulumResult Pendulum(SimulationSettings settings, int hz, int periods = 8)
    {
        settings = settings.Clone();
        settings.Damping = 0f; // so any energy lost is the integrator's own
        double g = settings.Gravity.Length(), d = 0, theta = PendulumAmplitude;
        double analytic = AnalyticReferences.PendulumPeriod(StrandLength, g, theta, d);
        if (settings.Length == LengthMode.None || settings.Bend == BendModel.RestShape) return new PendulumResult(double.NaN, analytic, double.NaN, double.NaN);
        var w = new HairWorld(1, 1, 2);
        w.SetStrand(0, [Vector3.Zero, new Vector3(0f, -StrandLength, 0f)], pinned: 1);
        w.SetPosition(1, new Vector3((float)(StrandLength * Math.Sin(theta)), (float)(-StrandLength * Math.Cos(theta)), 0f));
        var scene = new HairScene(w, settings);
        var sim = new HairSimulation(scene);
        float dt = 1f / hz;
        int frames = (int)Math.Ceiling((periods + 1.5) * analytic * hz);
        double prevX = w.PosX[1], prevE = Energy(w, g), firstT = double.NaN, firstE = double.NaN, lastT = double.NaN, lastE = double.NaN;
        int crossings = 0;
        for (int f = 1; f <= frames; f++)
        {
            sim.Step(dt);
            double x = w.PosX[1], e = Energy(w, g);
            if (!double.IsFinite(x) || !double.IsFinite(e)) return new PendulumResult(double.NaN, analytic, double.NaN, double.NaN);
            if (prevX < 0 && x >= 0)
            {
                double frac = prevX / (prevX - x);
                double t = (f - 1 + frac) * dt, ec = prevE + frac * (e - prevE);
                if (crossings == 0) { firstT = t; firstE = ec; }
                lastT = t; lastE = ec;
                crossings++;
            }
            prevX = x; prevE = e;
        }
        if (crossings < 2) return new PendulumResult(double.NaN, analytic, double.NaN, double.NaN);
        double span = lastT - firstT;
        return new PendulumResult(span / (crossings - 1), analytic, lastE / firstE, AnalyticReferences.PendulumEnergyRatio(d, span));
    }

    private static double Energy(HairWorld w, double g)
    {
        double vx = w.VelX[1], vy = w.VelY[1], vz = w.VelZ[1];
        return 0.5 * (vx * vx + vy * vy + vz * vz) + g * (w.PosY[1] + StrandLength);
    }

    // ---------------- head cases ----------------

    /// <summary>A small groom (12 sheets × 2 strands) on the reference head ellipsoid; 2 pinned particles per strand (1 for a 2-particle strand).</summary>
    public static GroomSettings SmallGroom(int particles = StrandParticles, int sheets = 12, int strandsPerSheet = 2) =>
        new() { SheetCount = sheets, StrandsPerSheet = strandsPerSheet, ParticlesPerStrand = particles, PinnedPerStrand = Math.Min(2, particles - 1) };

    /// <summary>The head sweeps sideways and nods for <paramref name="seconds"/>; after every frame: penetration and particles inside.</summary>
    public static CollisionResult CollisionSweep(SimulationSettings settings, int hz, float seconds = 3f)
    {
        var scene = GroomBuilder.BuildScene(SmallGroom(), settings);
        double pen = 0; int inside = 0, bad = 0;
        Run(scene, hz, seconds, HeadMotion.Sweep, (_, m) =>
        {
            pen = Max(pen, m.MaxPenetration); inside = Math.Max(inside, m.ParticlesInside); bad = Math.Max(bad, m.NonFinite);
        });
        return new CollisionResult(pen, inside, bad);
    }

    /// <summary>
    /// The head shakes "no" for <paramref name="seconds"/>: peak stretch of any frame, and the mean tip drop (tip
    /// height below its root, averaged over strands and frames; a time average, so the chaotic detail of the swing
    /// does not keep it from converging).
    /// </summary>
    public static MotionResult Shake(SimulationSettings settings, int hz, float seconds = 2f)
    {
        var scene = GroomBuilder.BuildScene(SmallGroom(), settings);
        var w = scene.World;
        double peak = 0, drop = 0; int bad = 0, frames = 0;
        Run(scene, hz, seconds, HeadMotion.Shake, (_, m) =>
        {
            peak = Max(peak, m.MaxEdgeStretch); bad = Math.Max(bad, m.NonFinite);
            double sum = 0;
            for (int s = 0; s < w.StrandCount; s++) sum += w.PosY[w.RootIndex(s)] - w.PosY[w.TipIndex(s)];
            drop += sum / w.StrandCount; frames++;
        });
        return new MotionResult(peak, bad, drop / frames);
    }

    /// <summary>
    /// The hair settles 0.5 s, then the head jumps 1 m and turns 120° in one frame (a respawn), then holds still 1 s.
    /// Peak stretch from the jump on.
    /// </summary>
    public static MotionResult Teleport(SimulationSettings settings, int hz)
    {
        var scene = GroomBuilder.BuildScene(SmallGroom(), settings);
        var jumped = new RigidTransform(new Vector3(0.8f, 0.2f, 0.55f), Quaternion.CreateFromAxisAngle(Vector3.UnitY, 2.1f));
        double peak = 0; int bad = 0;
        Run(scene, hz, 0.5f, null);
        Run(scene, hz, 1f, _ => jumped, (_, m) => { peak = Max(peak, m.MaxEdgeStretch); bad = Math.Max(bad, m.NonFinite); });
        return new MotionResult(peak, bad, double.NaN);
    }

    /// <summary>
    /// The shake's mean tip drop against the same case converged: substeps are doubled (the step halved) until the
    /// metric changes by less than <paramref name="tolerance"/> metres between successive runs, or 256 substeps.
    /// <paramref name="dropAtSubsteps"/> may supply (cached) tip drops of the same settings at other substep counts.
    /// </summary>
    public static ConvergedError ShakeAgainstConverged(SimulationSettings settings, int hz, double tolerance = 1e-3, Func<int, double>? dropAtSubsteps = null)
    {
        dropAtSubsteps ??= n =>
        {
            var s = settings.Clone();
            s.Substeps = n;
            return Shake(s, hz).MeanTipDrop;
        };
        double own = dropAtSubsteps(settings.Substeps), previous = own;
        int substeps = settings.Substeps;
        double change = double.PositiveInfinity;
        while (substeps * 2 <= 256)
        {
            substeps *= 2;
            double next = dropAtSubsteps(substeps);
            change = Math.Abs(next - previous);
            previous = next;
            if (change < tolerance) break;
        }
        return new ConvergedError(Math.Abs(own - previous), substeps, change);
    }

    // ---------------- run time ----------------

    /// <summary>
    /// Run time per frame of a groom of about <paramref name="strands"/> 16-particle strands on the head (with collision)
    /// while the head shakes: <paramref name="warmup"/> untimed frames, then <paramref name="batches"/> timed batches of
    /// <paramref name="frames"/> frames; the fastest batch counts (other work on the machine only ever slows a batch down).
    /// </summary>
    public static Timing Time(SimulationSettings settings, int hz, IThreadDispatcher? dispatcher, int strands = 1000, int frames = 20, int batches = 3, int warmup = 10)
    {
        var scene = GroomBuilder.BuildScene(SmallGroom(StrandParticles, Math.Max(1, strands / 20), 20), settings);
        var sim = new HairSimulation(scene, dispatcher: dispatcher);
        float dt = 1f / hz;
        int f = 0;
        for (; f < warmup; f++) sim.Step(dt, HeadMotion.Shake((f + 1) * dt));
        double best = double.PositiveInfinity;
        for (int b = 0; b < batches; b++)
        {
            var sw = Stopwatch.StartNew();
            for (int k = 0; k < frames; k++, f++) sim.Step(dt, HeadMotion.Shake((f + 1) * dt));
            best = Math.Min(best, sw.Elapsed.TotalSeconds / frames);
        }
        int particles = scene.World.ParticleCount;
        return new Timing(best * 1e6, particles * settings.Substeps / best, particles);
    }

    // ---------------- helpers ----------------

    /// <summary>Steps a scene for <paramref name="seconds"/>, the head following <paramref name="head"/>(t) if given; optionally measures after each frame.</summary>
    public static void Run(HairScene scene, int hz, float seconds, Func<float, RigidTransform>? head, Action<int, WorldMetrics>? afterFrame = null)
    {
        var sim = new HairSimulation(scene);
        float dt = 1f / hz;
        int frames = (int)MathF.Round(seconds * hz);
        for (int f = 0; f < frames; f++)
        {
            float t = (f + 1) * dt;
            if (head != null) sim.Step(dt, head(t)); else sim.Step(dt);
            afterFrame?.Invoke(f, WorldMetrics.Measure(scene));
        }
    }

    /// <summary>Max that keeps NaN (a non-finite run must not look accurate).</summary>
    private static double Max(double a, double b) => double.IsNaN(a) || double.IsNaN(b) ? double.NaN : Math.Max(a, b);
}
