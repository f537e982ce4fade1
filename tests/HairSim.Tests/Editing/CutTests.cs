using System.Numerics;
using HairSim;
using HairSim.Editing;

namespace HairSim.Tests.Editing;

public class CutTests
{
    [Fact]
    public void HorizontalStrokeCutsCrossedStrandsAtTheStrokeAndLeavesOthersUnchanged()
    {
        var scene = EditScenes.Curtain();
        var w = scene.World;
        var before = w.Clone();
        var cam = EditScenes.Front();
        // Crosses only the strands with x < 0.012 (the stroke stops between strands).
        var stroke = EditScenes.Horizontal(cam, -0.105f, -0.1f, 0.012f);
        var cmd = HairEditor.Cut(scene, stroke);
        cmd.Apply();

        int cut = 0;
        for (int s = 0; s < w.StrandCount; s++)
        {
            float x = w.PosX[w.RootIndex(s)];
            if (x > 0.012f) { Assert.True(EditScenes.StrandBitEquals(w, before, s), $"uncut strand {s} changed"); continue; }
            cut++;
            int tip = w.TipIndex(s);
            Assert.Equal(7, w.StrandParticleCount[s]); // particle 6 is at y = −0.12: the cut is on segment 5 → 6
            Assert.Equal(-0.105f, w.PosY[tip], 5);
            Assert.Equal(x, w.PosX[tip], 5);
            Assert.True(cam.Project(w.GetPosition(tip), out var screen, out _));
            Assert.True(EditScenes.DistanceToPolyline(screen, stroke.Points) < 1e-2f, "tip is not on the stroke's surface");
            Assert.Equal(Vector3.Distance(w.GetPosition(tip - 1), w.GetPosition(tip)), w.RestLength[tip], 6);
            Assert.Equal(w.RestLength[tip], Vector3.Distance(w.GetRest(tip - 1), w.GetRest(tip)), 5);
            Assert.Equal(0.105f, EditScenes.StrandRestLength(w, s), 5);
        }
        Assert.Equal(6, cut);
        Assert.Equal(6, cmd.Strands.Count);
    }

    [Fact]
    public void CutTipIsAtRestAndDoesNotSpring()
    {
        var settings = new SimulationSettings { Gravity = Vector3.Zero, Damping = 0f };
        var scene = EditScenes.Curtain(settings: settings);
        var cam = EditScenes.Front();
        HairEditor.Cut(scene, EditScenes.Horizontal(cam, -0.113f)).Apply();
        var after = scene.World.Clone();
        var sim = new HairSimulation(scene);
        for (int f = 0; f < 30; f++) sim.Step(1f / 60f);
        float moved = 0;
        for (int i = 0; i < after.ParticleCount; i++) moved = MathF.Max(moved, Vector3.Distance(after.GetPosition(i), scene.World.GetPosition(i)));
        Assert.True(moved < 1e-5f, $"cut strands moved {moved} m without any force: the new tip springs");
    }

    [Fact]
    public void PerspectiveCutWithAMovedHeadPutsTipsOnTheStrokeSurface()
    {
        var g = new GroomSettings { SheetCount = 30, StrandsPerSheet = 6, ParticlesPerStrand = 10 };
        var scene = GroomBuilder.BuildScene(g);
        var w = scene.World;
        w.PlaceHead(new RigidTransform(new Vector3(0.3f, 1.2f, -0.4f), Quaternion.CreateFromYawPitchRoll(0.6f, 0.2f, -0.1f)));
        var cam = StrokeCamera.LookAtPerspective(new Vector3(0.5f, 1.3f, 0.6f), w.Head.Position, Vector3.UnitY, 0.8f, new Vector2(800, 600));
        Assert.True(cam.Project(w.Head.Position, out var c, out _));
        var stroke = new Stroke([c + new Vector2(-300, -60), c + new Vector2(0, -20), c + new Vector2(300, -80)], cam);
        var before = w.Clone();
        var cmd = HairEditor.Cut(scene, stroke, new CutOptions { Reach = CutReach.AllThrough, MinRemainingLength = 0f });
        cmd.Apply();
        Assert.True(cmd.Strands.Count > 10, $"only {cmd.Strands.Count} strands cut");
        var cutSet = new HashSet<int>(cmd.Strands);
        for (int s = 0; s < w.StrandCount; s++)
        {
            if (!cutSet.Contains(s)) { Assert.True(EditScenes.StrandBitEquals(w, before, s)); continue; }
            int tip = w.TipIndex(s);
            Assert.True(cam.Project(w.GetPosition(tip), out var sp, out _));
            Assert.True(EditScenes.DistanceToPolyline(sp, stroke.Points) < 0.05f, $"strand {s} tip is {EditScenes.DistanceToPolyline(sp, stroke.Points)} px off the stroke");
            Assert.True(w.StrandParticleCount[s] < before.StrandParticleCount[s] || w.GetPosition(tip) != before.GetPosition(tip));
            // Rest data in head space agrees with the world-space tip: the rest tip lies on the old rest segment that
            // was crossed. That is the tip's own old segment, or, where the crossing fell within a tenth of a segment
            // past the tip particle (HairEditor.MinTipShare), the next one: the tip particle moved onto the stroke
            // instead of leaving a sliver of a segment.
            var rt = w.GetRest(tip);
            bool sliver = OffSegment(before.GetRest(tip - 1), before.GetRest(tip), rt) > 1e-5f;
            var ra = before.GetRest(sliver ? tip : tip - 1); var rb = before.GetRest(sliver ? tip + 1 : tip);
            Assert.True(OffSegment(ra, rb, rt) < 1e-5f, $"strand {s}: the rest tip is off the crossed rest segment");
            if (sliver) Assert.True(Vector3.Distance(rt, ra) < HairEditor.MinTipShare * Vector3.Distance(ra, rb) + 1e-5f);
            Assert.Equal(w.RestLength[tip], Vector3.Distance(before.GetRest(tip - 1), rt), 4);
        }
    }

    private static float OffSegment(Vector3 a, Vector3 b, Vector3 p)
    {
        var d = Vector3.Normalize(b - a);
        float along = Vector3.Dot(p - a, d);
        if (along < -1e-5f || along > Vector3.Distance(a, b) + 1e-5f) return float.MaxValue;
        return Vector3.Distance(p, a + along * d);
    }

    [Fact]
    public void MinimumRemainingLengthAndTheRootAreNeverCut()
    {
        var scene = EditScenes.Curtain();
        var w = scene.World;
        var before = w.Clone();
        var cam = EditScenes.Front();
        // Crossing 5 mm below the root: on the first segment, whose root end is pinned.
        var cmd = HairEditor.Cut(scene, EditScenes.Horizontal(cam, -0.005f), new CutOptions { MinRemainingLength = 0.01f });
        Assert.Empty(cmd.Strands);
        cmd = HairEditor.Cut(scene, EditScenes.Horizontal(cam, -0.005f), new CutOptions { MinRemainingLength = 0f });
        Assert.Equal(w.StrandCount, cmd.Strands.Count); // the first segment's tip end is free: cut there, 5 mm remain
        cmd.Apply();
        for (int s = 0; s < w.StrandCount; s++)
        {
            Assert.Equal(2, w.StrandParticleCount[s]);
            Assert.Equal(before.GetPosition(w.RootIndex(s)), w.GetPosition(w.RootIndex(s)));
        }
        // A stroke through the roots themselves never removes them.
        var cmd2 = HairEditor.Cut(scene, EditScenes.Horizontal(cam, 0f), new CutOptions { MinRemainingLength = 0f });
        cmd2.Apply();
        for (int s = 0; s < w.StrandCount; s++) Assert.True(w.StrandParticleCount[s] >= 2);
    }

    [Fact]
    public void VisibleOnlySparesStrandsBehindTheHeadAllThroughCutsThem()
    {
        var w = new HairWorld(1, 8, 11);
        var pts = new Vector3[11];
        for (int s = 0; s < 8; s++)
        {
            float x = -0.03f + 0.06f * (s % 4) / 3f, z = s < 4 ? 0.15f : -0.15f; // 4 in front of the head, 4 behind
            for (int k = 0; k < 11; k++) pts[k] = new Vector3(x, -EditScenes.Segment * k, z);
            w.SetStrand(s, pts, 1, true);
        }
        var scene = new HairScene(w);
        scene.AddCollider(Collider.Sphere(new Vector3(0, -0.1f, 0), 0.1f));
        var cam = EditScenes.Front();
        var visible = HairEditor.Cut(scene, EditScenes.Horizontal(cam, -0.1f));
        Assert.Equal([0, 1, 2, 3], visible.Strands);
        var all = HairEditor.Cut(scene, EditScenes.Horizontal(cam, -0.1f), new CutOptions { Reach = CutReach.AllThrough });
        Assert.Equal([0, 1, 2, 3, 4, 5, 6, 7], all.Strands);
    }

    [Fact]
    public void DegenerateStrokesAndCamerasAreRefusedAndChangeNothing()
    {
        var scene = EditScenes.Curtain();
        var before = scene.World.Clone();
        var cam = EditScenes.Front();
        Assert.Throws<ArgumentException>(() => new Stroke(ReadOnlySpan<Vector2>.Empty, cam));
        Assert.Throws<ArgumentException>(() => new Stroke([new Vector2(10, 10)], cam));
        Assert.Throws<ArgumentException>(() => new Stroke([new Vector2(10, 10), new Vector2(10, 10), new Vector2(10, 10)], cam));
        Assert.Throws<ArgumentException>(() => new Stroke([new Vector2(10, 10), new Vector2(600, 10)], cam));
        Assert.Throws<ArgumentException>(() => new Stroke([new Vector2(10, 10), new Vector2(-1, 10)], cam));
        Assert.Throws<ArgumentException>(() => new Stroke([new Vector2(10, float.NaN), new Vector2(20, 10)], cam));
        var view = Matrix4x4.CreateLookAt(new Vector3(0, 0, 1), Vector3.Zero, Vector3.UnitY);
        Assert.ThrowsAny<ArgumentException>(() => StrokeCamera.Perspective(view, new Matrix4x4(), new Vector2(100, 100)));
        Assert.ThrowsAny<ArgumentException>(() => StrokeCamera.Orthographic(new Matrix4x4(), Matrix4x4.CreateOrthographic(1, 1, 0.1f, 10), new Vector2(100, 100)));
        Assert.ThrowsAny<ArgumentException>(() => StrokeCamera.Perspective(view, Matrix4x4.CreatePerspectiveFieldOfView(1, 1, 0.1f, 10) * float.NaN, new Vector2(100, 100)));
        Assert.ThrowsAny<ArgumentException>(() => StrokeCamera.Perspective(view, Matrix4x4.CreatePerspectiveFieldOfView(1, 1, 0.1f, 10), new Vector2(0, 100)));
        Assert.ThrowsAny<ArgumentException>(() => StrokeCamera.Perspective(view, Matrix4x4.CreateOrthographic(1, 1, 0.1f, 10), new Vector2(100, 100)));
        Assert.ThrowsAny<ArgumentException>(() => HairEditor.Cut(scene, EditScenes.Horizontal(cam, -0.1f), new CutOptions { MinRemainingLength = float.NaN }));
        Assert.True(scene.World.BitEquals(before));
        // Repeated points inside a stroke are merged: the stroke still works.
        var s = new Stroke([new Vector2(10, 10), new Vector2(10, 10), new Vector2(30, 10)], cam);
        Assert.Equal(2, s.Count);
    }

    [Fact]
    public void ProjectionAndRayAgreeForPerspectiveAndOrthographicCameras()
    {
        var cams = new[]
        {
            StrokeCamera.LookAtPerspective(new Vector3(0.4f, 0.3f, 1.1f), new Vector3(0, -0.05f, 0), Vector3.UnitY, 0.9f, new Vector2(640, 480)),
            StrokeCamera.LookAtOrthographic(new Vector3(-0.7f, 0.2f, 0.5f), Vector3.Zero, Vector3.UnitY, 0.6f, new Vector2(300, 500)),
        };
        var rng = new SplitMix64(5);
        foreach (var cam in cams)
            for (int k = 0; k < 200; k++)
            {
                var p = new Vector3(rng.NextFloat() - 0.5f, rng.NextFloat() - 0.5f, rng.NextFloat() - 0.5f) * 0.4f;
                Assert.True(cam.Project(p, out var sp, out float depth));
                Assert.True(depth > 0);
                var (o, d) = cam.ScreenRay(sp);
                Assert.Equal(1f, d.Length(), 4);
                var onRay = o + d * Vector3.Dot(p - o, d);
                Assert.True(Vector3.Distance(onRay, p) < 1e-4f, $"{cam.Kind}: ray misses the point by {Vector3.Distance(onRay, p)}");
            }
    }

    [Fact]
    public void RenderStrandsFollowTheCutOfTheirSheet()
    {
        var scene = EditScenes.Curtain(sheets: 2, strandsPerSheet: 5);
        scene.Render = new RenderSettings { StrandsPerGap = 3 };
        var cam = EditScenes.Front();
        HairEditor.Cut(scene, EditScenes.Horizontal(cam, -0.09f)).Apply();
        var interpolate = new InterpolateSystem(scene);
        interpolate.Run(scene, new FrameContext(), 0, 0, scene.World.SheetCount);
        var r = scene.RenderOutput!;
        Assert.Equal(2 * (5 + 4 * 3), r.StrandCount);
        for (int k = 0; k < r.StrandCount; k++)
        {
            var strand = r.Strand(k);
            Assert.Equal(6, strand.Length);
            Assert.Equal(-0.09f, strand[^1].Y, 5);
            foreach (var p in strand) Assert.True(p.Y >= -0.09f - 1e-5f);
        }
    }

    [Fact]
    public void GridFindsExactlyTheStrandsABruteForceSearchFinds()
    {
        var g = new GroomSettings { SheetCount = 40, StrandsPerSheet = 8, ParticlesPerStrand = 12 };
        var scene = GroomBuilder.BuildScene(g);
        var cam = StrokeCamera.LookAtPerspective(new Vector3(0.1f, 0.05f, 0.8f), Vector3.Zero, Vector3.UnitY, 0.7f, new Vector2(700, 700));
        var rng = new SplitMix64(11);
        for (int trial = 0; trial < 5; trial++)
        {
            var pts = new Vector2[2 + trial * 7];
            for (int k = 0; k < pts.Length; k++) pts[k] = new Vector2(50 + 600 * rng.NextFloat(), 50 + 600 * rng.NextFloat());
            var stroke = new Stroke(pts, cam);
            var options = new CutOptions { Reach = CutReach.AllThrough, MinRemainingLength = 0f };
            var fast = HairEditor.Cut(scene, stroke, options).Strands;
            var brute = new List<int>();
            var w = scene.World;
            for (int s = 0; s < w.StrandCount; s++)
            {
                bool hit = false;
                for (int k = 1; k < w.StrandParticleCount[s] && !hit; k++)
                {
                    int i = w.StrandFirst[s] + k;
                    if (w.InvMass[i] == 0f) continue;
                    cam.Project(w.GetPosition(i - 1), out var a, out _);
                    cam.Project(w.GetPosition(i), out var b, out _);
                    for (int m = 0; m + 1 < stroke.Count && !hit; m++)
                        hit = Crosses(a, b, stroke.Points[m], stroke.Points[m + 1]);
                }
                if (hit) brute.Add(s);
            }
            Assert.Equal(brute, fast);
        }
    }

    private static bool Crosses(Vector2 a, Vector2 b, Vector2 c, Vector2 d)
    {
        static float Side(Vector2 p, Vector2 q, Vector2 r) => (q.X - p.X) * (r.Y - p.Y) - (q.Y - p.Y) * (r.X - p.X);
        return Side(a, b, c) * Side(a, b, d) <= 0 && Side(c, d, a) * Side(c, d, b) <= 0;
    }
}
