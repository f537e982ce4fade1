using System.Numerics;
using HairSim.Fast;

namespace HairSim.Tests.Fast;

/// <summary>
/// The fast render interpolation against the reference (double precision inside). Tolerance 1e-6 m: the fast path
/// rounds a handful of float operations on offsets of at most a few centimetres plus one add at world scale
/// (≈ 3e-8 m at 0.3 m), so a correct kernel stays ~30× inside it, and a wrong weight or a wrong neighbour moves a
/// point by millimetres.
/// </summary>
public class FastInterpolateTests
{
    private const float Tolerance = 1e-6f;

    /// <summary>Both systems over every sheet of the scene's current state: (reference output, fast output).</summary>
    private static (RenderStrands Reference, RenderStrands Fast) Both(HairScene scene)
    {
        var reference = new InterpolateSystem(scene);
        var fast = new FastInterpolateSystem(scene);
        var ctx = new FrameContext();
        reference.Run(scene, ctx, 0, 0, scene.World.SheetCount);
        fast.Run(scene, ctx, 0, 0, scene.World.SheetCount);
        return (reference.Output, fast.Output);
    }

    private static float MaxDifference(RenderStrands a, RenderStrands b)
    {
        Assert.Equal(a.Counts, b.Counts);
        float worst = 0;
        for (int r = 0; r < a.StrandCount; r++)
        {
            var pa = a.Strand(r); var pb = b.Strand(r);
            for (int k = 0; k < pa.Length; k++)
            {
                Assert.True(float.IsFinite(pb[k].X) && float.IsFinite(pb[k].Y) && float.IsFinite(pb[k].Z), $"render strand {r} point {k}");
                worst = MathF.Max(worst, Vector3.Distance(pa[k], pb[k]));
            }
        }
        return worst;
    }

    /// <summary>A shaken groom: sheets of 1, 2, 3, 5 and 40 strands; strands of 5, 16, 23 and 33 particles; some cut.</summary>
    private static HairScene MovedScene(int strandsPerGap, bool cut)
    {
        int[] sheets = [1, 2, 3, 5, 40];
        var g = GroomSettings.Reference();
        g.SheetCount = sheets.Length;
        var regular = GroomBuilder.Build(g); // positions to borrow: a real groom's roots and directions
        int total = 0;
        foreach (int n in sheets) total += n;
        int[] lengths = [5, 16, 23, 33];
        var caps = new int[total];
        for (int s = 0; s < total; s++) caps[s] = lengths[s % lengths.Length];
        var w = new HairWorld(sheets, caps);
        for (int s = 0; s < total; s++)
        {
            var src = regular.GetStrandPositions(s % regular.StrandCount);
            var dir = Vector3.Normalize(src[^1] - src[0]);
            var pts = new Vector3[caps[s]];
            for (int k = 0; k < pts.Length; k++) pts[k] = src[0] + dir * (0.25f * k / (pts.Length - 1));
            w.SetStrand(s, pts, straightRestShape: true);
        }
        var scene = new HairScene(w, new SimulationSettings());
        scene.AddCollider(Collider.Ellipsoid(Vector3.Zero, new Vector3(0.078f, 0.1f, 0.095f)));
        var sim = new HairSimulation(scene);
        float dt = 1f / 60f;
        for (int f = 0; f < 30; f++) sim.Step(dt, HairSim.Measurement.HeadMotion.Shake((f + 1) * dt));
        if (cut)
            for (int s = 0; s < total; s += 3) w.StrandParticleCount[s] = Math.Max(2, caps[s] / 2 + s % 4);
        scene.Render = new RenderSettings { StrandsPerGap = strandsPerGap };
        return scene;
    }

    [Theory]
    [InlineData(0, false)]
    [InlineData(1, false)]
    [InlineData(3, false)]
    [InlineData(1, true)]
    [InlineData(4, true)]
    public void MatchesTheReferenceOnAMovedGroom(int strandsPerGap, bool cut)
    {
        var scene = MovedScene(strandsPerGap, cut);
        var (reference, fast) = Both(scene);
        float worst = MaxDifference(reference, fast);
        Assert.True(worst <= Tolerance, $"fast differs from reference by {worst:E3} m");
        // The comparison has teeth: the render strands are not all on simulated strands.
        if (strandsPerGap > 0) Assert.True(reference.StrandCount > scene.World.StrandCount);
    }

    [Fact]
    public void CoincidentAndNearlyCoincidentNeighboursStayFiniteAndMatch()
    {
        var g = GroomSettings.Reference();
        g.SheetCount = 2;
        var scene = GroomBuilder.BuildScene(g, new SimulationSettings());
        scene.Render = new RenderSettings { StrandsPerGap = 2 };
        var w = scene.World;
        // Sheet 0: strand 1 on strand 0 exactly, strand 3 a nanometre from strand 2 (the reference's float
        // Barry–Goldman would cancel there), strand 5 at 3 µm, all of strand 7's particles on one point.
        void Copy(int from, int to, Vector3 offset)
        {
            for (int k = 0; k < w.StrandParticleCount[to]; k++) w.SetPosition(w.StrandFirst[to] + k, w.GetPosition(w.StrandFirst[from] + k) + offset);
        }
        Copy(0, 1, Vector3.Zero);
        Copy(2, 3, new Vector3(1e-9f, 0, 0));
        Copy(4, 5, new Vector3(0, 3e-6f, 0));
        for (int k = 0; k < w.StrandParticleCount[7]; k++) w.SetPosition(w.StrandFirst[7] + k, w.GetPosition(w.StrandFirst[7]));
        var (reference, fast) = Both(scene);
        float worst = MaxDifference(reference, fast);
        Assert.True(worst <= Tolerance, $"fast differs from reference by {worst:E3} m");
    }

    [Fact]
    public void TheFastPathUsesItAndTheReferencePathDoesNot()
    {
        var scene = MovedScene(1, false);
        var fast = new HairSimulation(scene).Pipeline.Systems.First(s => s.Name == InterpolateSystem.SystemName);
        Assert.IsType<FastInterpolateSystem>(fast);
        scene.Settings.Path = SolverPath.Reference;
        scene.SettingsChanged();
        var reference = new HairSimulation(scene).Pipeline.Systems.First(s => s.Name == InterpolateSystem.SystemName);
        Assert.IsType<InterpolateSystem>(reference);
    }

    [Fact]
    public void AFrameOfTheFastPipelineMatchesTheReferenceInterpolationOfTheSameState()
    {
        var scene = MovedScene(2, true);
        var sim = new HairSimulation(scene);
        sim.Step(1f / 60f, HairSim.Measurement.HeadMotion.Shake(0.6f));
        var fromPipeline = scene.RenderOutput!;
        var copy = new RenderStrands(scene.World, scene.Render!);
        Array.Copy(fromPipeline.Points, copy.Points, copy.Points.Length);
        Array.Copy(fromPipeline.Counts, copy.Counts, copy.Counts.Length);
        var reference = new InterpolateSystem(scene);
        reference.Run(scene, new FrameContext(), 0, 0, scene.World.SheetCount);
        float worst = MaxDifference(reference.Output, copy);
        Assert.True(worst <= Tolerance, $"pipeline output differs from reference by {worst:E3} m");
    }
}
