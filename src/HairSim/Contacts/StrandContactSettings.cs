namespace HairSim;

/// <summary>
/// A scene component that keeps the layers of hair apart: a strand of one sheet never ends a pass in, or on the far side
/// of, a strand of another sheet. Each pair of segments from different sheets that comes closer than
/// <see cref="Thickness"/> is pushed apart, and a pair that crossed during the pass is put back on the side it came
/// from (continuous: a fast layer cannot tunnel through a slow one). Add it with
/// <c>scene.SetComponent(new StrandContactSettings())</c>; the pipeline then holds <see cref="StrandContactSystem"/>
/// (once per pass, after the substeps) and leaves it out when no scene asks for it. Strands of one sheet do not
/// collide with each other: a sheet is one layer, held in order by its own structure. Works with or without
/// <see cref="VolumeSettings"/> (volume pushes packed hair apart over a grid; contacts are the hard guarantee between
/// layers). Every value is scale-free and frame-rate-free.
/// </summary>
public sealed class StrandContactSettings
{
    /// <summary>
    /// How far apart the centre lines of two strands of different sheets are kept, in mean segment lengths of the groom
    /// (so it scales with the hair). 0.25 (the default) = a quarter segment: 4 mm on the reference groom's 16 mm
    /// segments, a layer resting on another sits that far above it; 0.05 = layers nearly touch; 1 = a segment apart,
    /// thick, puffy layering.
    /// </summary>
    public float Thickness { get; set; } = 0.25f;

    /// <summary>
    /// Gauss–Seidel sweeps over the contacts per pass: more sweeps settle stacks of several layers more exactly. 4 = the
    /// default; 1 = cheapest (two layers); 16 = deep stacks.
    /// </summary>
    public int Iterations { get; set; } = 4;

    /// <summary>
    /// How much of the velocity with which two strands meet is kept after they touch, along the contact: 0 (the
    /// default) = they stop against each other (hair does not bounce); 1 = they keep it (the push alone separates them).
    /// </summary>
    public float Restitution { get; set; }

    /// <summary>
    /// Friction between touching strands of different sheets (Coulomb's μ, static and kinetic alike): how much they
    /// resist sliding past each other, as a share of how hard they press together. 0 = they slide freely (a layer slips
    /// off another at the slightest slope); 0.3 (the default, about hair on hair) = a layer rests on another at slopes
    /// up to about 17°; 1 = up to 45°.
    /// </summary>
    public float Friction { get; set; } = 0.3f;

    /// <summary>
    /// The most candidate segment pairs per segment (on average) a groom may hold where it stands when contacts are
    /// switched on (and after each edit); moving hair may hold <see cref="StrandContactSystem.PassBudget"/> times as many
    /// before a pass is skipped. Hair of a few layers has a few (two crossing sheets: about 2.5); a full head of hair,
    /// hundreds of sheets over one another, has hundreds, which no per-pair method can afford every frame: such a groom
    /// is refused with a message (use <see cref="VolumeSettings"/>).
    /// </summary>
    public const int PairsPerSegment = 16;

    /// <summary>The most candidate pairs a pass holds, whatever the groom's size (32 MB of pair indices).</summary>
    public const int MaxPairs = 1 << 22;

    public StrandContactSettings Clone() => (StrandContactSettings)MemberwiseClone();

    /// <summary>Refuses non-finite or out-of-range values with a message that names the setting.</summary>
    public void Validate()
    {
        if (!float.IsFinite(Thickness) || Thickness < 0.01f || Thickness > 10f)
            throw new ArgumentOutOfRangeException(nameof(Thickness), Thickness, $"Strand contact Thickness must be a finite number in [0.01, 10] segments, got {Thickness}.");
        if (Iterations < 1 || Iterations > 64)
            throw new ArgumentOutOfRangeException(nameof(Iterations), Iterations, $"Strand contact Iterations must be in 1 … 64, got {Iterations}.");
        if (!float.IsFinite(Friction) || Friction < 0f || Friction > 10f)
            throw new ArgumentOutOfRangeException(nameof(Friction), Friction, $"Strand contact Friction must be a finite number in [0, 10], got {Friction}.");
        if (!float.IsFinite(Restitution) || Restitution < 0f || Restitution > 1f)
            throw new ArgumentOutOfRangeException(nameof(Restitution), Restitution, $"Strand contact Restitution must be a finite number in [0, 1], got {Restitution}.");
    }
}
