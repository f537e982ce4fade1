namespace HairSim;

/// <summary>
/// The bending compliance of each joint of a strand under <see cref="BendModel.RestShape"/>, as a squared time
/// constant T² (s²) per joint, derived from the strand's rest lengths and <see cref="SimulationSettings.Sag"/>.
///
/// Joint j sits at particle j and holds segment j+1 (particle j → j+1) at its rest direction in segment j's frame
/// (joint 0 is the root clamp, in the head's frame). Each substep the bend sweep keeps the share T²/(T² + h²) of the
/// deviation (implicit Euler of a joint spring on the child particle), so at rest a joint deviates by
/// θ_j = T_j²·g⊥/ℓ_{j+1} whatever the substep h: the held shape does not depend on frame rate or substeps.
///
/// The T_j² are chosen so that a straight horizontal strand under 1 g takes the shape of a uniform cantilever
/// (θ_j ∝ joint length × weight moment beyond the joint) whose tip drops exactly Sag × its length. Every T² scales
/// with length / g, so a strand looks the same at any scale when time scales with √(length / g) (Froude scaling).
/// </summary>
public static class BendProfile
{
    /// <summary>Standard gravity (m/s²): <see cref="SimulationSettings.Sag"/> is the sag under 1 g.</summary>
    public const double StandardGravity = 9.80665;

    /// <summary>
    /// Writes T² for the joints of strand s into <paramref name="t2"/> at the strand's particle indices: entry
    /// first + j holds joint j (0 … n−2); the last live particle's entry and pinned runs' joints are 0.
    /// </summary>
    public static void Compute(HairWorld w, int s, float sag, float[] t2)
    {
        int first = w.StrandFirst[s], n = w.StrandParticleCount[s], cap = w.StrandCapacity[s];
        for (int k = 0; k < cap; k++) t2[first + k] = 0f;
        // The cantilever starts at the last particle of the leading pinned run (the root for one pin).
        int j0 = 0;
        while (j0 + 1 < n && w.InvMass[first + j0 + 1] == 0f) j0++;
        if (j0 >= n - 1 || sag <= 0f) return;

        // Arc length from particle j0 to particle k, the joint lengths, and the weight moment beyond each joint
        // (unit masses, unit gravity, strand horizontal): τ_j = Σ_{i>j} (S_i − S_j).
        double total = 0;
        for (int k = j0 + 1; k < n; k++) total += w.RestLength[first + k];
        if (!(total > 0)) return;
        double suffixS = 0, denominator = 0;
        int suffixCount = 0;
        double arc = total; // S_k, walked from the tip back
        for (int j = n - 2; j >= j0; j--)
        {
            double lNext = w.RestLength[first + j + 1];
            // S_{j+1} joins the suffix before S_j is computed.
            suffixS += arc; suffixCount++;
            arc -= lNext;
            double torque = suffixS - suffixCount * arc;
            double lPrev = j > j0 ? w.RestLength[first + j] : 0.0;
            double weight = 0.5 * (lPrev + lNext) * torque;
            double toTip = total - arc;
            denominator += weight * toTip;
            t2[first + j] = (float)(weight * lNext); // scaled below
        }
        if (!(denominator > 0)) { for (int j = j0; j < n - 1; j++) t2[first + j] = 0f; return; }
        double c = sag * total / (denominator * StandardGravity);
        for (int j = j0; j < n - 1; j++) t2[first + j] = (float)(t2[first + j] * c);
    }

    /// <summary>The share of a joint's deviation kept by one substep of length h: T² / (T² + h²).</summary>
    public static double Keep(double t2, double h) => t2 / (t2 + h * h);
}
