namespace HairSim;

/// <summary>
/// A scene component that gives hair volume: strands push apart where hair is packed denser than the groom at rest,
/// and neighbouring strands drag one another along (friction between strands), as in the volumetric hair methods of
/// Petrovic, Henne and Anderson 2005 and Unity's strand hair. Add it with <c>scene.SetComponent(new VolumeSettings())</c>;
/// the pipeline then holds <see cref="VolumeSystem"/> (once per frame, before the substeps) and leaves it out when no
/// scene asks for it. Every value is scale-free and frame-rate-free: the same numbers look the same on a 1 cm doll and a
/// 10 m creature, at 30 or 240 Hz.
/// </summary>
public sealed class VolumeSettings
{
    /// <summary>
    /// How hard packed hair pushes outward, in g (1 g = 9.81 m/s²) per unit of over-density per cell: where two layers
    /// lie in one another (twice the target density) the hair between them is pushed apart with about this many g.
    /// 0 = no push (friction only, layers sink into one another); 8 = the default, a layer dropped on another comes to
    /// rest on it about a cell above; 30 = springy, packed hair bursts apart sideways; 100 = big hair.
    /// </summary>
    public float Stiffness { get; set; } = 8f;

    /// <summary>
    /// Friction between strands: how fast a strand's velocity relative to its neighbours decays, per natural time
    /// √(L / 1 g) (0.16 s for 25 cm hair). 0 = strands slide freely through one another's motion; 1 = the difference
    /// falls to 37 % in one natural time; 4 = neighbouring strands drift together; 50 (the default) = strands that touch
    /// move together within a few milliseconds, so a layer stops where it meets another (hair as a body, like real
    /// hair's strand-to-strand friction); 1000 = the grid's velocity outright.
    /// </summary>
    public float Friction { get; set; } = 50f;

    /// <summary>
    /// The density hair may reach before it pushes back, as a multiple of the groom at rest (the median density the
    /// rest pose's particles see). 1 = hair may not pack denser than it typically is at rest (the default: the sparser
    /// outer layer may still sink until it is that dense); 0.5 = hair without its own lift (limp, or the source's
    /// triples) keeps its grown thickness on the crown, at about twice the volume passes; 2 = it may compress to half
    /// before pushing.
    /// </summary>
    public float Density { get; set; } = 1f;

    /// <summary>
    /// Grid cell size in mean segment lengths of the groom (so a 16-particle and a 64-particle groom of the same hair
    /// see the same grid per particle). Larger cells are cheaper and push over longer distances. Default 1. The grid
    /// never holds more than <see cref="VolumeGrid.MaxNodes"/> nodes: for hair spread wider than that, cells grow.
    /// </summary>
    public float CellSize { get; set; } = 1f;

    /// <summary>
    /// The grid is filled from every N-th strand of each sheet (and its last), each standing for the strands around it,
    /// and the pushes found at those strands are spread linearly to the strands between: the strands of a sheet lie
    /// millimetres apart, far closer than a cell, so this costs little accuracy and saves most of the work. 1 = every
    /// strand (exact); 4 = the default. (A stride chosen per sheet from the rest spacing was measured: worse layering on
    /// the crossing-sheets case and more cost on the reference groom.)
    /// </summary>
    public int SampleEvery { get; set; } = 4;

    /// <summary>
    /// The longest time between two volume passes, in natural times √(L / 1 g): a longer frame is stepped in parts (the
    /// substeps shared out between them), so hair behaves the same at 30 and 240 Hz and at every size. 0.125 (the
    /// default) = 20 ms for 25 cm hair (one pass per frame at 60 Hz, two at 30 Hz), 4 ms for a 1 cm doll's, 125 ms for
    /// a 10 m creature's. While the push is stiff (a layer landing on another) the rest of the frame is cut finer, down
    /// to MaxStep / <see cref="MaxRefine"/> (<see cref="StabilityLimit"/>); quiet hair keeps MaxStep. At most
    /// <see cref="MaxParts"/> parts per frame.
    /// </summary>
    public float MaxStep { get; set; } = 0.125f;

    /// <summary>The push moves hair at most this share of a cell per volume pass (so a strongly packed region opens up over several passes instead of launching hair).</summary>
    internal const double MaxPushPerPass = 0.5;

    /// <summary>The most parts a frame is cut into for the volume (a 1 cm doll at 30 Hz needs 9 at the default MaxStep, 34 at 1/32).</summary>
    public const int MaxParts = IFrameSplitter.MaxParts;

    /// <summary>
    /// The stability bound of the push: a pass of length dt is stable while Stiffness · 1 g · dt² / cell × H stays
    /// below this, with H the largest curvature of the over-density over the grid's hair (the second difference of P
    /// between neighbouring nodes, per cell²). Measured on the crossing sheets and the reference groom: a sheet as
    /// sampled (H ≈ 3.3) and the shaken reference groom (H ≈ 2.4 … 3.1) pass at MaxStep 1/8; a layer that lands on
    /// another and starts to churn (H ≈ 8 … 9) is cut to about 1/16 … 1/32 natural time until it rests (H ≈ 3.7).
    /// </summary>
    internal const double StabilityLimit = 4.5;

    /// <summary>Passes are never shorter than MaxStep / this (4: 1/32 natural time at the default MaxStep): what a stiff frame may cost at most, 4× the volume's quiet cost.</summary>
    public const int MaxRefine = 4;

    /// <summary>
    /// The longest pass the push stays stable for, in seconds, given the largest over-density curvature
    /// <paramref name="curvature"/> (per cell²) the last pass measured on a grid of <paramref name="cell"/> metres; never
    /// shorter than MaxStep / <see cref="MaxRefine"/> natural times. Infinity when nothing is stiff.
    /// </summary>
    internal double LongestPart(double curvature, double cell, in GroomScale scale)
    {
        double stiff = Stiffness * BendProfile.StandardGravity * curvature / cell;
        if (!(stiff > 0) || !double.IsFinite(stiff)) return double.PositiveInfinity;
        return Math.Max(Math.Sqrt(StabilityLimit / stiff), MaxStep * scale.NaturalTime / MaxRefine);
    }

    /// <summary>Into how many parts a frame of dt seconds is stepped for these settings.</summary>
    public int PartsOf(float dt, in GroomScale scale)
    {
        Validate();
        double parts = Math.Ceiling(dt / (MaxStep * scale.NaturalTime) - 1e-6);
        return (int)Math.Clamp(parts, 1, MaxParts);
    }

    /// <summary>Settings that compute the whole grid and change nothing (for measuring a framework that never leaves the system out).</summary>
    public static VolumeSettings Inert => new() { Stiffness = 0f, Friction = 0f };

    internal bool IsInert => Stiffness == 0f && Friction == 0f;

    public VolumeSettings Clone() => (VolumeSettings)MemberwiseClone();

    /// <summary>Refuses non-finite or out-of-range values with a message that names the setting.</summary>
    public void Validate()
    {
        Range(Stiffness, 0f, 1000f, nameof(Stiffness));
        Range(Friction, 0f, 1000f, nameof(Friction));
        Range(Density, 0.05f, 100f, nameof(Density));
        Range(CellSize, 0.1f, 100f, nameof(CellSize));
        Range(MaxStep, 0.01f, 100f, nameof(MaxStep));
        if (SampleEvery < 1 || SampleEvery > 64)
            throw new ArgumentOutOfRangeException(nameof(SampleEvery), SampleEvery, $"Volume SampleEvery must be in 1 … 64, got {SampleEvery}.");
    }

    private static void Range(float v, float lo, float hi, string name)
    {
        if (!float.IsFinite(v) || v < lo || v > hi)
            throw new ArgumentOutOfRangeException(name, v, $"Volume {name} must be a finite number in [{lo}, {hi}], got {v}.");
    }
}
