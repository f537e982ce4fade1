using System.Numerics;

namespace HairSim;

/// <summary>
/// The guards the stability map asked for, applied per frame to a copy of the settings that every system reads
/// (FrameContext.Settings), so the reference and the fast path both get them. See docs/stability.md.
/// - Müller α is clamped to 1: above it the goal pull overshoots (α ≥ 2 flips sign every substep and never settles).
/// - Substeps are raised so no substep is longer than MaxSubstep, if set (an absolute time, off by default: the fall
///   limit below does the same job scale-free). Either way a frame hitch (or a 15 Hz device) adds substeps instead of
///   lengthening them, so the goal pull and gravity per substep stay in the range measured stable.
/// - Substeps are raised on frames where the head moves fast, so the pins and the head collider move at most
///   MaxHeadTravel per substep: a head that sweeps deep into the hair in one substep pushes particles out by more
///   than an edge length and tears the strand (the "near teleport" row of the map).
/// - Substeps are raised so gravity moves a particle at most MaxFallPerSubstep × the groom's mean segment length in
///   one substep (h²·|g| ≤ f·ℓ): the scale-free form of the substep limit. Hair of a 1 cm doll moves √25 times faster
///   than a person's (Froude scaling), so it needs shorter substeps to look the same; a 10 m creature needs no more.
/// Never more than 256 substeps (the settings' own limit).
/// The same copy turns the scale-free settings into the SI values the systems use (<see cref="GroomScale"/>):
/// Damping into 1/s, MaxSpeed into m/s.
/// </summary>
public static class StabilityGuards
{
    public const int MaxSubsteps = 256;

    /// <summary>Writes the guarded settings for a frame of length dt in which the head origin moves <paramref name="headTranslation"/> metres and turns <paramref name="headAngle"/> radians.</summary>
    /// <param name="scale">The groom's size: its reach (a turn of θ moves the farthest particle θ·reach), mean segment and strand length.</param>
    /// <param name="baseSubsteps">Substeps before the guards raise them (the requested count unless a frame is stepped in parts).</param>
    public static void Apply(SimulationSettings requested, SimulationSettings effective, float dt, float headTranslation, float headAngle, bool teleported, in GroomScale scale, int baseSubsteps = 0)
    {
        requested.CopyTo(effective);
        // α is the source's triple stiffness: no other bend model has triples (a global shape pull may still run).
        if (requested.Bend != BendModel.SourceTriples) effective.Alpha = 0f;
        effective.Damping = (float)(requested.Damping / scale.NaturalTime);
        effective.MaxSpeed = (float)(requested.MaxSpeed * scale.NaturalSpeed);
        if (baseSubsteps > 0) effective.Substeps = baseSubsteps;
        float reach = scale.Reach, segment = scale.Segment;
        if (!requested.Guards) return;
        if (requested.Mode == ShapeMatchMode.Muller && requested.Alpha > 1f) effective.Alpha = 1f;
        double substeps = baseSubsteps > 0 ? baseSubsteps : requested.Substeps;
        if (requested.MaxSubstep > 0f) substeps = Raise(substeps, Math.Ceiling(dt / requested.MaxSubstep - 1e-4));
        double g = requested.Gravity.Length();
        if (requested.MaxFallPerSubstep > 0f && segment > 0f && g > 0)
        {
            double longest = Math.Sqrt(requested.MaxFallPerSubstep * segment / g);
            substeps = Raise(substeps, Math.Ceiling(dt / longest - 1e-4));
        }
        if (requested.MaxHeadTravel > 0f && segment > 0f && !teleported)
        {
            double travel = headTranslation + (double)headAngle * reach;
            substeps = Raise(substeps, Math.Ceiling(travel / (requested.MaxHeadTravel * segment)));
        }
        effective.Substeps = (int)Math.Clamp(substeps, 1, MaxSubsteps);
    }

    /// <summary>
    /// The larger of two substep counts, a NaN limit ignored: a figure that overflowed (0·∞ from a groom or a head move
    /// at the edge of float's range) must not turn into 0 substeps, a frozen scene.
    /// </summary>
    private static double Raise(double substeps, double limit) => double.IsNaN(limit) ? substeps : Math.Max(substeps, limit);

    /// <summary>The mean rest length of the live segments of every strand (0 for a world without any).</summary>
    public static float MeanSegment(HairWorld world)
    {
        double sum = 0; long count = 0;
        for (int s = 0; s < world.StrandCount; s++)
        {
            int first = world.StrandFirst[s];
            for (int k = 1; k < world.StrandParticleCount[s]; k++) { sum += world.RestLength[first + k]; count++; }
        }
        return count == 0 ? 0f : (float)(sum / count);
    }

    /// <summary>The hair's reach: the largest distance of a rest-pose particle from the head origin.</summary>
    public static float Reach(HairWorld world)
    {
        float reach = 0f;
        for (int i = 0; i < world.ParticleCount; i++)
            reach = MathF.Max(reach, new Vector3(world.RestX[i], world.RestY[i], world.RestZ[i]).Length());
        return reach;
    }
}

/// <summary>
/// How big a groom is, measured from its rest pose (after every edit): the lengths that make the settings scale-free.
/// Under Froude scaling (lengths × k, times × √k) a hairstyle moves the same at any size, so times are stated in units
/// of the natural time √(L / 1 g) and speeds in √(1 g · L), with L the mean strand length.
/// </summary>
public readonly record struct GroomScale(float Reach, float Segment, float StrandLength)
{
    /// <summary>Used when a world has no segment at all: the reference scene's strand length.</summary>
    public const float FallbackLength = 0.25f;

    /// <summary>√(L / 1 g), seconds: 0.16 s for 25 cm hair, 1 s for a 10 m creature's.</summary>
    public double NaturalTime => Math.Sqrt(Length / BendProfile.StandardGravity);

    /// <summary>√(1 g · L), m/s: 1.57 m/s for 25 cm hair.</summary>
    public double NaturalSpeed => Math.Sqrt(BendProfile.StandardGravity * Length);

    private double Length => StrandLength > 0f ? StrandLength : FallbackLength;

    /// <summary>A groom of strands of one length and particle count (tests, tools).</summary>
    public static GroomScale Of(float strandLength, int particles, float reach) => new(reach, strandLength / (particles - 1), strandLength);

    public static GroomScale Of(HairWorld world)
    {
        double sum = 0; long segments = 0; int strands = 0;
        for (int s = 0; s < world.StrandCount; s++)
        {
            int first = world.StrandFirst[s], n = world.StrandParticleCount[s];
            double length = 0;
            for (int k = 1; k < n; k++) length += world.RestLength[first + k];
            if (n > 1) { sum += length; segments += n - 1; strands++; }
        }
        float reach = StabilityGuards.Reach(world);
        return strands == 0 ? new GroomScale(reach, 0f, 0f) : new GroomScale(reach, (float)(sum / segments), (float)(sum / strands));
    }
}
