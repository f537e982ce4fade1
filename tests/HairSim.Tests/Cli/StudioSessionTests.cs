using System.Net;
using System.Net.Http.Json;
using System.Numerics;
using System.Text.Json;
using HairSim.Cli.Studio;
using Xunit;

namespace HairSim.Tests.Cli;

/// <summary>
/// The studio's server side without a browser: the wire formats, three.js's camera convention, every command's
/// effect on the library's state, refusals that leave the hair unchanged, and the HTTP layer.
/// The page itself is tested in Chromium (tests/studio).
/// </summary>
public sealed class StudioSessionTests : IDisposable
{
    private readonly StudioSession _session = new("small", threads: ThreadDispatchers.CreateDefault());

    public void Dispose() => _session.Dispose();

    // A 900 × 800 canvas with three.js's default camera set-up in the studio: eye 95 cm in front of the head.
    private const float Width = 900, Height = 800;

    /// <summary>The camera as three.js sends it: column-major elements of matrixWorldInverse and projectionMatrix.</summary>
    private static CameraRequest ThreeCamera(Vector3 eye, Vector3 target, float fovDegrees = 35f, float near = 0.01f, float far = 100f)
    {
        // three.js Matrix4.makePerspective (column-major): the OpenGL projection with NDC z in [−1, 1].
        float f = 1f / MathF.Tan(fovDegrees * MathF.PI / 360f), aspect = Width / Height;
        float[] projection =
        [
            f / aspect, 0, 0, 0,
            0, f, 0, 0,
            0, 0, -(far + near) / (far - near), -1,
            0, 0, -2 * far * near / (far - near), 0,
        ];
        // Camera world matrix (columns: right, up, back, eye); the view matrix is its inverse, written column-major.
        var back = Vector3.Normalize(eye - target);
        var right = Vector3.Normalize(Vector3.Cross(Vector3.UnitY, back));
        var up = Vector3.Cross(back, right);
        float[] view =
        [
            right.X, up.X, back.X, 0,
            right.Y, up.Y, back.Y, 0,
            right.Z, up.Z, back.Z, 0,
            -Vector3.Dot(right, eye), -Vector3.Dot(up, eye), -Vector3.Dot(back, eye), 1,
        ];
        return new CameraRequest { View = view, Projection = projection, Width = Width, Height = Height };
    }

    /// <summary>Where three.js would draw a world point: clip = P·V·p with column-major matrices, then to CSS pixels.</summary>
    private static Vector2 ThreeProject(CameraRequest c, Vector3 p)
    {
        static Vector4 Mul(float[] m, Vector4 v) => new(
            m[0] * v.X + m[4] * v.Y + m[8] * v.Z + m[12] * v.W,
            m[1] * v.X + m[5] * v.Y + m[9] * v.Z + m[13] * v.W,
            m[2] * v.X + m[6] * v.Y + m[10] * v.Z + m[14] * v.W,
            m[3] * v.X + m[7] * v.Y + m[11] * v.Z + m[15] * v.W);
        var clip = Mul(c.Projection!, Mul(c.View!, new Vector4(p, 1)));
        return new Vector2((clip.X / clip.W + 1) / 2 * c.Width, (1 - clip.Y / clip.W) / 2 * c.Height);
    }

    private static readonly CameraRequest Front = ThreeCamera(new Vector3(0, 0.05f, 0.95f), new Vector3(0, -0.06f, 0));

    private static float[] Line(CameraRequest camera, Vector3 from, Vector3 to, int points = 20)
    {
        var flat = new float[2 * points];
        for (int i = 0; i < points; i++)
        {
            var s = ThreeProject(camera, Vector3.Lerp(from, to, i / (points - 1f)));
            flat[2 * i] = s.X; flat[2 * i + 1] = s.Y;
        }
        return flat;
    }

    private void Settle(int frames = 60) { for (int i = 0; i < frames; i++) _session.StepFrame(); }

    [Fact]
    public void ThreeJsCameraMapsToTheSameScreenPoints()
    {
        var camera = Front.ToStrokeCamera();
        foreach (var p in new[] { new Vector3(0, 0, 0), new Vector3(0.1f, -0.2f, 0.05f), new Vector3(-0.3f, 0.1f, -0.1f) })
        {
            Assert.True(camera.Project(p, out var screen, out float depth));
            var expected = ThreeProject(Front, p);
            Assert.InRange(Vector2.Distance(screen, expected), 0f, 0.01f);
            Assert.True(depth > 0.5f);
        }
        // And the ray through a pixel passes through the point drawn there.
        var q = new Vector3(0.05f, -0.1f, 0.08f);
        var (o, d) = camera.ScreenRay(ThreeProject(Front, q));
        var closest = o + d * Vector3.Dot(q - o, d);
        Assert.InRange(Vector3.Distance(closest, q), 0f, 1e-4f);
    }

    [Fact]
    public void FrameRoundTripsWithinHalfAQuantum()
    {
        Settle(10);
        var frame = _session.Frame();
        var state = _session.State();
        Assert.Equal(FrameEncoder.FrameHeaderBytes + 6 * state.Particles, frame.Length);
        Assert.True(FrameEncoder.FrameMagic.SequenceEqual(frame.AsSpan(0, 4)));
        float quantum = BitConverter.ToSingle(frame, 28);
        var world = new HairWorld(1, 1, 2);
        world.SetPosition(0, new Vector3(0.1f, 0.2f, 0.3f));
        world.SetPosition(1, new Vector3(-0.4f, 0.05f, 0.9f));
        var small = new byte[FrameEncoder.FrameBytes(world)];
        FrameEncoder.EncodeFrame(world, 7, 3, 1.5f, small);
        float q = BitConverter.ToSingle(small, 28);
        for (int i = 0; i < 2; i++)
            Assert.InRange(Vector3.Distance(FrameEncoder.DecodePosition(small, i), world.GetPosition(i)), 0f, 0.51f * q * MathF.Sqrt(3));
        Assert.Equal(7u, BitConverter.ToUInt32(small, 4));
        Assert.Equal(3, BitConverter.ToInt32(small, 8));
        Assert.InRange(quantum, 1e-7f, 1e-4f);   // a groom of tens of centimetres: micrometre steps
    }

    [Fact]
    public void CutStrokeShortensTheStrandsItCrossesAndUndoRestoresThem()
    {
        Settle();
        var before = _session.State();
        var message = _session.Cut(new StrokeRequest { Points = Line(Front, new(-0.3f, -0.12f, 0.1f), new(0.3f, -0.12f, 0.1f)), Camera = Front });
        var after = _session.State();
        Assert.StartsWith("Cut", message);
        Assert.True(after.CutStrands > 20, $"{after.CutStrands} strands cut");
        Assert.True(after.TotalRestLength < before.TotalRestLength);
        Assert.True(after.LiveParticles < before.LiveParticles);
        Assert.NotEqual(before.Revision, after.Revision);
        var topology = _session.Topology();
        int liveInTopology = 0;
        for (int s = 0; s < after.Strands; s++) liveInTopology += BitConverter.ToInt32(topology, FrameEncoder.TopologyHeaderBytes + 16 * s + 4);
        Assert.Equal(after.LiveParticles, liveInTopology);

        _session.Undo();
        var undone = _session.State();
        Assert.Equal(before.TotalRestLength, undone.TotalRestLength);
        Assert.Equal(before.LiveParticles, undone.LiveParticles);
        Assert.Equal(0, undone.CutStrands);
        _session.Redo();
        Assert.Equal(after.TotalRestLength, _session.State().TotalRestLength);
    }

    [Fact]
    public void SelectionShapesAndModesCombine()
    {
        Settle();
        var rect = new SelectRequest { Shape = "rectangle", Points = Line(Front, new(-0.08f, 0.12f, 0.08f), new(0.08f, 0.0f, 0.1f), 2), Camera = Front };
        _session.Select(rect);
        int n = _session.State().Selection.Length;
        Assert.InRange(n, 5, 959);

        var brush = new SelectRequest { Shape = "brush", Mode = "add", Radius = 40, Points = Line(Front, new(-0.15f, 0.05f, 0.05f), new(-0.15f, -0.05f, 0.05f), 8), Camera = Front };
        _session.Select(brush);
        int added = _session.State().Selection.Length;
        Assert.True(added >= n);

        _session.Select(new SelectRequest { Shape = rect.Shape, Mode = "subtract", Points = rect.Points, Camera = Front });
        var left = _session.State().Selection;
        Assert.Equal(added - n, left.Length);

        float[] lasso = [.. Line(Front, new(-0.1f, 0.12f, 0.08f), new(0.1f, 0.12f, 0.08f), 3), .. Line(Front, new(0.1f, 0f, 0.1f), new(-0.1f, 0f, 0.1f), 3)];
        _session.Select(new SelectRequest { Shape = "lasso", Points = lasso, Camera = Front });
        Assert.InRange(_session.State().Selection.Length, 5, 959);
        _session.ClearSelection();
        Assert.Empty(_session.State().Selection);
    }

    [Fact]
    public void FitGivesTheSelectedStrandsTheStrokesShapeAndUndoRemovesIt()
    {
        Settle();
        _session.SetPaused(true);
        _session.Select(new SelectRequest { Points = Line(Front, new(-0.06f, 0.1f, 0.08f), new(0.06f, 0.02f, 0.1f), 2), Camera = Front });
        var before = _session.Save();
        var stroke = new float[26];
        for (int i = 0; i <= 12; i++)
        {
            float t = i / 12f;
            var s = ThreeProject(Front, new Vector3(0, 0.1f + 0.05f * MathF.Sin(MathF.PI * t), 0.05f + 0.12f * t));
            stroke[2 * i] = s.X; stroke[2 * i + 1] = s.Y;
        }
        Assert.StartsWith("Fitted", _session.Fit(new StrokeRequest { Points = stroke, Camera = Front }));
        Assert.NotEqual(before, _session.Save());
        _session.Undo();
        Assert.Equal(before, _session.Save());
    }

    [Fact]
    public void RefusedCommandsLeaveTheHairAsItWas()
    {
        Settle(10);
        _session.SetPaused(true);
        var before = _session.Save();
        var line = Line(Front, new(-0.3f, -0.12f, 0.1f), new(0.3f, -0.12f, 0.1f));
        var nan = (float[])line.Clone(); nan[5] = float.NaN;
        var shortMatrix = new CameraRequest { View = Front.View![..15], Projection = Front.Projection, Width = Width, Height = Height };
        var refused = new Action[]
        {
            () => _session.Cut(new StrokeRequest { Points = nan, Camera = Front }),
            () => _session.Cut(new StrokeRequest { Points = line, Camera = shortMatrix }),
            () => _session.Cut(new StrokeRequest { Points = line }),
            () => _session.Cut(new StrokeRequest { Points = [1, 2, 3], Camera = Front }),
            () => _session.Fit(new StrokeRequest { Points = line, Camera = Front }),                       // nothing selected
            () => _session.Select(new SelectRequest { Shape = "circle", Points = line, Camera = Front }),
            () => _session.Select(new SelectRequest { Mode = "toggle", Points = line, Camera = Front }),
            () => _session.Select(new SelectRequest { Shape = "brush", Radius = float.NaN, Points = line, Camera = Front }),
            () => _session.ApplySettings(new SettingsRequest { Sag = 0.2f, Substeps = 0 }),              // one bad value: none applied
            () => _session.ApplySettings(new SettingsRequest { Gravity = float.NaN }),
            () => _session.ApplySettings(new SettingsRequest { Damping = -1 }),
            () => _session.ApplySettings(new SettingsRequest { Path = "Quantum" }),
            () => _session.ApplySettings(new SettingsRequest { Sag = 0.2f, Volume = true, VolumeFriction = float.NaN }), // none applied
            () => _session.ApplySettings(new SettingsRequest { Volume = true, VolumeDensity = 0f }),
            () => _session.Load([]),
            () => _session.Load("HSTY but not really a hairstyle"u8),
            () => _session.Load(before.AsSpan(0, before.Length - 9)),
            () => _session.SetHead(new HeadRequest { Position = [0, float.PositiveInfinity, 0] }),
            () => _session.SetGroom(new GroomRequest { Name = "bald" }),
            () => _session.SetGroom(new GroomRequest { Name = "small", StrandsPerSheet = 0 }),
            () => _session.Export("fbx"),
        };
        foreach (var command in refused) Assert.ThrowsAny<ArgumentException>(command);
        Assert.Equal(before, _session.Save());
        Assert.Equal(0.01f, _session.State().Settings.Sag);
        Assert.False(_session.State().Settings.Volume);
        Assert.Equal(0, _session.State().UndoCount);
    }

    [Fact]
    public void SaveLoadRoundTripsAndExportsHaveTheirFormats()
    {
        Settle();
        _session.Cut(new StrokeRequest { Points = Line(Front, new(-0.3f, -0.12f, 0.1f), new(0.3f, -0.12f, 0.1f)), Camera = Front });
        _session.SetPaused(true);
        var saved = _session.Save();
        var cut = _session.State();
        _session.Regrow();
        Assert.Equal(0, _session.State().CutStrands);
        Assert.StartsWith("Loaded", _session.Load(saved));
        var loaded = _session.State();
        Assert.Equal(cut.CutStrands, loaded.CutStrands);
        Assert.Equal(cut.TotalRestLength, loaded.TotalRestLength);
        Assert.True(loaded.CanRegrow, "a file of the groom's layout can still be regrown");
        _session.SetPaused(true);
        Assert.Equal(saved, _session.Save());

        Assert.Equal("HAIR"u8.ToArray(), _session.Export("hair").Data[..4]);
        Assert.Contains("\nl ", System.Text.Encoding.UTF8.GetString(_session.Export("obj").Data));
        Assert.StartsWith("#usda 1.0", System.Text.Encoding.UTF8.GetString(_session.Export("usda").Data));
    }

    [Fact]
    public void SettingsGroomsAndHeadApply()
    {
        _session.ApplySettings(new SettingsRequest { Sag = 0.2f, Gravity = 0.5f, Substeps = 6, StaticFriction = 0.5f, Path = "Reference" });
        var s = _session.State().Settings;
        Assert.Equal(0.2f, s.Sag);
        Assert.Equal(0.5f, s.Gravity!.Value, 5);
        Assert.Equal(6, s.Substeps);
        Assert.Equal("Reference", s.Path);
        Settle(5);
        Assert.Equal(0, _session.State().Metrics.NonFinite);

        _session.SetHead(new HeadRequest { Position = [0.05f, 0, 0], Yaw = 0.3f, Shake = true });
        Settle(30);
        var head = _session.State().Head;
        Assert.True(head.Shake);
        Assert.Equal(0.05f, head.Position![0]);

        // Hair volume: on with its own stiffness and friction, kept through a new groom, off again.
        _session.ApplySettings(new SettingsRequest { Volume = true, VolumeStiffness = 12f, VolumeFriction = 30f, VolumeDensity = 0.5f });
        Assert.True(_session.State().Settings.Volume);
        Assert.Equal((12f, 30f, 0.5f), (_session.State().Settings.VolumeStiffness, _session.State().Settings.VolumeFriction, _session.State().Settings.VolumeDensity));
        Settle(5);
        Assert.Equal(0, _session.State().Metrics.NonFinite);

        _session.SetGroom(new GroomRequest { Name = "small", StrandsPerSheet = 4 });
        var fresh = _session.State();
        Assert.Equal(480, fresh.Strands);
        Assert.Equal(0, fresh.UndoCount);
        Assert.False(fresh.Head.Shake);
        Assert.True(fresh.Settings.Volume, "hair volume is a studio setting: a new groom keeps it");
        Settle(5);
        Assert.Equal(0, _session.State().Metrics.NonFinite);
        _session.ApplySettings(new SettingsRequest { Volume = false });
        Assert.False(_session.State().Settings.Volume);
    }

    [Fact]
    public void RunningSessionStreamsNewFramesAndAnEditReachesTheNextFrame()
    {
        _session.Start();
        static uint FrameNumber(byte[] f) => BitConverter.ToUInt32(f, 4);
        var first = _session.Frame();
        SpinWait.SpinUntil(() => FrameNumber(_session.Frame()) > FrameNumber(first) + 3, TimeSpan.FromSeconds(20));
        Assert.True(FrameNumber(_session.Frame()) > FrameNumber(first) + 3, "frames advance while the simulation runs");
        int revision = BitConverter.ToInt32(_session.Frame(), 8);
        _session.Cut(new StrokeRequest { Points = Line(Front, new(-0.3f, -0.12f, 0.1f), new(0.3f, -0.12f, 0.1f)), Camera = Front });
        // The first frame asked for after an edit already carries the new revision (no stale topology is streamed).
        Assert.NotEqual(revision, BitConverter.ToInt32(_session.Frame(), 8));
        Assert.True(_session.State().SimHz >= 0);
    }

    [Fact]
    public void MeshHeadGroomCarriesItsMeshForThePageAndThroughSaveAndLoad()
    {
        Assert.Null(_session.Mesh());
        _session.SetGroom(new GroomRequest { Name = StudioGrooms.MeshHead, StrandsPerSheet = 4 });
        var state = _session.State();
        Assert.True(state.HasMesh);
        Assert.Empty(state.Colliders);
        var mesh = _session.Mesh()!;
        Assert.Equal("HSM1"u8.ToArray(), mesh[..4]);
        int vertices = BitConverter.ToInt32(mesh, 4), triangles = BitConverter.ToInt32(mesh, 8);
        Assert.InRange(triangles, 10_000, 50_000);
        Assert.Equal(12 + 12 * vertices + 12 * triangles, mesh.Length);
        Settle(30);
        Assert.True(_session.State().Metrics.MaxPenetrationMm < 1.0, $"{_session.State().Metrics.MaxPenetrationMm} mm inside the head mesh");
        _session.SetPaused(true);
        var saved = _session.Save();
        _session.Load(saved);
        Assert.True(_session.State().HasMesh, "the loaded haircut still collides with the head mesh");
        Assert.Equal(saved, _session.Save());
    }

    [Fact]
    public void A_head_of_the_users_own_carries_the_mesh_head_groom_and_its_scalp_can_be_painted()
    {
        // `studio --head file`: an egg-shaped head without colours (all of it scalp), read as a file would be.
        var own = HairSim.Meshes.TriangleMesh.Ellipsoid(new Vector3(0f, 0.02f, 0f), new Vector3(0.07f, 0.09f, 0.08f), 16, 32);
        string file = Path.Combine(Path.GetTempPath(), $"studio-head-{Guid.NewGuid():N}.obj");
        using (var w = new StreamWriter(file)) HairSim.Meshes.ObjReader.Write(w, own);
        try
        {
            var head = HairSim.Meshes.MeshFile.Load(file);
            using var session = new StudioSession(StudioGrooms.MeshHead, 4, ThreadDispatchers.CreateDefault(), head);
            var mesh = session.Mesh()!;
            Assert.Equal(own.TriangleCount, BitConverter.ToInt32(mesh, 8));
            Assert.True(session.State().HasMesh);
            // The scalp starts as the whole mesh (no colours) and is the one the page paints.
            var scalp = session.ScalpMask()!;
            Assert.Equal(own.TriangleCount, BitConverter.ToInt32(scalp, 8));
            Assert.All(scalp[12..], b => Assert.Equal(1, b));
            // The hair grew on this head: every root lies just outside the egg, far from the project's head's features.
            var roots = HairRoots(session);
            Assert.NotEmpty(roots);
            foreach (var r in roots)
            {
                var u = (r - new Vector3(0f, 0.02f, 0f)) / new Vector3(0.07f, 0.09f, 0.08f);
                Assert.InRange(u.Length(), 0.98f, 1.08f);
            }
        }
        finally { File.Delete(file); }
    }

    /// <summary>Each strand's root as the page receives the hair (decoded from a frame, by the topology's strand starts).</summary>
    private static List<Vector3> HairRoots(StudioSession session)
    {
        session.StepFrame();
        session.SetPaused(true);   // roots are pinned: where they grew
        var frame = session.Frame();
        var topology = session.Topology();
        var roots = new List<Vector3>();
        for (int s = 0; s < session.State().Strands; s++)
            roots.Add(FrameEncoder.DecodePosition(frame, BitConverter.ToInt32(topology, FrameEncoder.TopologyHeaderBytes + 16 * s)));
        return roots;
    }

    /// <summary>The head mesh's triangle centres and the painted mask, decoded from what the page receives.</summary>
    private (Vector3[] Centres, byte[] Mask) MeshAndScalp()
    {
        var mesh = _session.Mesh()!;
        int nv = BitConverter.ToInt32(mesh, 4), nt = BitConverter.ToInt32(mesh, 8);
        Vector3 V(int i) => new(BitConverter.ToSingle(mesh, 12 + 12 * i), BitConverter.ToSingle(mesh, 16 + 12 * i), BitConverter.ToSingle(mesh, 20 + 12 * i));
        var centres = new Vector3[nt];
        for (int t = 0; t < nt; t++)
        {
            int o = 12 + 12 * nv + 12 * t;
            centres[t] = (V(BitConverter.ToInt32(mesh, o)) + V(BitConverter.ToInt32(mesh, o + 4)) + V(BitConverter.ToInt32(mesh, o + 8))) / 3f;
        }
        var scalp = _session.ScalpMask()!;
        Assert.Equal("HSS1"u8.ToArray(), scalp[..4]);
        Assert.Equal(nt, BitConverter.ToInt32(scalp, 8));
        return (centres, scalp[12..]);
    }

    [Fact]
    public void PaintingTheScalpNeedsAMeshHeadAndSaysSo()
    {
        Settle(5);
        _session.SetPaused(true);
        var before = _session.Save();
        Assert.Null(_session.State().Scalp);
        Assert.Null(_session.ScalpMask());
        var stroke = new ScalpPaintRequest { Points = Line(Front, new(-0.04f, 0.085f, 0.05f), new(0.04f, 0.085f, 0.05f), 8), Camera = Front };
        var refused = new Func<string>[]
        {
            () => _session.PaintScalp(stroke), () => _session.FillScalp(new ScalpFillRequest { To = "none" }),
            _session.UndoScalp, _session.RedoScalp, _session.GrowOnScalp,
        };
        foreach (var command in refused) Assert.Contains("mesh head", Assert.ThrowsAny<ArgumentException>(() => command()).Message);
        Assert.Equal(before, _session.Save());
        Assert.Equal(0, _session.State().UndoCount);
    }

    [Fact]
    public void PaintedScalpGrowsHairOnlyThereStrokesUndoAndBadInputChangesNothing()
    {
        _session.SetGroom(new GroomRequest { Name = StudioGrooms.MeshHead, StrandsPerSheet = 4 });
        _session.SetPaused(true);
        var start = _session.State().Scalp!;
        Assert.Equal(1200, _session.State().Strands);
        Assert.True(start.Painted > 1000, $"painting starts from the mesh's vertex-colour scalp ({start.Painted} triangles)");
        Assert.Equal(1200, start.GrowStrands);   // the whole of the groom's own scalp grows the groom's strands
        var startMask = _session.ScalpMask();
        var hair = _session.Save();

        // Bad strokes: refused with a reason, the mask and the hair as they were.
        var line = Line(Front, new(-0.04f, 0.085f, 0.05f), new(0.04f, 0.085f, 0.05f), 8);
        var nan = (float[])line.Clone(); nan[3] = float.NaN;
        var refused = new Action[]
        {
            () => _session.PaintScalp(new ScalpPaintRequest { Shape = "lasso", Points = line[..4], Camera = Front }),          // two points
            () => _session.PaintScalp(new ScalpPaintRequest { Shape = "lasso", Points = [.. line[..2], .. line[..2], .. line[..2]], Camera = Front }), // no area
            () => _session.PaintScalp(new ScalpPaintRequest { Shape = "rectangle", Points = [.. line[..2], .. line[..2]], Camera = Front }),          // no size
            () => _session.PaintScalp(new ScalpPaintRequest { Points = nan, Camera = Front }),
            () => _session.PaintScalp(new ScalpPaintRequest { Points = line }),                                                  // no camera
            () => _session.PaintScalp(new ScalpPaintRequest { Points = line, Camera = Front, Mode = "smudge" }),
            () => _session.PaintScalp(new ScalpPaintRequest { Points = line, Camera = Front, Shape = "circle" }),
            () => _session.PaintScalp(new ScalpPaintRequest { Points = line, Camera = Front, Radius = 0 }),
            () => _session.PaintScalp(new ScalpPaintRequest { Points = [], Camera = Front }),
            () => _session.FillScalp(new ScalpFillRequest { To = "half" }),
        };
        foreach (var command in refused) Assert.ThrowsAny<ArgumentException>(command);
        Assert.Equal(startMask, _session.ScalpMask());
        Assert.Equal(0, _session.State().Scalp!.UndoCount);

        // An empty scalp grows nothing and keeps the hair.
        Assert.StartsWith("Scalp cleared", _session.FillScalp(new ScalpFillRequest { To = "none" }));
        Assert.Equal(0, _session.State().Scalp!.Painted);
        Assert.Contains("empty", Assert.ThrowsAny<ArgumentException>(_session.GrowOnScalp).Message);
        Assert.Equal(hair, _session.Save());

        // A brush stroke across the top of the forehead: painted there only, one undo step.
        const float radius = 25f;
        var cleared = _session.State().Scalp!;
        Assert.StartsWith("Painted", _session.PaintScalp(new ScalpPaintRequest { Shape = "brush", Mode = "add", Points = line, Radius = radius, Camera = Front }));
        var painted = _session.State().Scalp!;
        Assert.True(painted.Painted > 20, $"{painted.Painted} triangles painted");
        Assert.NotEqual(cleared.Revision, painted.Revision);
        Assert.Equal(2, painted.UndoCount);
        Assert.InRange(painted.GrowStrands, 4, 600);
        var (centres, mask) = MeshAndScalp();
        var camera = Front.ToStrokeCamera();
        var strokePoints = Enumerable.Range(0, line.Length / 2).Select(i => new Vector2(line[2 * i], line[2 * i + 1])).ToArray();
        float FromStroke(Vector2 p) => strokePoints.Min(q => Vector2.Distance(p, q));
        for (int t = 0; t < mask.Length; t++)
            if (mask[t] == 1)
            {
                Assert.True(camera.Project(centres[t], out var sc, out _) && FromStroke(sc) <= radius + 0.01f, $"triangle {t} painted off the stroke");
                Assert.True(centres[t].Z > 0, $"triangle {t} painted on the back of the head");
            }
        // Painting leaves the hair alone.
        Assert.Equal(hair, _session.Save());
        Assert.Equal(0, _session.State().UndoCount);

        // Grow: the groom's density on the painted area, every root on a painted triangle, under the stroke.
        Assert.StartsWith("Grew", _session.GrowOnScalp());
        var grown = _session.State();
        Assert.Equal(painted.GrowStrands, grown.Strands);
        Assert.Equal(0, grown.UndoCount);
        Assert.True(grown.CanRegrow, "the grown hair is the groom Regrow brings back");
        Settle(30);
        Assert.Equal(0, _session.State().Metrics.NonFinite);
        var paintedCentres = centres.Where((_, t) => mask[t] == 1).ToArray();
        _session.SetPaused(true);   // roots are pinned: where they grew
        var frame = _session.Frame();
        var topology = _session.Topology();
        for (int s = 0; s < grown.Strands; s++)
        {
            var root = FrameEncoder.DecodePosition(frame, BitConverter.ToInt32(topology, FrameEncoder.TopologyHeaderBytes + 16 * s));
            float nearest = paintedCentres.Min(c => Vector3.Distance(c, root));
            Assert.True(nearest < 0.006f, $"root of strand {s} is {nearest * 1000:F1} mm from the painted scalp");
            Assert.True(camera.Project(root, out var sc, out _) && FromStroke(sc) < radius + 15f, $"root of strand {s} at {sc} is off the stroke");
        }

        // Undo and redo take back paint strokes, not the hair.
        var grownHair = _session.Save();
        Assert.StartsWith("Scalp stroke undone", _session.UndoScalp());
        Assert.Equal(0, _session.State().Scalp!.Painted);
        Assert.Equal(grown.Strands, _session.State().Strands);
        _session.UndoScalp();
        Assert.Equal(startMask![12..], _session.ScalpMask()![12..]);
        Assert.StartsWith("Nothing to undo", _session.UndoScalp());
        _session.RedoScalp();
        _session.RedoScalp();
        Assert.Equal(painted.Painted, _session.State().Scalp!.Painted);
        Assert.Equal(grownHair, _session.Save());

        // Too small a patch for one sheet: refused with the reason, the hair kept.
        _session.FillScalp(new ScalpFillRequest { To = "none" });
        _session.PaintScalp(new ScalpPaintRequest { Points = line[..2], Radius = 4, Camera = Front });
        var tiny = _session.State().Scalp!;
        Assert.InRange(tiny.Painted, 1, 8);
        Assert.Equal(0, tiny.GrowStrands);
        Assert.Contains("too small", Assert.ThrowsAny<ArgumentException>(_session.GrowOnScalp).Message);
        Assert.Equal(grownHair, _session.Save());

        // Back to the mesh's colours and grow: the groom as it started.
        _session.FillScalp(new ScalpFillRequest { To = "colours" });
        Assert.Equal(startMask![12..], _session.ScalpMask()![12..]);
        _session.GrowOnScalp();
        Assert.Equal(1200, _session.State().Strands);

        // Another groom drops the painted scalp with its mesh.
        _session.SetGroom(new GroomRequest { Name = "small" });
        Assert.Null(_session.State().Scalp);
    }

    [Fact]
    public async Task HttpApiServesStateFramesAndRefusesBadRequestsWith400()
    {
        var (app, url) = await StudioServer.StartAsync(_session, "127.0.0.1", 0);
        try
        {
            using var http = new HttpClient { BaseAddress = new Uri(url) };
            var state = await http.GetFromJsonAsync<JsonElement>("api/state");
            Assert.Equal("small", state.GetProperty("groom").GetString());
            var frame = await http.GetByteArrayAsync("api/frame");
            Assert.Equal(FrameEncoder.FrameHeaderBytes + 6 * state.GetProperty("particles").GetInt32(), frame.Length);
            Assert.Contains("HairSheet Studio", await http.GetStringAsync("/"));

            var bad = await http.PostAsJsonAsync("api/cut", new { points = new[] { 1f, 2f } });
            Assert.Equal(HttpStatusCode.BadRequest, bad.StatusCode);
            Assert.Contains("camera", (await bad.Content.ReadFromJsonAsync<JsonElement>()).GetProperty("error").GetString());
            var corrupt = await http.PostAsync("api/load", new ByteArrayContent("nonsense"u8.ToArray()));
            Assert.Equal(HttpStatusCode.BadRequest, corrupt.StatusCode);
            Assert.Equal(HttpStatusCode.BadRequest, (await http.GetAsync("api/export/fbx")).StatusCode);

            var paint = await http.PostAsJsonAsync("api/scalp/paint", new { shape = "brush", points = new[] { 400f, 300f }, radius = 20f });
            Assert.Equal(HttpStatusCode.BadRequest, paint.StatusCode);
            Assert.Contains("mesh head", (await paint.Content.ReadFromJsonAsync<JsonElement>()).GetProperty("error").GetString());
            Assert.Equal(HttpStatusCode.NotFound, (await http.GetAsync("api/scalp")).StatusCode);
            Assert.Equal(JsonValueKind.Null, (await http.GetFromJsonAsync<JsonElement>("api/state")).GetProperty("scalp").ValueKind);

            var saved = await http.GetByteArrayAsync("api/save");
            var reload = await http.PostAsync("api/load", new ByteArrayContent(saved));
            Assert.Equal(HttpStatusCode.OK, reload.StatusCode);
        }
        finally { await app.StopAsync(); await app.DisposeAsync(); }
    }
}
