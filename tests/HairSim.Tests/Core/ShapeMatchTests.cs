using System.Numerics;

namespace HairSim.Tests.Core;

public class ShapeMatchTests
{
    private static (double[] gx, double[] gy, double[] gz, int[] count) Goals(HairWorld w)
    {
        int n = w.StrandCapacity[0];
        var r = (new double[n], new double[n], new double[n], new int[n]);
        ShapeMatchSystem.AccumulateGoals(w, 0, w.Head, r.Item1, r.Item2, r.Item3, r.Item4);
        return r;
    }

    [Fact]
    public void FourParticleStrandGoalsMatchHandComputation()
    {
        // Straight rest, l0 = 1; current strand stretched to edges of 2 along −Y.
        var w = TestWorlds.Strand(4, 1f, Vector3.Zero, -Vector3.UnitY);
        TestWorlds.SetPositions(w, 0, new(0, 0, 0), new(0, -2, 0), new(0, -4, 0), new(0, -6, 0));
        var (gx, gy, gz, count) = Goals(w);
        // Triple 1: centroid (0,−2,0), d = (0,−1,0): goals −1, −2, −3. Triple 2: centroid (0,−4,0): goals −3, −4, −5.
        Assert.Equal(new[] { 1, 2, 2, 1 }, count);
        Assert.Equal(new[] { -1.0, -5.0, -7.0, -5.0 }, gy);
        Assert.All(gx, v => Assert.Equal(0.0, v));
        Assert.All(gz, v => Assert.Equal(0.0, v));
        // Means: −1, −2.5, −3.5, −5.
        Assert.Equal(-2.5, gy[1] / count[1]);
        Assert.Equal(-3.5, gy[2] / count[2]);
    }

    [Fact]
    public void FiveParticleBentStrandGoalsMatchHandComputation()
    {
        var w = TestWorlds.Strand(5, 1f, Vector3.Zero, Vector3.UnitX);
        // A staircase: right, down, right, down.
        TestWorlds.SetPositions(w, 0, new(0, 0, 0), new(1, 0, 0), new(1, -1, 0), new(2, -1, 0), new(2, -2, 0));
        var (gx, gy, _, count) = Goals(w);
        Assert.Equal(new[] { 1, 2, 3, 2, 1 }, count);
        double r = Math.Sqrt(0.5);
        // Triple 1 (p0,p1,p2): centroid (2/3, −1/3); triple 2 (p1,p2,p3): centroid (4/3, −2/3);
        // triple 3 (p2,p3,p4): centroid (5/3, −4/3); every direction d = (r, −r). Goals c − d, c, c + d.
        double[] ex = { 2.0 / 3 - r, 2 - r, 11.0 / 3, 3 + r, 5.0 / 3 + r };
        double[] ey = { -1.0 / 3 + r, -1 + r, -7.0 / 3, -2 - r, -4.0 / 3 - r };
        for (int k = 0; k < 5; k++)
        {
            Assert.Equal(ex[k], gx[k], 12);
            Assert.Equal(ey[k], gy[k], 12);
        }
    }

    /// <summary>The source's algorithm (SPEC A.3) transcribed directly: goals c − l0·d, c, c + l0·d.</summary>
    private static (double[] x, double[] y, double[] z, int[] m) SourceGoals(Vector3[] p, float l0)
    {
        int n = p.Length;
        var gx = new double[n]; var gy = new double[n]; var gz = new double[n]; var m = new int[n];
        for (int i = 1; i < n - 1; i++)
        {
            double cx = ((double)p[i - 1].X + p[i].X + p[i + 1].X) / 3, cy = ((double)p[i - 1].Y + p[i].Y + p[i + 1].Y) / 3, cz = ((double)p[i - 1].Z + p[i].Z + p[i + 1].Z) / 3;
            double dx = (double)p[i + 1].X - p[i - 1].X, dy = (double)p[i + 1].Y - p[i - 1].Y, dz = (double)p[i + 1].Z - p[i - 1].Z;
            double len = Math.Sqrt(dx * dx + dy * dy + dz * dz);
            dx /= len; dy /= len; dz /= len;
            gx[i - 1] += cx - l0 * dx; gy[i - 1] += cy - l0 * dy; gz[i - 1] += cz - l0 * dz; m[i - 1]++;
            gx[i] += cx; gy[i] += cy; gz[i] += cz; m[i]++;
            gx[i + 1] += cx + l0 * dx; gy[i + 1] += cy + l0 * dy; gz[i + 1] += cz + l0 * dz; m[i + 1]++;
        }
        return (gx, gy, gz, m);
    }

    [Fact]
    public void StraightRestShapeGivesExactlyTheSourceGoals()
    {
        var rng = new Random(7);
        for (int trial = 0; trial < 50; trial++)
        {
            int n = rng.Next(3, 24);
            float l0 = 0.01f + (float)rng.NextDouble() * 0.1f;
            var w = TestWorlds.Strand(n, l0, Vector3.Zero, -Vector3.UnitY);
            // The source has one preset edge length l0 (not lengths measured from float points).
            for (int k = 1; k < n; k++) w.RestLength[k] = l0;
            RestShape.SetStraight(w, 0);
            var p = new Vector3[n];
            for (int k = 0; k < n; k++)
                p[k] = new Vector3((float)rng.NextDouble(), (float)rng.NextDouble(), (float)rng.NextDouble()) * 0.3f;
            TestWorlds.SetPositions(w, 0, p);
            var (gx, gy, gz, count) = Goals(w);
            var (sx, sy, sz, m) = SourceGoals(p, l0);
            Assert.Equal(m, count);
            Assert.Equal(sx, gx);
            Assert.Equal(sy, gy);
            Assert.Equal(sz, gz);
        }
    }

    [Fact]
    public void StraightRestShapeFromPointsEqualsAnalyticStraight()
    {
        var w = TestWorlds.Strand(8, 0.05f, new Vector3(0.1f, 0.2f, 0.3f), new Vector3(1, -2, 0.5f));
        var straight = w.Clone();
        RestShape.SetFromRestPose(w, 0);
        for (int i = 0; i < w.ParticleCount; i++)
        {
            Assert.Equal(straight.ShapePrev[i], w.ShapePrev[i], 5);
            Assert.Equal(straight.ShapeMid[i], w.ShapeMid[i], 5);
            Assert.Equal(straight.ShapeNext[i], w.ShapeNext[i], 5);
            Assert.True(Math.Abs(w.ShapeBend[i]) < 1e-5f);
        }
    }

    private static Vector3[] Arc(int n, float radius, float step)
    {
        var pts = new Vector3[n];
        for (int k = 0; k < n; k++)
        {
            float a = k * step / radius;
            pts[k] = new Vector3(radius * MathF.Sin(a), radius * (MathF.Cos(a) - 1f), 0f);
        }
        return pts;
    }

    [Fact]
    public void BentRestShapeIsAnEquilibriumWithoutGravity()
    {
        var w = new HairWorld(1, 1, 12);
        w.SetStrand(0, Arc(12, 0.05f, 0.01f), pinned: 2);
        var before = w.Clone();
        var scene = new HairScene(w, TestWorlds.Settings(s => { s.Gravity = Vector3.Zero; s.Length = LengthMode.None; }));
        var sim = new HairSimulation(scene);
        for (int f = 0; f < 120; f++) sim.Step(1f / 60f);
        for (int i = 0; i < w.ParticleCount; i++)
            Assert.True(Vector3.Distance(before.GetPosition(i), w.GetPosition(i)) < 1e-5f, $"particle {i} moved");
    }

    [Fact]
    public void BentRestShapeKeepsItsCurvatureUnderGravity()
    {
        // A curl (≈ 290° of arc) hanging from a pinned root. The local (per-triple) rest shape alone holds part of
        // it; a straight rest shape with the same start hangs nearly straight.
        int n = 16;
        float radius = 0.03f, step = 0.01f, arcLength = step * (n - 1);
        float Span(bool straightRest, Action<SimulationSettings> settings, bool shake)
        {
            var w = new HairWorld(1, 1, n);
            w.SetStrand(0, Arc(n, radius, step), pinned: 2, straightRestShape: straightRest);
            var sim = new HairSimulation(new HairScene(w, TestWorlds.Settings(settings)));
            for (int f = 0; f < 300; f++)
                sim.Step(1f / 60f, shake ? new RigidTransform(Vector3.Zero, Quaternion.CreateFromAxisAngle(Vector3.UnitY, 0.5f * MathF.Sin(f / 20f))) : w.Head);
            Assert.Equal(0, w.CountNonFinite());
            return Vector3.Distance(w.GetPosition(0), w.GetPosition(n - 1));
        }
        float straight = Span(true, s => s.Substeps = 16, false);
        float curled = Span(false, s => s.Substeps = 16, false);
        Assert.True(straight > 0.9f * arcLength, $"straight rest shape hangs straight: {straight} of {arcLength}");
        Assert.True(curled < 0.75f * arcLength, $"local rest shape keeps the curl: span {curled} of {arcLength}");
        // Default substeps plus a light pull to the rest pose: the curl holds while the head shakes.
        float held = Span(false, s => s.GlobalShapeStiffness = 0.01f, true);
        Assert.True(held < 0.4f * arcLength, $"curl held with global shape stiffness: span {held} of {arcLength}");
    }

    [Fact]
    public void BentRestShapeStaysStableAtEverySubstepCount()
    {
        // Regression: bend directions taken from a head-fixed reference flipped as a curl swung and pumped energy in.
        foreach (int substeps in new[] { 1, 4, 8, 16 })
        {
            var w = new HairWorld(1, 1, 16);
            w.SetStrand(0, Arc(16, 0.03f, 0.01f), pinned: 2);
            var scene = new HairScene(w, TestWorlds.Settings(s => { s.Substeps = substeps; s.Length = LengthMode.None; }));
            var sim = new HairSimulation(scene);
            for (int f = 0; f < 300; f++) sim.Step(1f / 60f);
            Assert.True(w.GetVelocity(15).Length() < 0.2f, $"{substeps} substeps: tip still moving fast");
            Assert.True(WorldMetrics.Measure(scene).LengthRatio < 4, $"{substeps} substeps: bounded");
        }
    }
}
