using System.Numerics;
using HairSim.Measurement;
using Xunit.Abstractions;

namespace HairSim.Tests.Core;

/// <summary>
/// Styles that hold: with default settings a straight horizontal strand, an upward arc and a hanging curl keep their
/// rest shape within 2 % of the strand's length at every scale from a 1 cm doll to a 10 m creature, at 30 … 240 Hz and
/// 1 … 16 substeps, on both paths, and the figure hardly moves across scales and rates (the model is scale- and
/// frame-rate-free). Against the analytic answer of the model's own definition: a horizontal strand sags Sag × L.
/// </summary>
public class HeldShapeTests(ITestOutputHelper output)
{
    private static readonly float[] Lengths = [0.01f, 0.25f, 10f];
    private static readonly int[] Rates = [30, 60, 240];
    private static readonly int[] Substeps = [1, 4, 16];

    public static TheoryData<HeldShape, SolverPath> ShapesAndPaths()
    {
        var d = new TheoryData<HeldShape, SolverPath>();
        foreach (var shape in Enum.GetValues<HeldShape>())
            foreach (var path in new[] { SolverPath.Reference, SolverPath.Fast })
                d.Add(shape, path);
        return d;
    }

    [Theory]
    [MemberData(nameof(ShapesAndPaths))]
    public void DefaultsHoldTheRestShapeAtEveryScaleAndRate(HeldShape shape, SolverPath path)
    {
        double lo = double.MaxValue, hi = 0;
        foreach (float length in Lengths)
            foreach (int hz in Rates)
                foreach (int substeps in Substeps)
                {
                    var r = HeldShapeCases.Run(shape, length, 16, hz, new SimulationSettings { Path = path, Substeps = substeps });
                    string where = $"{shape}, {length} m, {hz} Hz, {substeps} substeps, {path}";
                    Assert.True(r.Finite, where);
                    Assert.True(r.WorstError < 0.02, $"{where}: worst particle {r.WorstError:P2} of the length from its rest place");
                    Assert.True(r.TipError <= r.WorstError);
                    Assert.True(r.LengthError < 1e-5, $"{where}: lengths drift {r.LengthError:E2}");
                    lo = Math.Min(lo, r.WorstError); hi = Math.Max(hi, r.WorstError);
                }
        output.WriteLine($"{shape} on {path}: worst particle {lo:P3} … {hi:P3} of the length over {Lengths.Length * Rates.Length * Substeps.Length} runs");
        Assert.True(hi - lo < 0.01, $"the held shape varies by {hi - lo:P2} of the length across scales and rates");
    }

    [Theory]
    [InlineData(0.003f)]
    [InlineData(0.01f)]
    [InlineData(0.1f)]
    public void AHorizontalStrandSagsSagTimesItsLengthUnderOneG(float sag)
    {
        // The model's definition (BendProfile): under 1 g a straight horizontal strand's tip drops Sag × L, whatever L.
        foreach (float length in new[] { 0.02f, 0.3f, 3f })
        {
            var st = new SimulationSettings { Sag = sag, Path = SolverPath.Reference, Gravity = new Vector3(0f, -(float)BendProfile.StandardGravity, 0f) };
            var scene = HeldShapeCases.Scene(HeldShape.Cantilever, length, 16, st);
            var sim = new HairSimulation(scene);
            int frames = (int)(4 * Math.Sqrt(length / 0.25) * 60) + 60;
            for (int f = 0; f < frames; f++) sim.Step(1f / 60f);
            var w = scene.World;
            double drop = (w.GetRest(15).Y - w.GetPosition(15).Y) / length;
            output.WriteLine($"Sag {sag}, L {length} m: tip drop {drop:P3} of the length");
            // Small sags are the linear answer; at 10 % the strand's own turn shortens the lever a little.
            Assert.InRange(drop, sag * (sag > 0.05f ? 0.85 : 0.95), sag * 1.03);
        }
    }

    [Fact]
    public void StifferSagHoldsCloserAndLimpHairHangs()
    {
        var held = HeldShapeCases.Worst(new SimulationSettings { Path = SolverPath.Reference }, 60);
        var stiff = HeldShapeCases.Worst(new SimulationSettings { Path = SolverPath.Reference, Sag = 0.002f }, 60);
        var limp = HeldShapeCases.Run(HeldShape.Cantilever, 0.25f, 16, 60, new SimulationSettings { Path = SolverPath.Reference, Bend = BendModel.Limp });
        var source = HeldShapeCases.Run(HeldShape.Cantilever, 0.25f, 16, 60, new SimulationSettings { Path = SolverPath.Reference, Bend = BendModel.SourceTriples });
        output.WriteLine($"default {held.WorstError:P2}, Sag 0.002 {stiff.WorstError:P2}, limp {limp.TipError:P1}, source triples {source.TipError:P1}");
        Assert.True(stiff.WorstError < held.WorstError / 3);
        // Without a rest-shape model a horizontal strand simply hangs: its tip ends about √2 L from where it was.
        Assert.True(limp.TipError > 1.2);
        Assert.True(source.TipError > 0.8);
    }

    [Fact]
    public void AtRestTheVelocityBuffersReadNoMotion()
    {
        // The bend sweep's reaction leaves out what only holds a particle up, so a held strand reads zero velocity, not
        // the follow-the-leader residue h·g·s. Bound: a thousandth of the scale's natural speed √(g·L) (0.16 mm/s at 25 cm… 10 mm/s at 10 m).
        foreach (var shape in Enum.GetValues<HeldShape>())
            foreach (float length in new[] { 0.01f, 0.25f })
            {
                var r = HeldShapeCases.Run(shape, length, 16, 60, new SimulationSettings { Path = SolverPath.Reference });
                Assert.True(r.MaxSpeedAtRest < 1e-3, $"{shape}, {length} m: {r.MaxSpeedAtRest:E2} √(gL)");
            }
        var person = HeldShapeCases.Run(HeldShape.Curl, 0.25f, 16, 60, new SimulationSettings());
        Assert.True(person.MaxSpeedAtRest * Math.Sqrt(9.81 * 0.25) < 1e-3, $"a 25 cm curl at rest reads {person.MaxSpeedAtRest * Math.Sqrt(9.81 * 0.25) * 1000:F3} mm/s");
    }

    [Fact]
    public void AStyleComesBackAfterTheHeadShakes()
    {
        // A fringe-like strand sticking forward and curling down: 2 s of head shake, then 2 s still. It must come back.
        var pts = HeldShapeCases.Points(HeldShape.UpwardArc, 0.15f, 16);
        for (int k = 0; k < pts.Length; k++) pts[k] = new Vector3(pts[k].X, -pts[k].Y, 0f) + new Vector3(0f, 0.1f, 0.1f);
        foreach (var path in new[] { SolverPath.Reference, SolverPath.Fast })
        {
            var w = new HairWorld(1, 1, 16);
            w.SetStrand(0, pts, pinned: 2);
            var scene = new HairScene(w, new SimulationSettings { Path = path });
            var sim = new HairSimulation(scene);
            double shaken = 0;
            for (int f = 0; f < 120; f++)
            {
                sim.Step(1f / 60f, HeadMotion.Shake((f + 1) / 60f));
                shaken = Math.Max(shaken, Distance(w));
            }
            for (int f = 0; f < 120; f++) sim.Step(1f / 60f, RigidTransform.Identity);
            double back = Distance(w);
            output.WriteLine($"{path}: farthest from the style while shaking {shaken * 1000:F1} mm, after 2 s still {back * 1000:F2} mm");
            Assert.True(shaken > 1e-3, "the shake moved the hair");
            Assert.True(back < 0.02 * 0.15, $"{path}: {back * 1000:F2} mm from the style after the shake");
        }

        static double Distance(HairWorld w)
        {
            double d = 0;
            for (int k = 0; k < 16; k++) d = Math.Max(d, Vector3.Distance(w.GetPosition(k), w.Head.TransformPoint(w.GetRest(k))));
            return d;
        }
    }

    [Theory]
    [InlineData(SolverPath.Reference)]
    [InlineData(SolverPath.Fast)]
    public void TheSpeedLimitBoundsTheVelocityBuffers(SolverPath path)
    {
        // A spinning head at 5 turns/s drives hair far past 2 natural speeds (√(g·L) = 1.57 m/s at 25 cm): every
        // velocity left in the buffers after any frame stays within the limit (collision only takes speed away).
        var st = new SimulationSettings { Path = path, MaxSpeed = 2f };
        var scene = GroomBuilder.BuildScene(CanonicalCases.SmallGroom(), st);
        var sim = new HairSimulation(scene);
        double limit = st.MaxSpeed * GroomScale.Of(scene.World).NaturalSpeed, fastest = 0;
        for (int f = 0; f < 60; f++)
        {
            sim.Step(1f / 60f, HeadMotion.Spin((f + 1) / 60f, 5f));
            for (int i = 0; i < scene.World.ParticleCount; i++) fastest = Math.Max(fastest, scene.World.GetVelocity(i).Length());
        }
        output.WriteLine($"{path}: fastest {fastest:F3} m/s, limit {limit:F3} m/s");
        Assert.True(fastest <= limit * (1 + 1e-5), $"{fastest} m/s over the limit of {limit} m/s");
        Assert.True(fastest > 0.9 * limit, "the spin did not reach the limit, so the test shows nothing");
    }
}
