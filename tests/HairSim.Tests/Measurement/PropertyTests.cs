using System.Numerics;
using CsCheck;
using HairSim.Measurement;

namespace HairSim.Tests.Measurement;

/// <summary>
/// Thousands of random configurations (solver settings, strand sizes, frame times, gravity, head motion, degenerate
/// starting states) on both solver paths, default guards on: every value stays finite, lengths stay bounded, nothing is left inside the head.
/// </summary>
public class PropertyTests
{
    /// <summary>One random scene and how it is driven.</summary>
    public sealed record RandomCase(
        int Particles, int Sheets, int StrandsPerSheet, ShapeMatchMode Mode, float AlphaShare, int Substeps, LengthMode Length,
        int LengthIterations, int Hz, float GravityScale, float Damping, int Start, int Motion, float Rate, SolverPath Path,
        BendModel Bend = BendModel.RestShape, float Sag = 0.01f)
    {
        public SimulationSettings Settings() => new()
        {
            Bend = Bend, Sag = Sag,
            Mode = Mode,
            Alpha = Mode == ShapeMatchMode.Muller ? 4f * AlphaShare : 1000f * AlphaShare,
            Substeps = Substeps, Length = Length, LengthIterations = LengthIterations,
            Gravity = new Vector3(0f, -9.81f, 0f) * GravityScale, Damping = Damping, Path = Path,
        };

        /// <summary>Head pose for frame f: still, shaking, spinning at up to 30 turns/s, or jumping about (some jumps are teleports).</summary>
        public RigidTransform Head(int f, float t) => Motion switch
        {
            1 => HeadMotion.Shake(t * Rate),
            2 => HeadMotion.Spin(t, 30f * Rate),
            3 => new RigidTransform(new Vector3(MathF.Sin(7.3f * f) * Rate, MathF.Cos(3.1f * f) * 0.5f * Rate, 0f),
                Quaternion.CreateFromAxisAngle(Vector3.Normalize(new Vector3(1f, 2f, MathF.Sin(f))), 2.5f * Rate * MathF.Sin(5.7f * f))),
            _ => RigidTransform.Identity,
        };
    }

    private static readonly Gen<RandomCase> Cases =
        Gen.Select(Gen.Int[2, 40], Gen.Int[1, 3], Gen.Int[1, 3], Gen.Enum<ShapeMatchMode>(), Gen.Float[0f, 1f], Gen.Int[1, 8], Gen.Enum<LengthMode>(), Gen.Enum<SolverPath>(),
               (p, sh, st, mode, alpha, sub, len, path) => (p, sh, st, mode, alpha, sub, len, path))
           .Select(Gen.Int[1, 8], Gen.Int[15, 960], Gen.Float[1f, 100f], Gen.Float[0f, 10f], Gen.Int[0, 3], Gen.Int[0, 3], Gen.Float[0f, 1f],
               (a, it, hz, g, d, start, motion, rate) => new RandomCase(a.p, a.sh, a.st, a.mode, a.alpha, a.sub, a.len, it, hz, g, d, start, motion, rate, a.path))
           .Select(Gen.Enum<BendModel>(), Gen.Float[0f, 2f], (c, bend, sag) => c with { Bend = bend, Sag = sag * sag });

    private const int Frames = 12;

    [Fact]
    public void RandomConfigurationsStayFiniteBoundedAndOutsideTheHead()
    {
        Cases.Sample(c =>
        {
            var st = c.Settings();
            var scene = GroomBuilder.BuildScene(CanonicalCases.SmallGroom(c.Particles, c.Sheets, c.StrandsPerSheet), st);
            var w = scene.World;
            if (c.Start > 0) StabilityMap.Prepare(w, c.Start switch { 1 => StabilityScenario.ZeroLengthEdges, 2 => StabilityScenario.CoincidentParticles, _ => StabilityScenario.StartInsideHead });
            var sim = new HairSimulation(scene);
            float dt = 1f / c.Hz, reach = StabilityGuards.Reach(w);
            double maxSpeed = st.MaxSpeed * GroomScale.Of(w).NaturalSpeed; // MaxSpeed is in units of √(g·L)
            double headTravel = 0;
            int substepsRun = 0;
            for (int f = 0; f < Frames; f++)
            {
                var head = c.Head(f, (f + 1) * dt);
                headTravel += Vector3.Distance(head.Position, w.Head.Position) + RigidTransform.Delta(w.Head, head).Angle * reach;
                sim.Step(dt, head);
                substepsRun += sim.Pipeline.LastFrame.Substeps;
                var m = WorldMetrics.Measure(scene);
                if (m.NonFinite != 0) Assert.Fail($"frame {f}: {m.NonFinite} non-finite values");
                if (m.ParticlesInside != 0) Assert.Fail($"frame {f}: {m.ParticlesInside} particles inside the head ({m.MaxPenetration * 1000:F3} mm)");
                // The speed limit bounds how far free neighbours drift apart, pinned roots move with the head, and a
                // push-out adds at most the head's size.
                double bound = 2 * maxSpeed * (f + 1) * dt + headTravel + 0.25;
                for (int s = 0; s < w.StrandCount; s++)
                    for (int k = 1; k < w.StrandParticleCount[s]; k++)
                    {
                        int i = w.StrandFirst[s] + k;
                        double l = Vector3.Distance(w.GetPosition(i), w.GetPosition(i - 1));
                        if (l > w.RestLength[i] + bound) Assert.Fail($"frame {f}: edge {k} of strand {s} is {l:F3} m (rest {w.RestLength[i]:F3} m)");
                        // Follow-the-leader keeps every edge within the stability map's 50 % under shakes and spins. Exempt:
                        // a start inside the head (the first push-out scatters particles over the surface before the strand
                        // pulls together), the first frame after a collapsed start (the strand unfolds along its rest
                        // direction, partly into the scalp, and is pushed out) and random jumps (a head moving up to 0.5 m per frame at several hundred Hz pushes
                        // particles out by more than a short edge; the head-travel guard only limits it to 2 cm a substep).
                        // The bend sweep unfolds a collapsed strand over its joints' time constants, not in one substep (at
                        // least 8 substeps); and at high rates the unfolding and push-out take longer than a frame: the first
                        // 50 ms are exempt (seeds 3RV7V2u9-4K2, 395 Hz × 5 substeps; 2IABmeMuKtA1, 662 Hz, source's scheme).
                        bool exact = st.Length == LengthMode.FollowTheLeader || st.Bend == BendModel.RestShape;
                        bool unfolding = c.Start != 0 && (f == 0 || (f + 1) * dt <= 0.05f || (st.Bend == BendModel.RestShape && substepsRun <= 8));
                        if (exact && c.Start != 3 && !unfolding && c.Motion != 3 && l > 1.5 * w.RestLength[i])
                            Assert.Fail($"frame {f}: edge {k} of strand {s} stretched {l / w.RestLength[i] - 1:P0} with exact lengths ({st.Bend}, {st.Length})");
                    }
            }
        }, iter: 2000, threads: 2);
    }
}
