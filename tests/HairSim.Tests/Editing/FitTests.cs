using System.Numerics;
using HairSim;
using HairSim.Editing;
using Xunit.Abstractions;

namespace HairSim.Tests.Editing;

public class FitTests(ITestOutputHelper output)
{
    /// <summary>Side orthographic camera (looking along +X, so +Z is to the right), 1000 px per metre, centred at (0, −0.1, 0).</summary>
    private static StrokeCamera Side() =>
        StrokeCamera.LookAtOrthographic(new Vector3(-1f, -0.1f, 0), new Vector3(0, -0.1f, 0), Vector3.UnitY, 0.5f, new Vector2(500, 500));

    /// <summary>A stroke drawn over a world-space curve (each point projected by the camera).</summary>
    private static Stroke Over(StrokeCamera cam, IEnumerable<Vector3> curve)
    {
        var pts = new List<Vector2>();
        foreach (var p in curve) { Assert.True(cam.Project(p, out var sp, out _)); pts.Add(sp); }
        return new Stroke(pts, cam);
    }

    /// <summary>Straight down 3 cm from the root, then a circle of radius r in the y–z plane, for the given turns.</summary>
    private static IEnumerable<Vector3> Curl(float r, float turns, int samples = 200)
    {
        yield return Vector3.Zero;
        var top = new Vector3(0, -0.03f, 0);
        yield return top;
        var centre = top + new Vector3(0, 0, r);
        for (int k = 1; k <= samples; k++)
        {
            float a = turns * 2 * MathF.PI * k / samples;
            yield return centre + r * new Vector3(0, -MathF.Sin(a), -MathF.Cos(a));
        }
    }

    private static void AssertLengthsKept(HairWorld w, int s)
    {
        for (int k = 1; k < w.StrandParticleCount[s]; k++)
        {
            int i = w.StrandFirst[s] + k;
            Assert.Equal(w.RestLength[i], Vector3.Distance(w.GetPosition(i - 1), w.GetPosition(i)), 5);
        }
    }

    private static double TipToRootOverLength(HairWorld w, int s) =>
        Vector3.Distance(w.GetPosition(w.RootIndex(s)), w.GetPosition(w.TipIndex(s))) / EditScenes.StrandRestLength(w, s);

    /// <summary>Mean turning angle between consecutive segments of the free part of a strand (radians).</summary>
    private static double MeanTurn(HairWorld w, int s)
    {
        double sum = 0; int n = 0;
        for (int k = 2; k < w.StrandParticleCount[s]; k++)
        {
            int i = w.StrandFirst[s] + k;
            var a = Vector3.Normalize(w.GetPosition(i - 1) - w.GetPosition(i - 2));
            var b = Vector3.Normalize(w.GetPosition(i) - w.GetPosition(i - 1));
            sum += Math.Acos(Math.Clamp(Vector3.Dot(a, b), -1f, 1f)); n++;
        }
        return sum / n;
    }

    [Fact]
    public void SelectionByRectangleLassoAndBrushPicksTheStrandsInside()
    {
        var scene = EditScenes.Curtain(sheets: 1, strandsPerSheet: 11); // x = −0.05, −0.04, …, 0.05
        var cam = EditScenes.Front();
        float y = EditScenes.ScreenY(-0.1f);
        var rect = HairEditor.Select(scene, cam, SelectionArea.Rectangle(new(EditScenes.ScreenX(-0.025f), y - 5), new(EditScenes.ScreenX(0.015f), y + 5)));
        Assert.Equal([3, 4, 5, 6], rect.Strands.ToArray());
        Assert.True(rect.Mask[4] && !rect.Mask[7]);
        var brush = HairEditor.Select(scene, cam, SelectionArea.Brush(new(EditScenes.ScreenX(0.05f), y), 12f));
        Assert.Equal([9, 10], brush.Strands.ToArray());
        var lasso = HairEditor.Select(scene, cam, SelectionArea.Lasso([new(EditScenes.ScreenX(-0.06f), y), new(EditScenes.ScreenX(-0.035f), y - 30), new(EditScenes.ScreenX(-0.035f), y + 30)]));
        Assert.Equal([0, 1], lasso.Strands.ToArray());
        var roots = HairEditor.Select(scene, cam, SelectionArea.Rectangle(new(0, y - 5), new(500, y + 5)), new SelectionOptions { RootsOnly = true });
        Assert.Equal(0, roots.Count); // the roots are at y = 0, far above the rectangle
        Assert.Throws<ArgumentException>(() => SelectionArea.Lasso([new(0, 0), new(1, 1), new(2, 2)]));
        Assert.Throws<ArgumentException>(() => SelectionArea.Rectangle(new(5, 5), new(5, 50)));
    }

    [Fact]
    public void FittedStrandsFollowTheStrokeKeepTheirOffsetsLengthsAndRoots()
    {
        var scene = EditScenes.Curtain(sheets: 1, strandsPerSheet: 5, particles: 11);
        var w = scene.World;
        var before = w.Clone();
        var cam = Side();
        var all = new StrandSelection(w, [0, 1, 2, 3, 4]);
        // Sweep the hair forward (+Z) and down at 45°: a straight stroke from the roots.
        var stroke = Over(cam, [Vector3.Zero, new Vector3(0, -0.2f, 0.2f)]);
        var cmd = HairEditor.Fit(scene, all, stroke);
        cmd.Apply();
        var dir = Vector3.Normalize(new Vector3(0, -1, 1));
        for (int s = 0; s < 5; s++)
        {
            AssertLengthsKept(w, s);
            Assert.Equal(before.GetPosition(w.RootIndex(s)), w.GetPosition(w.RootIndex(s)));
            // The curtain was a line across x: offsets along the view direction (x) are kept, the rest follows the stroke.
            float x = before.PosX[before.RootIndex(s)];
            for (int k = 1; k < w.StrandParticleCount[s]; k++)
            {
                var p = w.GetPosition(w.StrandFirst[s] + k);
                Assert.Equal(x, p.X, 4);
                var along = new Vector3(0, p.Y, p.Z);
                Assert.True(Vector3.Distance(along, dir * along.Length()) < 1e-4f, $"strand {s} particle {k} is off the stroke: {p}");
            }
            // The fitted shape is the new rest pose (head space) and rest shape.
            for (int k = 0; k < w.StrandParticleCount[s]; k++)
            {
                int i = w.StrandFirst[s] + k;
                Assert.True(Vector3.Distance(w.Head.InverseTransformPoint(w.GetPosition(i)), w.GetRest(i)) < 1e-6f);
                Assert.Equal(Vector3.Zero, w.GetVelocity(i));
            }
        }
        Assert.False(cmd.Extended);
    }

    [Fact]
    public void PerspectiveFitWithAMovedHeadFollowsTheStrokeOnScreenAndStoresRestInHeadSpace()
    {
        var scene = EditScenes.Curtain(sheets: 1, strandsPerSheet: 5, particles: 11);
        var w = scene.World;
        var head = new RigidTransform(new Vector3(0.4f, 1.5f, -0.3f), Quaternion.CreateFromYawPitchRoll(0.9f, 0.3f, 0.2f));
        w.PlaceHead(head);
        var before = w.Clone();
        // Looking at the curtain edge-on from its side, 0.8 m away, in head-relative terms.
        var cam = StrokeCamera.LookAtPerspective(head.TransformPoint(new Vector3(-0.8f, -0.1f, 0)), head.TransformPoint(new Vector3(0, -0.1f, 0)),
            head.TransformDirection(Vector3.UnitY), 0.9f, new Vector2(800, 600));
        var curve = new[] { new Vector3(0, 0, 0), new Vector3(0, -0.05f, 0.03f), new Vector3(0, -0.12f, 0.08f), new Vector3(0, -0.2f, 0.06f), new Vector3(0, -0.3f, 0.0f) };
        var stroke = Over(cam, curve.Select(head.TransformPoint));
        HairEditor.Fit(scene, new StrandSelection(w, [0, 1, 2, 3, 4]), stroke).Apply();
        for (int k = 0; k < 11; k++)
        {
            var mean = Vector3.Zero;
            for (int s = 0; s < 5; s++) mean += w.GetPosition(w.StrandFirst[s] + k) / 5f;
            Assert.True(cam.Project(mean, out var sp, out _));
            Assert.True(EditScenes.DistanceToPolyline(sp, stroke.Points) < 0.5f, $"key curve point {k} is {EditScenes.DistanceToPolyline(sp, stroke.Points):F2} px off the stroke");
        }
        for (int s = 0; s < 5; s++)
        {
            AssertLengthsKept(w, s);
            Assert.Equal(before.GetPosition(w.RootIndex(s)), w.GetPosition(w.RootIndex(s)));
            for (int k = 0; k < 11; k++)
            {
                int i = w.StrandFirst[s] + k;
                Assert.True(Vector3.Distance(head.TransformPoint(w.GetRest(i)), w.GetPosition(i)) < 1e-5f);
            }
        }
    }

    [Theory]
    [InlineData(SolverPath.Reference)]
    [InlineData(SolverPath.Fast)]
    public void WithDefaultSettingsAFittedCurlStaysFittedThroughTenSecondsOfHeadShake(SolverPath path)
    {
        // The default bend model holds the fitted rest shape itself: no global pull, no bake.
        var scene = EditScenes.Curtain(sheets: 1, strandsPerSheet: 5, particles: 16, settings: new SimulationSettings { Path = path });
        var w = scene.World;
        HairEditor.Fit(scene, new StrandSelection(w, [0, 1, 2, 3, 4]), Over(Side(), Curl(0.03f, 2.5f))).Apply();
        var sim = new HairSimulation(scene);
        double worstDuring = 0;
        for (int f = 0; f < 600; f++)
        {
            sim.Step(1f / 60f, HairSim.Measurement.HeadMotion.Shake((f + 1) / 60f));
            for (int s = 0; s < 5; s++) worstDuring = Math.Max(worstDuring, FromStyle(w, s));
        }
        for (int f = 0; f < 60; f++) sim.Step(1f / 60f, RigidTransform.Identity);
        Assert.Equal(0, w.CountNonFinite());
        for (int s = 0; s < 5; s++)
        {
            double after = FromStyle(w, s);
            output.WriteLine($"{path}, strand {s}: farthest particle from the fitted style after 10 s of shake + 1 s still: {after:P2} of its length (during the shake up to {worstDuring:P1})");
            Assert.True(after < 0.02, $"strand {s} is {after:P2} of its length from its fitted shape");
            AssertLengthsKept(w, s);
        }
        Assert.True(worstDuring > 0.005, "the shake moved the curls");

        static double FromStyle(HairWorld w, int s)
        {
            double d = 0, length = 0;
            int first = w.StrandFirst[s];
            for (int k = 0; k < w.StrandParticleCount[s]; k++)
            {
                d = Math.Max(d, Vector3.Distance(w.GetPosition(first + k), w.Head.TransformPoint(w.GetRest(first + k))));
                if (k > 0) length += w.RestLength[first + k];
            }
            return d / length;
        }
    }

    [Fact]
    public void FittedCurlIsStillCurledAfterFiveSecondsOfSimulation()
    {
        // The source's scheme needs the global pull to hold a curl (docs/editing.md, "Keeping a style").
        var settings = new SimulationSettings { Bend = BendModel.SourceTriples, GlobalShapeStiffness = 0.05f };
        var scene = EditScenes.Curtain(sheets: 1, strandsPerSheet: 5, particles: 16, settings: settings);
        var w = scene.World;
        var cam = Side();
        HairEditor.Fit(scene, new StrandSelection(w, [0, 1, 2, 3, 4]), Over(cam, Curl(0.03f, 2.5f))).Apply();
        var fitted = new double[5]; var turn = new double[5];
        for (int s = 0; s < 5; s++) { fitted[s] = TipToRootOverLength(w, s); turn[s] = MeanTurn(w, s); AssertLengthsKept(w, s); }
        var sim = new HairSimulation(scene);
        for (int f = 0; f < 300; f++)
        {
            // Gravity and a head that nods and turns (±0.4 rad at 1 Hz) while the curl hangs from it.
            float t = (f + 1) / 60f;
            sim.Step(1f / 60f, new RigidTransform(new Vector3(0, 0.02f * MathF.Sin(2 * MathF.PI * t), 0),
                Quaternion.CreateFromYawPitchRoll(0.4f * MathF.Sin(2 * MathF.PI * t), 0.2f * MathF.Sin(2 * MathF.PI * 0.7f * t), 0)));
        }
        Assert.Equal(0, w.CountNonFinite());
        for (int s = 0; s < 5; s++)
        {
            double ratio = TipToRootOverLength(w, s), t = MeanTurn(w, s);
            output.WriteLine($"strand {s}: tip–root / length fitted {fitted[s]:F3} → {ratio:F3} after 5 s; mean turn {turn[s]:F3} → {t:F3} rad");
            Assert.True(fitted[s] < 0.35, $"the fit did not curl strand {s} ({fitted[s]:F3})");
            Assert.True(ratio < 0.5, $"strand {s} uncurled: tip–root / length = {ratio:F3} (a hanging strand has 1)");
            Assert.True(t > 0.7 * turn[s], $"strand {s} lost curvature: {turn[s]:F3} → {t:F3} rad per segment");
        }
    }

    [Fact]
    public void EmptySelectionIsRefusedAndChangesNothing()
    {
        var scene = EditScenes.Curtain();
        var before = scene.World.Clone();
        var cam = Side();
        var empty = new StrandSelection(scene.World, ReadOnlySpan<int>.Empty);
        var e = Assert.Throws<ArgumentException>(() => HairEditor.Fit(scene, empty, Over(cam, [Vector3.Zero, new Vector3(0, -0.2f, 0.1f)])));
        Assert.Contains("Nothing is selected", e.Message);
        var other = EditScenes.Curtain();
        Assert.Throws<ArgumentException>(() => HairEditor.Fit(scene, new StrandSelection(other.World, [0]), Over(cam, [Vector3.Zero, new Vector3(0, -0.2f, 0.1f)])));
        Assert.True(scene.World.BitEquals(before));
    }

    [Fact]
    public void StrokeShorterThanTheKeyCurveIsContinuedStraight()
    {
        var scene = EditScenes.Curtain(sheets: 1, strandsPerSheet: 3, particles: 11); // strands 0.2 m long
        var w = scene.World;
        var cam = Side();
        // 5 cm down, then 5 cm forward: far shorter than the hair.
        var cmd = HairEditor.Fit(scene, new StrandSelection(w, [0, 1, 2]), Over(cam, [Vector3.Zero, new Vector3(0, -0.05f, 0), new Vector3(0, -0.05f, 0.05f)]));
        Assert.True(cmd.Extended);
        cmd.Apply();
        for (int s = 0; s < 3; s++)
        {
            AssertLengthsKept(w, s);
            // Past the stroke the hair carries on straight forward (+Z) at the stroke's last height.
            for (int k = 7; k < 11; k++)
            {
                var p = w.GetPosition(w.StrandFirst[s] + k);
                Assert.Equal(-0.05f, p.Y, 3);
                Assert.True(p.Z > 0.05f);
            }
        }
    }

    [Fact]
    public void StrokeThatDoublesBackFoldsTheHairAndKeepsItsLength()
    {
        var scene = EditScenes.Curtain(sheets: 1, strandsPerSheet: 3, particles: 11);
        var w = scene.World;
        var cam = Side();
        // Down 12 cm, then straight back up along (almost) the same line.
        var cmd = HairEditor.Fit(scene, new StrandSelection(w, [0, 1, 2]),
            Over(cam, [Vector3.Zero, new Vector3(0, -0.12f, 0), new Vector3(0, -0.12f, 0.005f), new Vector3(0, 0f, 0.005f)]));
        cmd.Apply();
        Assert.Equal(0, w.CountNonFinite());
        for (int s = 0; s < 3; s++)
        {
            AssertLengthsKept(w, s);
            float lowest = float.MaxValue;
            for (int k = 0; k < 11; k++) lowest = MathF.Min(lowest, w.PosY[w.StrandFirst[s] + k]);
            Assert.Equal(-0.12f, lowest, 2);
            Assert.True(w.PosY[w.TipIndex(s)] > lowest + 0.06f, "the hair did not fold back up");
        }
    }

    [Fact]
    public void StrandsOfDifferentLengthsEachFollowTheKeyCurveForTheirOwnLength()
    {
        var scene = EditScenes.Curtain(sheets: 1, strandsPerSheet: 4, particles: 11);
        var w = scene.World;
        var front = EditScenes.Front();
        HairEditor.Cut(scene, EditScenes.Horizontal(front, -0.09f, -0.06f, -0.02f)).Apply(); // strands 0 and 1 → 9 cm
        var lengths = new float[4];
        for (int s = 0; s < 4; s++) lengths[s] = EditScenes.StrandRestLength(w, s);
        Assert.True(lengths[0] < 0.1f && lengths[3] > 0.19f);
        var cam = Side();
        var cmd = HairEditor.Fit(scene, new StrandSelection(w, [0, 1, 2, 3]), Over(cam, [Vector3.Zero, new Vector3(0, -0.05f, 0.05f), new Vector3(0, -0.25f, 0.1f)]));
        cmd.Apply();
        for (int s = 0; s < 4; s++)
        {
            AssertLengthsKept(w, s);
            Assert.Equal(lengths[s], EditScenes.StrandRestLength(w, s), 6);
            // Every particle sits at the target curve's point at its own arc length, offset only across the view (x).
            var pts = w.GetStrandPositions(s);
            float arc = 0;
            for (int k = 1; k < pts.Length; k++)
            {
                arc += Vector3.Distance(pts[k - 1], pts[k]);
                cmd.Target.Frame(arc, out var c, out _, out _, out _);
                var d = pts[k] - c;
                Assert.True(MathF.Abs(d.Y) < 2e-3f && MathF.Abs(d.Z) < 2e-3f, $"strand {s} particle {k} is {d} from the key curve");
            }
        }
    }

    [Fact]
    public void KeyCurveFramesAreRotationMinimisingAndOffsetsTurnWithTheCurve()
    {
        // A helix: its rotation-minimising frame stays orthonormal and turns only as much as the tangent does.
        var pts = new Vector3[400];
        for (int k = 0; k < pts.Length; k++) { float a = k * 0.05f; pts[k] = new Vector3(MathF.Cos(a) * 0.03f, -0.002f * k, MathF.Sin(a) * 0.03f); }
        var samples = KeyCurve.Resample(pts, 0.001f, 300);
        var curve = KeyCurve.FromSamples(samples, 0.001f);
        for (int k = 0; k + 1 < samples.Length; k++)
        {
            var t = curve.Tangents[k]; var n = curve.Normals[k];
            Assert.Equal(0f, Vector3.Dot(t, n), 4);
            Assert.Equal(1f, n.Length(), 4);
            // Rotation minimising: the normal changes only along the tangent's change (no spin about the tangent).
            var dn = curve.Normals[k + 1] - n;
            float spin = Vector3.Dot(dn, Vector3.Cross(t, n));
            Assert.True(MathF.Abs(spin) < 1e-3f, $"frame spins by {spin} at sample {k}");
        }
    }
}
