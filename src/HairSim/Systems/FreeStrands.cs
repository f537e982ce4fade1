namespace HairSim;

/// <summary>
/// Free strands (no pinned particle: a clipping, a loose hair; <see cref="HairWorld.IsFreeStrand"/>) in place of the two
/// root-to-tip sweeps, bend (<see cref="BendSystem"/>) and follow-the-leader (<see cref="LengthSystem"/>). Those sweeps
/// lead from the root and never move it, which is right when something holds the root: free, the strand would be pushed
/// and turned by a force and a torque from nowhere (tried: a sweep whose rigid part was taken off still pumped energy in
/// on contact, and a curl dropped on a floor flew off). So a free strand is solved symmetrically, as position-based
/// dynamics does (Müller et al. 2007): Gauss–Seidel distance constraints between neighbours (its lengths) and, under the
/// default bend model, across every joint (particles k−1 and k+1 held at their rest distance: the size of each bend, not
/// its direction or twist), each correction shared by the ends' inverse masses and turned into velocity (v += Δx/h). The
/// constraints are internal, so momentum and angular momentum are kept. Reference code in double without scratch arrays,
/// so the fast path hands its free strands here (same bits on both paths for the same state) from any thread.
/// </summary>
internal static class FreeStrands
{
    /// <summary>Gauss–Seidel sweeps per substep, alternating direction (enough for lengths within 0.1 % on 64 particles).</summary>
    public const int Iterations = 8;

    /// <summary>
    /// One substep's constraints on free strand s. <paramref name="jointT2"/> (joint j's squared time constant at
    /// [<paramref name="t2Base"/> + j], see <see cref="BendProfile"/>) adds the bend constraints, each closing the share
    /// h²/(T² + h²) of its error per substep, as the held sweep's implicit spring does; null: lengths only.
    /// </summary>
    public static void Relax(HairWorld w, int s, double h, float[]? jointT2 = null, int t2Base = 0)
    {
        int first = w.StrandFirst[s], n = w.StrandParticleCount[s];
        double invH = 1 / h, hh = h * h;
        for (int it = 0; it < Iterations; it++)
        {
            bool forward = it % 2 == 0;
            // Bends first, lengths last: the lengths are what a sweep leaves exact, and what the eye catches first.
            if (jointT2 != null)
                for (int j = 1; j < n - 1; j++)
                {
                    int k = forward ? j : n - 1 - j; // joint k, between particles k − 1 and k + 1
                    int a = first + k - 1, b = first + k + 1;
                    double rx = w.RestX[b] - w.RestX[a], ry = w.RestY[b] - w.RestY[a], rz = w.RestZ[b] - w.RestZ[a];
                    double t2 = jointT2[t2Base + k];
                    // Per iteration, so that all of them together close h²/(T² + h²) of the error.
                    double share = 1 - Math.Pow(t2 / (t2 + hh), 1.0 / Iterations);
                    Project(w, a, b, Math.Sqrt(rx * rx + ry * ry + rz * rz), share, invH);
                }
            for (int j = 1; j < n; j++)
            {
                int k = forward ? j : n - j; // segment k − 1 → k
                Project(w, first + k - 1, first + k, w.RestLength[first + k], 1, invH);
            }
        }
    }

    /// <summary>Moves particles a and b towards distance <paramref name="rest"/> by <paramref name="share"/> of the error, by their inverse masses, velocities taking the moves.</summary>
    private static void Project(HairWorld w, int a, int b, double rest, double share, double invH)
    {
        double wa = w.InvMass[a], wb = w.InvMass[b];
        if (wa + wb == 0) return;
        double ex = w.PosX[b] - w.PosX[a], ey = w.PosY[b] - w.PosY[a], ez = w.PosZ[b] - w.PosZ[a];
        double len = Math.Sqrt(ex * ex + ey * ey + ez * ez);
        if (len < 1e-12) return; // coincident: no direction (the next substep's motion gives one)
        double c = share * (len - rest) / (len * (wa + wb));
        Move(w, a, wa * c * ex, wa * c * ey, wa * c * ez, invH);
        Move(w, b, -wb * c * ex, -wb * c * ey, -wb * c * ez, invH);
    }

    private static void Move(HairWorld w, int i, double dx, double dy, double dz, double invH)
    {
        w.PosX[i] = (float)(w.PosX[i] + dx); w.PosY[i] = (float)(w.PosY[i] + dy); w.PosZ[i] = (float)(w.PosZ[i] + dz);
        w.VelX[i] = (float)(w.VelX[i] + dx * invH); w.VelY[i] = (float)(w.VelY[i] + dy * invH); w.VelZ[i] = (float)(w.VelZ[i] + dz * invH);
    }
}
