using System.Numerics;
using HairSim;
using HairSim.Meshes;

namespace HairSheet.Logic;

/// <summary>Every problem found in the inspector values at once, each naming the property the user sees.</summary>
public sealed class HairSettingsException : ArgumentException
{
    public HairSettingsException(IReadOnlyList<string> problems)
        : base("Invalid hair settings:\n  " + string.Join("\n  ", problems)) => Problems = problems;

    public IReadOnlyList<string> Problems { get; }
}

/// <summary>
/// The hair node's inspector values, engine-free. Validate() lists every bad value with the inspector's name
/// for it; the To* methods build HairSim's settings only from values that passed (so a bad edit in the
/// inspector leaves the running simulation untouched).
/// </summary>
public sealed class HairNodeSettings
{
    public int Sheets { get; set; } = 435;
    public int StrandsPerSheet { get; set; } = 40;
    public int ParticlesPerStrand { get; set; } = 16;
    public float StrandLength { get; set; } = 0.25f;
    /// <summary>What keeps the shape: the rest shape (default), the source's triples, or nothing (limp).</summary>
    public BendModel Bend { get; set; } = BendModel.RestShape;
    /// <summary>How far a horizontal strand's tip sags under 1 g, as a share of its length (0.01 = styled hair that holds).</summary>
    public float Sag { get; set; } = 0.01f;
    /// <summary>Damping ratio of bending: 0 = a bent strand rings, 1 = it returns without overshoot.</summary>
    public float BendDamping { get; set; } = 0.5f;
    /// <summary>The source's triple shape-matching α (Müller), used with <see cref="BendModel.SourceTriples"/>: 0 = limp, 1 = stiffest.</summary>
    public float Stiffness { get; set; } = 1f;
    /// <summary>Air drag per natural time √(length / 1 g): 0.32 = 2/s on 25 cm hair, the same look at any size.</summary>
    public float Damping { get; set; } = 0.32f;
    public int Substeps { get; set; } = 4;
    /// <summary>Coulomb friction against the colliders (static, kinetic): 0 = frictionless, 1 = hair clings up to ~45° slopes.</summary>
    public float StaticFriction { get; set; }
    public float KineticFriction { get; set; }
    public Vector3 Gravity { get; set; } = new(0f, -9.81f, 0f);
    /// <summary>Hair volume (docs/volume.md): strands push apart where packed and drag one another along. Off by default.</summary>
    public bool HairVolume { get; set; }
    /// <summary>g of push per unit of over-density per cell: 8 = a layer dropped on another rests on it.</summary>
    public float VolumeStiffness { get; set; } = 8f;
    /// <summary>Friction between strands per natural time: 50 = strands that touch move together.</summary>
    public float VolumeFriction { get; set; } = 50f;
    /// <summary>Density hair may pack to before it pushes, as a multiple of its median rest density: 1 = the default; 0.5 = limp hair keeps its grown thickness on the crown (about twice the passes).</summary>
    public float VolumeDensity { get; set; } = 1f;
    /// <summary>Longest time between volume passes in natural times: 0.125 = one per 60 Hz frame for 25 cm hair; 0.03 keeps layers apart at about 3× the cost.</summary>
    public float VolumeMaxStep { get; set; } = 0.125f;
    /// <summary>Strand contacts (docs/volume.md): strands of different sheets never pass through each other. Off by default; for hair of a few layers, not a full head.</summary>
    public bool StrandContacts { get; set; }
    /// <summary>How far apart layers are kept, in mean segments: 0.25 = a quarter segment.</summary>
    public float ContactThickness { get; set; } = 0.25f;
    /// <summary>Friction between touching layers (μ): 0.3 = a layer rests on another up to about 17°.</summary>
    public float ContactFriction { get; set; } = 0.3f;
    /// <summary>Interpolated render strands between neighbouring simulated strands.</summary>
    public int RenderDensity { get; set; } = 1;
    public Vector4 RootColor { get; set; } = new(0.16f, 0.10f, 0.06f, 1f);
    public Vector4 TipColor { get; set; } = new(0.45f, 0.32f, 0.20f, 1f);
    public float RootWidth { get; set; } = StrandLook.Default.RootWidth;
    public float TipWidth { get; set; } = StrandLook.Default.TipWidth;
    /// <summary>Hair steps per second (the fixed step is its inverse).</summary>
    public int StepsPerSecond { get; set; } = 60;
    public Vector3 HeadRadii { get; set; } = GroomSettings.Reference().HeadRadii;
    public ulong Seed { get; set; } = 2009;

    // Growth on a scalp mesh (HairSystem3D's Scalp Mesh). Only part of the growth key when a scalp mesh is set (GrowthKey).
    /// <summary>A vertex is scalp where its colour's red channel is at least this (0 = the whole mesh; a mesh without colours grows everywhere).</summary>
    public float ScalpMaskThreshold { get; set; } = 0.5f;
    /// <summary>Hair starts this far above the scalp (metres); the mesh collision keeps hair half of it off the surface.</summary>
    public float ScalpRootLift { get; set; } = 0.002f;
    /// <summary>0: strands stand out along the surface normal; 1: they turn to hang down within about a quarter of the head's size.</summary>
    public float ScalpDrape { get; set; } = 1f;
    /// <summary>Cell of the scalp's distance field: about a quarter of the thinnest part the hair must feel (2.5 mm for 1 cm ears).</summary>
    public float ScalpCellSize { get; set; } = 0.0025f;

    public IReadOnlyList<string> Validate()
    {
        var p = new List<string>();
        IntRange(p, "Sheets", Sheets, 1, 100_000);
        IntRange(p, "Strands Per Sheet", StrandsPerSheet, 1, HairWorld.MaxStrandsPerSheet);
        IntRange(p, "Particles Per Strand", ParticlesPerStrand, 3, HairWorld.MaxParticlesPerStrand);
        if (p.Count == 0)
        {
            long total = (long)Sheets * StrandsPerSheet * ParticlesPerStrand;
            if (total > HairWorld.MaxParticles)
                p.Add($"Sheets × Strands Per Sheet × Particles Per Strand = {total:N0} particles, more than the {HairWorld.MaxParticles:N0} a world holds.");
        }
        FloatRange(p, "Strand Length", StrandLength, 0.001f, 10f);
        if (!Enum.IsDefined(Bend)) p.Add($"Bend must be one of {string.Join(", ", Enum.GetNames<BendModel>())}, got {(int)Bend}.");
        FloatRange(p, "Sag", Sag, 0f, 100f);
        FloatRange(p, "Bend Damping", BendDamping, 0f, 100f);
        FloatRange(p, "Stiffness", Stiffness, 0f, 1f);
        FloatRange(p, "Damping", Damping, 0f, 100f);
        IntRange(p, "Substeps", Substeps, 1, 64);
        FloatRange(p, "Static Friction", StaticFriction, 0f, 10f);
        FloatRange(p, "Kinetic Friction", KineticFriction, 0f, 10f);
        if (!Finite(Gravity) || Gravity.Length() > 1000f) p.Add($"Gravity must be finite and at most 1000 m/s², got {Gravity}.");
        FloatRange(p, "Volume Stiffness", VolumeStiffness, 0f, 1000f);
        FloatRange(p, "Volume Friction", VolumeFriction, 0f, 1000f);
        FloatRange(p, "Volume Density", VolumeDensity, 0.05f, 100f);
        FloatRange(p, "Volume Max Step", VolumeMaxStep, 0.01f, 100f);
        FloatRange(p, "Contact Thickness", ContactThickness, 0.01f, 10f);
        FloatRange(p, "Contact Friction", ContactFriction, 0f, 10f);
        IntRange(p, "Render Density", RenderDensity, 0, RenderSettings.MaxStrandsPerGap);
        Color(p, "Root Color", RootColor);
        Color(p, "Tip Color", TipColor);
        FloatRange(p, "Root Width", RootWidth, 1e-5f, 0.05f);
        FloatRange(p, "Tip Width", TipWidth, 0f, 0.05f);
        if (float.IsFinite(RootWidth) && float.IsFinite(TipWidth) && TipWidth > RootWidth) p.Add($"Tip Width ({TipWidth}) must not exceed Root Width ({RootWidth}): tips are thinner than roots.");
        IntRange(p, "Steps Per Second", StepsPerSecond, 10, 1000);
        if (!Finite(HeadRadii) || HeadRadii.X <= 1e-3f || HeadRadii.Y <= 1e-3f || HeadRadii.Z <= 1e-3f || HeadRadii.Length() > 10f)
            p.Add($"Head Radii must be positive and finite (each > 1 mm, at most 10 m), got {HeadRadii}.");
        FloatRange(p, "Scalp Mask Threshold", ScalpMaskThreshold, 0f, 1f);
        FloatRange(p, "Scalp Root Lift", ScalpRootLift, 0f, 0.05f);
        FloatRange(p, "Scalp Drape", ScalpDrape, 0f, 1f);
        FloatRange(p, "Scalp Cell Size", ScalpCellSize, 0.0005f, 0.05f);
        return p;
    }

    public void ThrowIfInvalid()
    {
        var problems = Validate();
        if (problems.Count > 0) throw new HairSettingsException(problems);
    }

    public GroomSettings ToGroom()
    {
        ThrowIfInvalid();
        var g = GroomSettings.Reference();
        g.SheetCount = Sheets;
        g.StrandsPerSheet = StrandsPerSheet;
        g.ParticlesPerStrand = ParticlesPerStrand;
        g.StrandLength = StrandLength;
        g.HeadRadii = HeadRadii;
        g.Seed = Seed;
        g.PinnedPerStrand = Math.Min(g.PinnedPerStrand, ParticlesPerStrand - 1);
        g.Validate();
        return g;
    }

    /// <summary>The groom grown on a scalp mesh: the same sheet, strand and seed values as the ellipsoid groom, plus the scalp's.</summary>
    public MeshGroomSettings ToMeshGroom()
    {
        ThrowIfInvalid();
        var g = new MeshGroomSettings
        {
            SheetCount = Sheets,
            StrandsPerSheet = StrandsPerSheet,
            ParticlesPerStrand = ParticlesPerStrand,
            StrandLength = StrandLength,
            PinnedPerStrand = Math.Min(GroomSettings.Reference().PinnedPerStrand, ParticlesPerStrand - 1),
            RootLift = ScalpRootLift,
            Drape = ScalpDrape,
            ScalpMaskThreshold = ScalpMaskThreshold,
            Seed = Seed,
        };
        g.Validate();
        return g;
    }

    public SimulationSettings ToSimulation()
    {
        ThrowIfInvalid();
        var s = new SimulationSettings
        {
            Bend = Bend,
            Sag = Sag,
            BendDamping = BendDamping,
            Alpha = Stiffness,
            Damping = Damping,
            Substeps = Substeps,
            StaticFriction = StaticFriction,
            KineticFriction = KineticFriction,
            Gravity = Gravity,
            Path = SolverPath.Fast,
        };
        s.Validate();
        return s;
    }

    /// <summary>The volume component to put on the scene, or null when Hair Volume is off.</summary>
    public VolumeSettings? ToVolume()
    {
        ThrowIfInvalid();
        if (!HairVolume) return null;
        var v = new VolumeSettings { Stiffness = VolumeStiffness, Friction = VolumeFriction, Density = VolumeDensity, MaxStep = VolumeMaxStep };
        v.Validate();
        return v;
    }

    /// <summary>The strand-contact component to put on the scene, or null when Strand Contacts is off.</summary>
    public StrandContactSettings? ToContacts()
    {
        ThrowIfInvalid();
        if (!StrandContacts) return null;
        var c = new StrandContactSettings { Thickness = ContactThickness, Friction = ContactFriction };
        c.Validate();
        return c;
    }

    public RenderSettings ToRender()
    {
        ThrowIfInvalid();
        var r = new RenderSettings { StrandsPerGap = RenderDensity };
        r.Validate();
        return r;
    }

    public StrandLook ToLook()
    {
        ThrowIfInvalid();
        return new StrandLook(RootWidth, TipWidth);
    }

    public float FixedStep => 1f / StepsPerSecond;

    private static void IntRange(List<string> p, string name, int v, int lo, int hi)
    {
        if (v < lo || v > hi) p.Add($"{name} must be in {lo} … {hi}, got {v}.");
    }

    private static void FloatRange(List<string> p, string name, float v, float lo, float hi)
    {
        if (!float.IsFinite(v) || v < lo || v > hi) p.Add($"{name} must be in {lo} … {hi}, got {v}.");
    }

    private static void Color(List<string> p, string name, Vector4 c)
    {
        if (!float.IsFinite(c.X) || !float.IsFinite(c.Y) || !float.IsFinite(c.Z) || !float.IsFinite(c.W) ||
            c.X < 0f || c.Y < 0f || c.Z < 0f || c.W < 0f || c.W > 1f || c.X > 16f || c.Y > 16f || c.Z > 16f)
            p.Add($"{name} must have finite, non-negative channels (alpha at most 1), got {c}.");
    }

    private static bool Finite(Vector3 v) => float.IsFinite(v.X) && float.IsFinite(v.Y) && float.IsFinite(v.Z);
}
