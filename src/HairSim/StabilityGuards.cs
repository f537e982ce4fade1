using System.Numerics;

namespace HairSim;

/// <summary>
/// The guards the stability map asked for, applied per frame to a copy of the settings that every system reads
/// (FrameContext.Settings), so the reference and the fast path both get them. See docs/stability.md.
/// - Müller α is clamped to 1: above it the goal pull overshoots (α ≥ 2 flips sign every substep and never settles).
/// - Substeps are raised so no substep is longer than MaxSubstep (1/60 s): a frame hitch (or a 15 Hz device) adds
///   substeps instead of lengthening them, so the goal pull and gravity per substep stay in the range measured stable.
/// - Substeps are raised on frames where the head moves fast, so the pins and the head collider move at most
///   MaxHeadTravel per substep: a head that sweeps deep into the hair in one substep pushes particles out by more
///   than an edge length and tears the strand (the "near teleport" row of the map).
/// Never more than 256 substeps (the settings' own limit).
/// </summary>
public static class StabilityGuards
{
    public const int MaxSubsteps = 256;

    /// <summary>Writes the guarded settings for a frame of length dt in which the head origin moves <paramref name="headTranslation"/> metres and turns <paramref name="headAngle"/> radians.</summary>
    /// <param name="reach">Farthest distance (m) of any hair particle from the head origin: a turn of θ moves it θ·reach.</param>
    public static void Apply(SimulationSettings requested, SimulationSettings effective, float dt, float headTranslation, float headAngle, bool teleported, float reach)
    {
        requested.CopyTo(effective);
        if (!requested.Guards) return;
        if (requested.Mode == ShapeMatchMode.Muller && requested.Alpha > 1f) effective.Alpha = 1f;
        double substeps = requested.Substeps;
        if (requested.MaxSubstep > 0f) substeps = Math.Max(substeps, Math.Ceiling(dt / requested.MaxSubstep - 1e-4));
        if (requested.MaxHeadTravel > 0f && !teleported)
        {
            double travel = headTranslation + (double)headAngle * reach;
            substeps = Math.Max(substeps, Math.Ceiling(travel / requested.MaxHeadTravel));
        }
        effective.Substeps = (int)Math.Min(MaxSubsteps, substeps);
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
