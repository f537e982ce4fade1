using System.Numerics;

namespace HairSim;

/// <summary>What the groom builder grows. Validate() rejects bad values before anything is allocated.</summary>
public sealed class GroomSettings
{
    public int SheetCount { get; set; } = 435;
    public int StrandsPerSheet { get; set; } = 40;
    public int ParticlesPerStrand { get; set; } = 16;
    /// <summary>Strand length in metres.</summary>
    public float StrandLength { get; set; } = 0.25f;
    /// <summary>Head ellipsoid semi-axes (x: ear to ear, y: up, z: face forward), head space, metres.</summary>
    public Vector3 HeadRadii { get; set; } = new(0.078f, 0.1f, 0.095f);
    public Vector3 HeadCenter { get; set; } = Vector3.Zero;
    /// <summary>Scalp region: largest angle from the top of the head (radians) at the back and at the face.</summary>
    public float ScalpAngleBack { get; set; } = 1.95f;
    public float ScalpAngleFront { get; set; } = 0.95f;
    /// <summary>Root jitter as a share of root spacing (the source saw streaks with evenly spaced roots).</summary>
    public float RootJitter { get; set; } = 0.5f;
    /// <summary>How far a sheet spreads across the scalp, as a share of the spacing between sheet centres.</summary>
    public float SheetWidth { get; set; } = 1.0f;
    /// <summary>Particles pinned to the head per strand: 1 = a free hinge at the root (the source), 2 = root direction held.</summary>
    public int PinnedPerStrand { get; set; } = 2;
    /// <summary>Roots sit this far outside the scalp surface (metres), so strands do not start in contact.</summary>
    public float RootLift { get; set; } = 0.002f;
    /// <summary>
    /// How the rest pose is combed: 0 = straight out along the scalp normal (the source's groom), 1 = combed down over
    /// the head and falling (a hairstyle at rest, which the default <see cref="BendModel.RestShape"/> holds), values
    /// between bend down less. The rest shape is what the bend model keeps, so a groom that should hang must be grown hanging.
    /// </summary>
    public float Drape { get; set; } = 1f;
    public ulong Seed { get; set; } = 2009;

    public long TotalParticles => (long)SheetCount * StrandsPerSheet * ParticlesPerStrand;

    public GroomSettings Clone() => (GroomSettings)MemberwiseClone();

    /// <summary>The reference scene of the source: 435 sheets × 40 strands × 16 particles.</summary>
    public static GroomSettings Reference() => new();

    public void Validate()
    {
        if (SheetCount < 1) throw new ArgumentOutOfRangeException(nameof(SheetCount), SheetCount, "Sheet count must be at least 1.");
        if (StrandsPerSheet < 1 || StrandsPerSheet > HairWorld.MaxStrandsPerSheet)
            throw new ArgumentOutOfRangeException(nameof(StrandsPerSheet), StrandsPerSheet, $"Strands per sheet must be in 1 … {HairWorld.MaxStrandsPerSheet}.");
        if (ParticlesPerStrand < 2 || ParticlesPerStrand > HairWorld.MaxParticlesPerStrand)
            throw new ArgumentOutOfRangeException(nameof(ParticlesPerStrand), ParticlesPerStrand, $"Particles per strand must be in 2 … {HairWorld.MaxParticlesPerStrand}.");
        if (TotalParticles > HairWorld.MaxParticles)
            throw new ArgumentOutOfRangeException(nameof(SheetCount), TotalParticles, $"{TotalParticles:N0} particles exceed the limit of {HairWorld.MaxParticles:N0}.");
        if (!float.IsFinite(StrandLength) || StrandLength <= 0f || StrandLength > 1000f)
            throw new ArgumentOutOfRangeException(nameof(StrandLength), StrandLength, "Strand length must be in (0, 1000] metres.");
        if (!float.IsFinite(HeadRadii.X) || !float.IsFinite(HeadRadii.Y) || !float.IsFinite(HeadRadii.Z) ||
            HeadRadii.X <= 1e-5f || HeadRadii.Y <= 1e-5f || HeadRadii.Z <= 1e-5f || HeadRadii.Length() > 1000f)
            throw new ArgumentOutOfRangeException(nameof(HeadRadii), HeadRadii, "Head radii must be finite, at least 0.01 mm and at most 1000 m.");
        if (!float.IsFinite(HeadCenter.X) || !float.IsFinite(HeadCenter.Y) || !float.IsFinite(HeadCenter.Z))
            throw new ArgumentException("Head centre must be finite.", nameof(HeadCenter));
        Angle(ScalpAngleBack, nameof(ScalpAngleBack));
        Angle(ScalpAngleFront, nameof(ScalpAngleFront));
        if (!float.IsFinite(RootJitter) || RootJitter < 0f || RootJitter > 1f)
            throw new ArgumentOutOfRangeException(nameof(RootJitter), RootJitter, "Root jitter must be in 0 … 1.");
        if (!float.IsFinite(SheetWidth) || SheetWidth <= 0f || SheetWidth > 10f)
            throw new ArgumentOutOfRangeException(nameof(SheetWidth), SheetWidth, "Sheet width must be in (0, 10].");
        if (PinnedPerStrand < 1 || PinnedPerStrand >= ParticlesPerStrand)
            throw new ArgumentOutOfRangeException(nameof(PinnedPerStrand), PinnedPerStrand, "Pinned particles per strand must be at least 1 and fewer than the particles per strand.");
        if (!float.IsFinite(Drape) || Drape < 0f || Drape > 1f)
            throw new ArgumentOutOfRangeException(nameof(Drape), Drape, "Drape must be in 0 … 1.");
        if (!float.IsFinite(RootLift) || RootLift < 0f || RootLift > 0.1f)
            throw new ArgumentOutOfRangeException(nameof(RootLift), RootLift, "Root lift must be in 0 … 0.1 m.");
    }

    private static void Angle(float a, string name)
    {
        if (!float.IsFinite(a) || a <= 0.01f || a > MathF.PI)
            throw new ArgumentOutOfRangeException(name, a, $"{name} must be in (0.01, π] radians.");
    }
}
