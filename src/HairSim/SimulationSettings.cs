using System.Numerics;

namespace HairSim;

/// <summary>How shape-matching goals move particles.</summary>
public enum ShapeMatchMode
{
    /// <summary>Müller et al. 2005: v += α(g − x)/h + h·f/m; x += h·v. Stable for α in [0, 1].</summary>
    Muller,
    /// <summary>The source's literal force: a = gravity + α(g − x), semi-implicit Euler. For comparison.</summary>
    LiteralForce,
}

/// <summary>The inextensibility pass run after integration (the source has none).</summary>
public enum LengthMode
{
    None,
    /// <summary>Dynamic follow-the-leader (Müller et al. 2012): one root-to-tip sweep, exact lengths.</summary>
    FollowTheLeader,
    /// <summary>Position-based distance constraints, Gauss–Seidel, <see cref="SimulationSettings.LengthIterations"/> sweeps.</summary>
    Pbd,
}

/// <summary>What keeps a strand's shape (bending), see docs/styles.md.</summary>
public enum BendModel
{
    /// <summary>
    /// The default: every segment is held at its rest direction in its parent segment's frame, swept root to tip
    /// (<see cref="BendSystem"/>), with an implicit, time-step-free compliance set by <see cref="SimulationSettings.Sag"/>.
    /// Straight, curled and fitted rest shapes hold against gravity and come back after the head moves.
    /// </summary>
    RestShape,
    /// <summary>The source's triple shape matching (the 2009 Hair Sheet report's stretch and bend model) with <see cref="SimulationSettings.Alpha"/> and <see cref="SimulationSettings.Mode"/>, exactly as it describes it.</summary>
    SourceTriples,
    /// <summary>No bending at all: hair hangs and swings like a chain.</summary>
    Limp,
}

/// <summary>Which implementation of each system the pipeline uses.</summary>
public enum SolverPath
{
    /// <summary>Plain scalar code in double precision, single-threaded: the oracle.</summary>
    Reference,
    /// <summary>The optimised implementation (falls back to the reference where a system has none).</summary>
    Fast,
}

/// <summary>Solver parameters. Validate() rejects anything non-finite or out of range with a clear message.</summary>
public sealed class SimulationSettings
{
    public Vector3 Gravity { get; set; } = new(0f, -9.81f, 0f);
    /// <summary>What keeps a strand's shape; <see cref="BendModel.RestShape"/> by default.</summary>
    public BendModel Bend { get; set; } = BendModel.RestShape;
    /// <summary>
    /// Bending stiffness of <see cref="BendModel.RestShape"/>, given as what it looks like: how far the tip of a
    /// straight horizontal strand sags under 1 g, as a share of the strand's length, whatever its length, particle count
    /// or the frame rate. 0 = rigid, 0.01 = styled hair that holds (the default), 0.1 = soft hair, 1 and above = nearly limp.
    /// </summary>
    public float Sag { get; set; } = 0.01f;
    /// <summary>
    /// Damping ratio of bending under <see cref="BendModel.RestShape"/> (a dashpot in each joint, relative to its own
    /// stiffness, so scale- and rate-free): 0 = a bent strand rings, 1 = it returns to its shape without overshoot.
    /// </summary>
    public float BendDamping { get; set; } = 0.5f;
    /// <summary>Shape-matching stiffness α (Müller: 0 … 1 is stable; LiteralForce: a spring rate in 1/s²).</summary>
    public float Alpha { get; set; } = 1f;
    /// <summary>Pull towards the head-space rest pose (0 = off, as in the source); holds styled bangs in place.</summary>
    public float GlobalShapeStiffness { get; set; }
    public ShapeMatchMode Mode { get; set; } = ShapeMatchMode.Muller;
    /// <summary>
    /// Air drag, scale-free: velocities decay as e^(−Damping·t/T₀), with T₀ = √(L/1 g) the hair's natural time (L the
    /// mean strand length; 0.16 s for 25 cm hair). 0 = none; the default 0.32 is 2/s on 25 cm hair, 0.32/s on a 10 m
    /// creature's; 1 = a swing loses most of its speed within about one natural time (heavy, wet-looking hair).
    /// </summary>
    public float Damping { get; set; } = 0.32f;
    public int Substeps { get; set; } = 4;
    public LengthMode Length { get; set; } = LengthMode.FollowTheLeader;
    public int LengthIterations { get; set; } = 4;
    /// <summary>Share of the follow-the-leader correction fed back into velocity (Müller 2012's s_damping).</summary>
    public float LengthDamping { get; set; } = 0.9f;
    /// <summary>Tangential velocity kept on contact with a collider (1 = frictionless sliding).</summary>
    public float ContactSlide { get; set; } = 1f;
    /// <summary>
    /// Coulomb static friction μs against colliders, in position-based form (Macklin et al. 2014, §6.1): a particle
    /// whose slide along the surface in a substep is shorter than μs × the depth it was pushed out by stays where it was
    /// along the surface. Dimensionless, so scale- and rate-free. 0 = frictionless (the default, exactly as without it);
    /// 0.5: hair rests on a head turned about 25° and slides when it turns further (tan 25° ≈ 0.47); 1: it holds up to
    /// about 45°, hair clings to the top of the head and drapes over its sides; 2 and above: grippy, like wet or waxed hair.
    /// </summary>
    public float StaticFriction { get; set; }
    /// <summary>
    /// Coulomb kinetic friction μk against colliders: hair that does slide loses μk × the pushed-out depth of its slide
    /// per substep (Macklin et al. 2014, §6.1). Dimensionless. 0 = frictionless (the default); 0.3: hair still slides off
    /// a sloping head but visibly slower, settling where the slope flattens; 0.8 with μs 1: silky hair that slides in
    /// short, slow slips; usually a little below <see cref="StaticFriction"/>.
    /// </summary>
    public float KineticFriction { get; set; }
    /// <summary>
    /// Speed limit, a guard against explosions, in units of the hair's natural speed √(1 g·L) (1.57 m/s for 25 cm hair):
    /// the default 25 is 40 m/s there. Bounds the velocity every frame leaves in the buffers. 0 = off.
    /// </summary>
    public float MaxSpeed { get; set; } = 25f;
    /// <summary>
    /// A head move farther than this share of the hair's reach (the farthest rest particle from the head origin,
    /// 0.26 m for the reference groom, so 0.52 m) in one frame is a teleport: the hair is carried rigidly.
    /// </summary>
    public float TeleportDistance { get; set; } = 2f;
    /// <summary>Head turns more than this (radians) in one frame count as a teleport.</summary>
    public float TeleportAngle { get; set; } = MathF.PI / 3f;
    public SolverPath Path { get; set; } = SolverPath.Fast;
    /// <summary>
    /// Stability guards (see StabilityGuards): α clamped to 1 in Müller mode, and automatic substepping so no substep
    /// is longer than <see cref="MaxSubstep"/> and the head moves at most <see cref="MaxHeadTravel"/> per substep.
    /// Off = exactly the requested settings (e.g. the source's scheme, faithfully).
    /// </summary>
    public bool Guards { get; set; } = true;
    /// <summary>
    /// Longest substep (s) the guards allow; 0 = no limit (the default: a time in seconds is not scale-free, and the fall
    /// limit <see cref="MaxFallPerSubstep"/> sets the substep from the groom's own size instead; 1/60 s was the limit before).
    /// </summary>
    public float MaxSubstep { get; set; }
    /// <summary>
    /// Farthest the guards let any point of the hair's reach move with the head in one substep, as a share of the groom's
    /// mean segment length (1.2 = 2 cm for the reference groom's 1.67 cm segments); 0 = no limit.
    /// </summary>
    public float MaxHeadTravel { get; set; } = 1.2f;

    /// <summary>
    /// Farthest gravity may move a particle in one substep, as a share of the groom's mean segment length (h²·|g| ≤ this × ℓ);
    /// the guards add substeps to keep it (scale-free: small hair gets shorter substeps). 0 = no limit.
    /// </summary>
    public float MaxFallPerSubstep { get; set; } = 0.05f;

    public SimulationSettings Clone() => (SimulationSettings)MemberwiseClone();

    /// <summary>Copies every setting into target without allocating (the pipeline's per-frame guarded copy).</summary>
    public void CopyTo(SimulationSettings target)
    {
        target.Gravity = Gravity; target.Bend = Bend; target.Sag = Sag; target.BendDamping = BendDamping; target.Alpha = Alpha; target.GlobalShapeStiffness = GlobalShapeStiffness; target.Mode = Mode;
        target.Damping = Damping; target.Substeps = Substeps; target.Length = Length; target.LengthIterations = LengthIterations;
        target.LengthDamping = LengthDamping; target.ContactSlide = ContactSlide; target.MaxSpeed = MaxSpeed;
        target.StaticFriction = StaticFriction; target.KineticFriction = KineticFriction;
        target.TeleportDistance = TeleportDistance; target.TeleportAngle = TeleportAngle; target.Path = Path;
        target.Guards = Guards; target.MaxSubstep = MaxSubstep; target.MaxHeadTravel = MaxHeadTravel; target.MaxFallPerSubstep = MaxFallPerSubstep;
    }

    /// <summary>Strongest gravity accepted (m/s², about 1000 g; the stability map goes to 100 g): beyond it a substep's fall exceeds anything float positions hold.</summary>
    public const float MaxGravity = 1e4f;

    public void Validate()
    {
        if (!(Gravity.Length() <= MaxGravity))
            throw new ArgumentException($"Gravity must be finite and at most {MaxGravity} m/s² (about 1000 g), got {Gravity}.", nameof(Gravity));
        Range(Sag, 0f, 100f, nameof(Sag));
        Range(BendDamping, 0f, 100f, nameof(BendDamping));
        Range(Alpha, 0f, 1000f, nameof(Alpha));
        Range(GlobalShapeStiffness, 0f, 1f, nameof(GlobalShapeStiffness));
        Range(Damping, 0f, 100f, nameof(Damping));
        if (Substeps < 1 || Substeps > 256) throw new ArgumentOutOfRangeException(nameof(Substeps), Substeps, "Substeps must be in 1 … 256.");
        if (LengthIterations < 1 || LengthIterations > 256) throw new ArgumentOutOfRangeException(nameof(LengthIterations), LengthIterations, "Length iterations must be in 1 … 256.");
        Range(LengthDamping, 0f, 1f, nameof(LengthDamping));
        Range(ContactSlide, 0f, 1f, nameof(ContactSlide));
        Range(StaticFriction, 0f, 10f, nameof(StaticFriction));
        Range(KineticFriction, 0f, 10f, nameof(KineticFriction));
        Range(MaxSpeed, 0f, 1e6f, nameof(MaxSpeed));
        Range(TeleportDistance, 0f, 1e6f, nameof(TeleportDistance));
        Range(TeleportAngle, 0f, MathF.PI, nameof(TeleportAngle));
        Range(MaxSubstep, 0f, 1f, nameof(MaxSubstep));
        Range(MaxHeadTravel, 0f, 1000f, nameof(MaxHeadTravel));
        Range(MaxFallPerSubstep, 0f, 100f, nameof(MaxFallPerSubstep));
        if (!Enum.IsDefined(Bend)) throw new ArgumentOutOfRangeException(nameof(Bend));
        if (!Enum.IsDefined(Mode)) throw new ArgumentOutOfRangeException(nameof(Mode));
        if (!Enum.IsDefined(Length)) throw new ArgumentOutOfRangeException(nameof(Length));
        if (!Enum.IsDefined(Path)) throw new ArgumentOutOfRangeException(nameof(Path));
    }

    private static void Finite(float v, string name)
    {
        if (!float.IsFinite(v)) throw new ArgumentException($"{name} must be finite, got {v}.", name);
    }

    private static void Range(float v, float lo, float hi, string name)
    {
        if (!float.IsFinite(v) || v < lo || v > hi)
            throw new ArgumentOutOfRangeException(name, v, $"{name} must be in {lo} … {hi}.");
    }
}
