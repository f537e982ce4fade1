using System.Numerics;

namespace HairSim.Measurement;

/// <summary>What one cell of the stability map saw.</summary>
public readonly record struct StabilityResult(int NonFinite, double WorstStretch, double WorstElongation, double WorstCompression, int MaxInside, double EnergyBefore, double EnergyAfter)
{
    /// <summary>Worst edge elongation (l / l0 − 1 of any edge after any frame) that still counts as stable.</summary>
    public const double StretchLimit = 0.5;
    /// <summary>Kinetic energy per unit mass (J/kg) below which the hair counts as at rest.</summary>
    public const double RestEnergy = 1e-4;

    public bool Finite => NonFinite == 0 && double.IsFinite(WorstStretch) && double.IsFinite(EnergyAfter);

    /// <summary>
    /// With the head held still for the last second, visible motion must die down: the last half second has at most
    /// 0.9 × the kinetic energy of the one before, or the hair is at rest.
    /// </summary>
    public bool EnergyDecays => EnergyAfter <= 0.9 * EnergyBefore || EnergyAfter < RestEnergy;

    /// <summary>
    /// Stable: every value finite, no edge ever stretched by 50 % or more (l/l0 − 1 &lt; 0.5; compression is reported
    /// but not counted), no free particle inside a collider after any frame, and the energy dying down once the head stops.
    /// </summary>
    public bool Stable => Finite && WorstElongation < StretchLimit && MaxInside == 0 && EnergyDecays;

    /// <summary>Finite, calm and outside the head, but stretched past the limit (the source's stretchy hair).</summary>
    public bool OnlyStretch => Finite && MaxInside == 0 && EnergyDecays && WorstElongation >= StretchLimit;
}

/// <summary>How the scene of a cell starts, and how the head moves before it stops.</summary>
public enum StabilityScenario
{
    /// <summary>Head shakes "no" for 2 s, then holds still 1 s.</summary>
    Shake,
    /// <summary>Settles 0.5 s, the head jumps 1 m and turns 120° in one frame, then holds still.</summary>
    Teleport,
    /// <summary>As Teleport but just under the teleport thresholds (0.45 m, 55°): the hair is dragged, not carried.</summary>
    NearTeleport,
    /// <summary>Spins at 5 turns/s for 2 s, then stops dead.</summary>
    FastSpin,
    /// <summary>Spins at 20 turns/s for 2 s, then stops dead.</summary>
    VeryFastSpin,
    /// <summary>Every free particle starts on top of its root: every edge has zero length.</summary>
    ZeroLengthEdges,
    /// <summary>Particles start in coincident pairs (each odd particle on its predecessor).</summary>
    CoincidentParticles,
    /// <summary>Free particles start inside the head ellipsoid (scattered about its centre).</summary>
    StartInsideHead,
}

/// <summary>
/// Runs one cell of the stability map: a small groom (6 sheets × 2 strands) on the reference head, driven by a
/// scenario, with frame time dt, measuring after every frame.
/// </summary>
public static class StabilityMap
{
    /// <param name="scale">
    /// Size of the groom and the head's motion against the reference (1 = 25 cm hair): lengths × scale, the motion's
    /// times × √scale (Froude scaling, the same motion at another size), the frame time as given.
    /// </param>
    public static StabilityResult Run(SimulationSettings settings, float dt, int particles, StabilityScenario scenario, int sheets = 6, float scale = 1f)
    {
        if (!(scale > 0f) || !float.IsFinite(scale)) throw new ArgumentOutOfRangeException(nameof(scale), scale, "Scale must be positive and finite.");
        var g = CanonicalCases.SmallGroom(particles, sheets, 2);
        g.StrandLength *= scale; g.HeadRadii *= scale; g.HeadCenter *= scale; g.RootLift *= scale;
        var scene = GroomBuilder.BuildScene(g, settings);
        var w = scene.World;
        Prepare(w, scenario, scale);
        var sim = new HairSimulation(scene);
        float time = MathF.Sqrt(scale);
        float moving = time * scenario switch { StabilityScenario.Teleport or StabilityScenario.NearTeleport => 0.5f, StabilityScenario.ZeroLengthEdges or StabilityScenario.CoincidentParticles or StabilityScenario.StartInsideHead => 0f, _ => 2f };
        float total = moving + time;
        int frames = (int)MathF.Ceiling(total / dt);
        int stillFrom = (int)MathF.Round(moving / dt);
        int half = Math.Max(1, (int)MathF.Round(0.5f * time / dt));
        double worst = 0, before = 0, after = 0, longest = 0, shortest = 0;
        int inside = 0, bad = 0;
        var final = Scaled(FinalPose(scenario, moving / time), scale);
        var previous = new float[w.ParticleCount * 3];
        Snapshot(w, previous);
        for (int f = 0; f < frames; f++)
        {
            float t = (f + 1) * dt;
            var head = f + 1 <= stillFrom ? Scaled(Pose(scenario, t / time), scale) : final;
            sim.Step(dt, head);
            var m = WorldMetrics.Measure(scene);
            bad = Math.Max(bad, m.NonFinite);
            worst = double.IsNaN(m.MaxEdgeStretch) || double.IsNaN(worst) ? double.NaN : Math.Max(worst, m.MaxEdgeStretch);
            inside = Math.Max(inside, m.ParticlesInside);
            EdgeExtremes(w, ref longest, ref shortest);
            double e = VisibleKineticEnergy(w, previous, dt) / scale; // energy per mass ∝ speed² ∝ length
            if (f >= frames - half) after += e / half;
            else if (f >= frames - 2 * half) before += e / half;
        }
        return new StabilityResult(bad, worst, longest, shortest, inside, before, after);
    }

    private static RigidTransform Scaled(RigidTransform pose, float scale) => new(pose.Position * scale, pose.Rotation);

    /// <summary>Largest elongation l/l0 − 1 and largest compression 1 − l/l0 over the live edges.</summary>
    private static void EdgeExtremes(HairWorld w, ref double elongation, ref double compression)
    {
        for (int s = 0; s < w.StrandCount; s++)
        {
            int first = w.StrandFirst[s], n = w.StrandParticleCount[s];
            for (int k = 1; k < n; k++)
            {
                int i = first + k;
                double dx = w.PosX[i] - w.PosX[i - 1], dy = w.PosY[i] - w.PosY[i - 1], dz = w.PosZ[i] - w.PosZ[i - 1];
                double r = Math.Sqrt(dx * dx + dy * dy + dz * dz) / w.RestLength[i] - 1;
                if (double.IsNaN(r)) { elongation = compression = double.NaN; return; }
                elongation = Math.Max(elongation, r); compression = Math.Max(compression, -r);
            }
        }
    }

    private static RigidTransform Pose(StabilityScenario scenario, float t) => scenario switch
    {
        StabilityScenario.Shake => HeadMotion.Shake(t),
        StabilityScenario.FastSpin => HeadMotion.Spin(t, 5f),
        StabilityScenario.VeryFastSpin => HeadMotion.Spin(t, 20f),
        _ => RigidTransform.Identity,
    };

    private static RigidTransform FinalPose(StabilityScenario scenario, float moving) => scenario switch
    {
        StabilityScenario.Teleport => new RigidTransform(new Vector3(0.8f, 0.2f, 0.55f), Quaternion.CreateFromAxisAngle(Vector3.UnitY, 2.1f)),
        StabilityScenario.NearTeleport => new RigidTransform(new Vector3(0.45f, 0f, 0f), Quaternion.CreateFromAxisAngle(Vector3.UnitY, 0.96f)),
        StabilityScenario.Shake => HeadMotion.Shake(moving),
        StabilityScenario.FastSpin => HeadMotion.Spin(moving, 5f),
        StabilityScenario.VeryFastSpin => HeadMotion.Spin(moving, 20f),
        _ => RigidTransform.Identity,
    };

    /// <summary>Degenerate starting states, written straight into the buffers (SetStrand refuses them as rest poses).</summary>
    public static void Prepare(HairWorld w, StabilityScenario scenario, float scale = 1f)
    {
        var rng = new SplitMix64(7);
        for (int s = 0; s < w.StrandCount; s++)
        {
            int first = w.StrandFirst[s], n = w.StrandParticleCount[s];
            for (int k = 1; k < n; k++)
            {
                int i = first + k;
                if (w.InvMass[i] == 0f) continue;
                switch (scenario)
                {
                    case StabilityScenario.ZeroLengthEdges:
                        w.SetPosition(i, w.GetPosition(first));
                        break;
                    case StabilityScenario.CoincidentParticles:
                        if (k % 2 == 1) w.SetPosition(i, w.GetPosition(i - 1));
                        break;
                    case StabilityScenario.StartInsideHead:
                        w.SetPosition(i, new Vector3(rng.NextFloat() - 0.5f, rng.NextFloat() - 0.5f, rng.NextFloat() - 0.5f) * (0.08f * scale));
                        break;
                }
            }
        }
    }

    /// <summary>
    /// Mean kinetic energy per unit mass (J/kg) of the free particles' visible motion: from their displacement over the
    /// frame (x − x_prev)/dt, not the velocity buffer, so hair resting in contact (velocity removed again every
    /// substep) counts as at rest. Updates <paramref name="previous"/> to the current positions.
    /// </summary>
    public static double VisibleKineticEnergy(HairWorld w, float[] previous, float dt)
    {
        double sum = 0; int count = 0;
        for (int i = 0; i < w.ParticleCount; i++)
        {
            double vx = (w.PosX[i] - previous[3 * i]) / dt, vy = (w.PosY[i] - previous[3 * i + 1]) / dt, vz = (w.PosZ[i] - previous[3 * i + 2]) / dt;
            previous[3 * i] = w.PosX[i]; previous[3 * i + 1] = w.PosY[i]; previous[3 * i + 2] = w.PosZ[i];
            if (w.InvMass[i] == 0f) continue;
            sum += 0.5 * (vx * vx + vy * vy + vz * vz); count++;
        }
        return count == 0 ? 0 : sum / count;
    }

    private static void Snapshot(HairWorld w, float[] into)
    {
        for (int i = 0; i < w.ParticleCount; i++) { into[3 * i] = w.PosX[i]; into[3 * i + 1] = w.PosY[i]; into[3 * i + 2] = w.PosZ[i]; }
    }
}
