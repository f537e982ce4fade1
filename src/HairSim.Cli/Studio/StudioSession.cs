using System.Diagnostics;
using System.Numerics;
using HairSim.Editing;
using HairSim.IO;
using HairSim.Measurement;
using HairSim.Meshes;

namespace HairSim.Cli.Studio;

/// <summary>
/// One studio's hair: the scene, its simulation at 60 Hz on its own thread, the edit history, the selection and
/// the head the user drives. Everything the page does goes through here (HTTP is a thin layer over it), so it is
/// tested without a server. One lock serialises steps and edits: an edit lands between two frames, as in a game.
/// Every command checks its input before it changes anything; a refused command throws ArgumentException and
/// leaves the hair as it was.
/// </summary>
public sealed class StudioSession : IDisposable
{
    public const float FrameSeconds = 1f / 60f;
    public const int MaxStrokePoints = 10_000;

    private readonly object _gate = new();
    private readonly IDisposableDispatcher _threads;
    private HairScene _scene = null!;
    private HairSimulation _sim = null!;
    private EditHistory _history = null!;
    private HairWorld? _groomWorld;           // the freshly grown groom, for Regrow (null after loading another layout)
    private string _groomName = "";
    private StrandSelection? _selection;
    private int _revision;
    private long _frame;
    private double _simTime;
    private string _message = "";

    // The painted scalp of a mesh groom (null without a head mesh), how that groom grows, and the area of its own
    // (vertex-colour) scalp: growing on a painted scalp keeps the groom's strands per area.
    private ScalpPaint? _paint;
    private MeshGroomSettings? _meshGroom;
    private double _fullScalpArea;
    private int _scalpRevision;
    private volatile bool _growing;

    private Vector3 _headPosition;
    private float _yaw, _pitch, _roll;
    private bool _shake, _paused;
    private double _shakeTime;

    private double _stepMs, _stepMsWorst;
    private double _simHz;
    private WorldMetrics _metrics;

    // The latest encoded frame, published by the simulation thread after a step when a page asked for one, so a
    // request never waits for a step to finish (it gets the frame one step old) and the step never waits for the network.
    private sealed record EncodedFrame(byte[] Bytes, long Frame, int Revision);
    private volatile EncodedFrame? _published;
    private volatile bool _frameWanted;

    private Thread? _loop;
    private volatile bool _stop;

    /// <param name="head">The mesh the <see cref="StudioGrooms.MeshHead"/> groom grows on (`studio --head file`); null: the project's head.</param>
    public StudioSession(string groom = StudioGrooms.Default, int? strandsPerSheet = null, IDisposableDispatcher? threads = null, TriangleMesh? head = null)
    {
        _threads = threads ?? ThreadDispatchers.CreateDefault();
        _head = head;
        LoadGroom(groom, strandsPerSheet);
    }

    private readonly TriangleMesh? _head;

    /// <summary>Steps the hair at 60 Hz on a background thread until disposed (frames are dropped, not queued, when late).</summary>
    public void Start()
    {
        if (_loop != null) return;
        _loop = new Thread(Loop) { IsBackground = true, Name = "HairSheet Studio simulation" };
        _loop.Start();
    }

    private void Loop()
    {
        var clock = Stopwatch.StartNew();
        double next = 0, windowStart = 0;
        long windowFrames = 0;
        while (!_stop)
        {
            double now = clock.Elapsed.TotalSeconds;
            if (now < next) { Thread.Sleep(TimeSpan.FromSeconds(Math.Min(next - now, 0.005))); continue; }
            next = now - next > 3 * FrameSeconds ? now + FrameSeconds : next + FrameSeconds;
            if (StepFrame()) windowFrames++;
            if (now - windowStart >= 1.0)
            {
                _simHz = windowFrames / (now - windowStart);
                windowStart = now; windowFrames = 0;
            }
        }
    }

    /// <summary>One 1/60 s frame (unless paused); true if the hair moved.</summary>
    public bool StepFrame()
    {
        lock (_gate)
        {
            if (_paused) return false;
            if (_shake) _shakeTime += FrameSeconds;
            long t0 = Stopwatch.GetTimestamp();
            _sim.Step(FrameSeconds, HeadTarget());
            double ms = Stopwatch.GetElapsedTime(t0).TotalMilliseconds;
            _stepMs = _frame == 0 ? ms : 0.9 * _stepMs + 0.1 * ms;
            if (_frame > 30) _stepMsWorst = Math.Max(_stepMsWorst, ms);   // past the JIT's first frames
            _frame++;
            _simTime += FrameSeconds;
            if (_frame % 15 == 0) _metrics = WorldMetrics.Measure(_scene);
            if (_metrics.NonFinite > 0) { _paused = true; _message = "The simulation produced non-finite values and was paused: undo the last change or reset."; }
            if (_frameWanted) { _frameWanted = false; Publish(); }
            return true;
        }
    }

    private RigidTransform HeadTarget()
    {
        var rotation = Quaternion.CreateFromYawPitchRoll(_yaw, _pitch, _roll);
        var position = _headPosition;
        if (_shake)
        {
            var s = HeadMotion.Shake((float)_shakeTime);
            rotation = Quaternion.Normalize(rotation * s.Rotation);
            position += s.Position;
        }
        return new RigidTransform(position, rotation);
    }

    // ---------------- what the page reads ----------------

    /// <summary>
    /// The latest frame in the wire format of <see cref="FrameEncoder.EncodeFrame"/> (shared, do not modify). While the
    /// simulation runs on its thread this returns at once with the last published frame and asks for the next one.
    /// </summary>
    public byte[] Frame()
    {
        var p = _published;
        if (_loop != null && !_paused && p != null && p.Revision == _revision)
        {
            _frameWanted = true;
            return p.Bytes;
        }
        lock (_gate)
        {
            if (_published is not { } q || q.Frame != _frame || q.Revision != _revision) Publish();
            return _published!.Bytes;
        }
    }

    // Under the lock.
    private void Publish()
    {
        var b = new byte[FrameEncoder.FrameBytes(_scene.World)];
        FrameEncoder.EncodeFrame(_scene.World, _frame, _revision, (float)_stepMs, b);
        _published = new EncodedFrame(b, _frame, _revision);
    }

    public byte[] Topology() { lock (_gate) return FrameEncoder.EncodeTopology(_scene.World, _revision); }

    /// <summary>The mesh the hair collides with (head space), or null for heads made of colliders only.</summary>
    public byte[]? Mesh()
    {
        lock (_gate) return _scene.GetComponent<HairSim.Meshes.MeshCollider>()?.Mesh is { } m ? FrameEncoder.EncodeMesh(m) : null;
    }

    public StudioState State()
    {
        lock (_gate)
        {
            var w = _scene.World;
            int live = 0, cut = 0;
            for (int s = 0; s < w.StrandCount; s++)
            {
                live += w.StrandParticleCount[s];
                if (w.StrandParticleCount[s] < w.StrandCapacity[s]) cut++;
            }
            var st = _scene.Settings;
            var colliders = new List<ColliderState>(_scene.Colliders.Count);
            foreach (var collider in _scene.Colliders)
            {
                // The page draws colliders in head space; one fixed in the world is drawn where the head now sees it.
                var c = collider;
                var center = c.InWorld ? w.Head.InverseTransformPoint(c.Center) : c.Center;
                // A plane's end is its normal: a direction, not a point.
                var end = !c.InWorld ? c.End : c.Kind == ColliderKind.Plane ? w.Head.InverseTransformDirection(c.End) : w.Head.InverseTransformPoint(c.End);
                var rotation = c.InWorld ? Quaternion.Conjugate(w.Head.Rotation) * c.Rotation : c.Rotation;
                colliders.Add(new ColliderState(c.Kind.ToString(), Arr(center), Arr(end), Arr(c.Radii), [rotation.X, rotation.Y, rotation.Z, rotation.W]));
            }
            var selected = _selection?.Strands.ToArray() ?? [];
            return new StudioState(
                _groomName, StudioGrooms.All.Select(g => new GroomChoice(g.Name, g.Description)).ToArray(), _groomWorld != null,
                _scene.GetComponent<HairSim.Meshes.MeshCollider>()?.Mesh != null,
                w.StrandCount, w.ParticleCount, live, cut, w.TotalRestLength(), w.EditStamp,
                _revision, _frame, _simTime, _stepMs, _stepMsWorst, _simHz, _paused, _shake,
                _history.UndoCount, _history.RedoCount, selected,
                new MetricsState(_metrics.LengthRatio, _metrics.MaxEdgeStretch, _metrics.MaxPenetration * 1000, _metrics.ParticlesInside, _metrics.NonFinite),
                new SettingsRequest
                {
                    Sag = st.Sag, BendDamping = st.BendDamping, Damping = st.Damping, Gravity = -st.Gravity.Y / 9.81f, Substeps = st.Substeps,
                    StaticFriction = st.StaticFriction, KineticFriction = st.KineticFriction, Path = st.Path.ToString(),
                    Volume = _scene.HasComponent<VolumeSettings>(), VolumeStiffness = _volume.Stiffness, VolumeFriction = _volume.Friction,
                    VolumeDensity = _volume.Density,
                },
                new HeadRequest { Position = Arr(_headPosition), Yaw = _yaw, Pitch = _pitch, Roll = _roll, Shake = _shake },
                colliders.ToArray(),
                _paint == null ? null : new ScalpState(_paint.Mesh.TriangleCount, _paint.Count, _paint.Area * 1e4, _scalpRevision,
                    _paint.UndoCount, _paint.RedoCount, GrowCount(_paint.Area).Strands, _growing),
                _message);
        }
    }

    private static float[] Arr(Vector3 v) => [v.X, v.Y, v.Z];

    // ---------------- editing ----------------

    /// <summary>Cuts every strand the stroke crosses (the library's cut; <paramref name="visibleOnly"/> skips hair behind the head).</summary>
    public string Cut(StrokeRequest request)
    {
        var stroke = request.ToStroke();
        lock (_gate)
        {
            var cut = HairEditor.Cut(_scene, stroke, new CutOptions { Reach = request.VisibleOnly ? CutReach.VisibleOnly : CutReach.AllThrough });
            if (cut.Cuts.Count == 0) return Say("The stroke crossed no hair: nothing was cut.");
            _history.Do(cut);
            _revision++;
            return Say($"Cut {cut.Cuts.Count:N0} strands.");
        }
    }

    /// <summary>Selects strands in a rectangle, lasso or brush area, replacing, adding to or taking from the selection.</summary>
    public string Select(SelectRequest request)
    {
        var camera = request.Camera?.ToStrokeCamera() ?? throw new ArgumentException("A selection needs the camera it was drawn with.");
        var pts = StrokeRequest.ParsePoints(request.Points, 1);
        var options = new SelectionOptions { RootsOnly = request.RootsOnly, VisibleOnly = request.VisibleOnly };
        var areas = StrokeAreas(request.Shape, pts, request.Radius);
        if (request.Mode is not ("replace" or "add" or "subtract")) throw new ArgumentException($"Unknown selection mode '{request.Mode}': use replace, add or subtract.");
        lock (_gate)
        {
            var w = _scene.World;
            var mask = new bool[w.StrandCount];
            if (request.Mode != "replace" && _selection != null) foreach (int s in _selection.Strands) mask[s] = true;
            foreach (var area in areas)
                foreach (int s in HairEditor.Select(_scene, camera, area, options).Strands) mask[s] = request.Mode != "subtract";
            var chosen = new List<int>();
            for (int s = 0; s < mask.Length; s++) if (mask[s]) chosen.Add(s);
            _selection = new StrandSelection(w, chosen.ToArray());
            return Say($"{chosen.Count:N0} strands selected.");
        }
    }

    /// <summary>The screen areas of a rectangle (two corners), lasso (a polygon) or brush stroke (dabs along the path), for select and paint.</summary>
    private static List<SelectionArea> StrokeAreas(string? shape, Vector2[] pts, float radius)
    {
        var areas = new List<SelectionArea>();
        switch (shape)
        {
            case "rectangle":
                if (pts.Length < 2) throw new ArgumentException("A rectangle needs two corners.");
                if (MathF.Abs(pts[^1].X - pts[0].X) < 1f || MathF.Abs(pts[^1].Y - pts[0].Y) < 1f)
                    throw new ArgumentException("A rectangle needs a width and a height: drag its corners apart.");
                areas.Add(SelectionArea.Rectangle(pts[0], pts[^1]));
                break;
            case "lasso":
                if (pts.Length < 3) throw new ArgumentException("A lasso needs at least three points.");
                areas.Add(SelectionArea.Lasso(pts));
                break;
            case "brush":
                if (!float.IsFinite(radius) || radius <= 0f || radius > 2000f)
                    throw new ArgumentException("Brush radius must be in (0, 2000] pixels.");
                areas.AddRange(SelectionArea.BrushStroke(pts, radius));
                break;
            default:
                throw new ArgumentException($"Unknown stroke shape '{shape}': use rectangle, lasso or brush.");
        }
        return areas;
    }

    public string ClearSelection() { lock (_gate) { _selection = null; return Say("Selection cleared."); } }

    /// <summary>Fits the selected strands to the stroke: the stroke becomes their shape, and their rest shape.</summary>
    public string Fit(StrokeRequest request)
    {
        var stroke = request.ToStroke();
        lock (_gate)
        {
            if (_selection == null || _selection.Count == 0) throw new ArgumentException("Nothing is selected: select strands (rectangle, lasso or brush) before fitting.");
            var fit = HairEditor.Fit(_scene, _selection, stroke);
            _history.Do(fit);
            _revision++;
            return Say($"Fitted {_selection.Count:N0} strands to the stroke.");
        }
    }

    public string Undo() { lock (_gate) { if (!_history.Undo()) return Say("Nothing to undo."); _revision++; return Say("Undone."); } }
    public string Redo() { lock (_gate) { if (!_history.Redo()) return Say("Nothing to redo."); _revision++; return Say("Redone."); } }

    /// <summary>Regrows every strand at full length from the groom (undoable).</summary>
    public string Regrow()
    {
        lock (_gate)
        {
            if (_groomWorld == null) throw new ArgumentException("This hairstyle was loaded from a file with another layout; choose a groom to start afresh.");
            _history.Do(HairEditor.Regrow(_scene, _groomWorld, _selection is { Count: > 0 } ? _selection : null));
            _revision++;
            return Say(_selection is { Count: > 0 } ? $"Regrew {_selection.Count:N0} selected strands." : "Regrew all strands.");
        }
    }

    /// <summary>Puts the hair (selected strands, or all) back at its rest pose, at rest (undoable): hair that tangled comes loose.</summary>
    public string ResetPose()
    {
        lock (_gate)
        {
            _history.Do(HairEditor.ResetToRest(_scene, _selection is { Count: > 0 } ? _selection : null));
            _revision++;
            if (_paused && _scene.World.CountNonFinite() == 0) _paused = false;
            return Say("Hair put back at its rest pose.");
        }
    }

    public byte[] Save()
    {
        lock (_gate)
        {
            using var m = new MemoryStream();
            HairstyleFile.Save(_scene, m);
            return m.ToArray();
        }
    }

    /// <summary>Loads a .hairstyle: the haircut, its settings and colliders replace the current ones (which stay if the file is refused).</summary>
    public string Load(ReadOnlySpan<byte> data)
    {
        if (data.Length == 0) throw new ArgumentException("The file is empty.");
        HairScene loaded;
        try { loaded = HairstyleFile.Load(data); }
        catch (InvalidDataException e) { throw new ArgumentException($"Not a HairSheet hairstyle: {e.Message}", e); }
        lock (_gate)
        {
            var keepGroom = _groomWorld != null && loaded.World.SameLayout(_groomWorld) ? _groomWorld : null;
            // A hairstyle file holds the hair, not the head mesh: a haircut of this groom keeps colliding with its mesh.
            if (keepGroom != null && _scene.GetComponent<HairSim.Meshes.MeshCollider>() is { } mesh) loaded.SetComponent(mesh);
            Install(loaded, keepGroom, keepGroom != null ? _groomName : "loaded file");
            var head = loaded.World.Head;
            _headPosition = head.Position;
            (_yaw, _pitch, _roll) = YawPitchRoll(head.Rotation);
            return Say($"Loaded a hairstyle of {loaded.World.StrandCount:N0} strands.");
        }
    }

    /// <summary>The current strands as a file: "hair" (Cem Yuksel's .hair), "obj" (polylines) or "usda" (USD BasisCurves).</summary>
    public (byte[] Data, string FileName, string ContentType) Export(string format)
    {
        lock (_gate)
        {
            var curves = StrandCurves.FromWorld(_scene.World);
            using var m = new MemoryStream();
            switch (format)
            {
                case "hair":
                    CurveExport.WriteCyHair(m, curves);
                    return (m.ToArray(), "haircut.hair", "application/octet-stream");
                case "obj":
                    using (var o = new StreamWriter(m, leaveOpen: true)) CurveExport.WriteObj(o, curves);
                    return (m.ToArray(), "haircut.obj", "text/plain");
                case "usda":
                    using (var o = new StreamWriter(m, leaveOpen: true)) CurveExport.WriteUsda(o, curves);
                    return (m.ToArray(), "haircut.usda", "text/plain");
                default:
                    throw new ArgumentException($"Unknown export format '{format}': use hair, obj or usda.");
            }
        }
    }

    /// <summary>Changes settings live; values are checked together first and nothing changes if any is refused.</summary>
    public string ApplySettings(SettingsRequest r)
    {
        lock (_gate)
        {
            var next = _scene.Settings.Clone();
            if (r.Sag is float sag) next.Sag = sag;
            if (r.BendDamping is float bd) next.BendDamping = bd;
            if (r.Damping is float d) next.Damping = d;
            if (r.Gravity is float g)
            {
                if (!float.IsFinite(g) || g < 0f || g > 10f) throw new ArgumentException("Gravity must be 0 … 10 g.");
                next.Gravity = new Vector3(0f, -9.81f * g, 0f);
            }
            if (r.Substeps is int n)
            {
                if (n < 1 || n > 32) throw new ArgumentException("Substeps must be 1 … 32.");
                next.Substeps = n;
            }
            if (r.StaticFriction is float fs) next.StaticFriction = fs;
            if (r.KineticFriction is float fk) next.KineticFriction = fk;
            if (r.Path != null)
            {
                if (!Enum.TryParse<SolverPath>(r.Path, ignoreCase: true, out var path) || !Enum.IsDefined(path))
                    throw new ArgumentException($"Unknown solver path '{r.Path}': use Fast or Reference.");
                next.Path = path;
            }
            next.Validate();
            var volume = _volume.Clone();
            if (r.VolumeStiffness is float vs) volume.Stiffness = vs;
            if (r.VolumeFriction is float vf) volume.Friction = vf;
            if (r.VolumeDensity is float vd) volume.Density = vd;
            volume.Validate();
            next.CopyTo(_scene.Settings);
            _scene.SettingsChanged();
            _volume = volume;
            if (r.Volume is bool on) _volumeOn = on;
            ApplyVolume(_scene);
            return Say("Settings applied.");
        }
    }

    /// <summary>Starts afresh with a named groom (the edit history is cleared: the old hair is gone).</summary>
    public string SetGroom(GroomRequest r)
    {
        StudioGrooms.Create(r.Name ?? StudioGrooms.Default, r.StrandsPerSheet);   // refuse bad values before anything changes
        lock (_gate)
        {
            LoadGroom(r.Name ?? StudioGrooms.Default, r.StrandsPerSheet);
            return Say($"New groom '{_groomName}': {_scene.World.StrandCount:N0} strands.");
        }
    }

    /// <summary>Where the user holds the head (position in metres, yaw/pitch/roll in radians) and whether it shakes.</summary>
    public string SetHead(HeadRequest r)
    {
        var p = r.Position ?? [0f, 0f, 0f];
        if (p.Length != 3 || !float.IsFinite(p[0] + p[1] + p[2]) || MathF.Abs(p[0]) + MathF.Abs(p[1]) + MathF.Abs(p[2]) > 1000f)
            throw new ArgumentException("Head position must be three finite numbers within 1 km.");
        if (!float.IsFinite(r.Yaw + r.Pitch + r.Roll) || MathF.Abs(r.Yaw) + MathF.Abs(r.Pitch) + MathF.Abs(r.Roll) > 100f)
            throw new ArgumentException("Head angles must be finite radians.");
        lock (_gate)
        {
            _headPosition = new Vector3(p[0], p[1], p[2]);
            _yaw = r.Yaw; _pitch = r.Pitch; _roll = r.Roll;
            if (r.Shake != _shake) { _shake = r.Shake; _shakeTime = 0; }
            return "";
        }
    }

    public string SetPaused(bool paused) { lock (_gate) { _paused = paused; return Say(paused ? "Paused." : "Running."); } }

    // ---------------- the scalp of a mesh head ----------------

    /// <summary>Most strands a grow on the painted scalp makes (a face, neck and ears painted at a high density would make many more).</summary>
    public const int MaxGrowStrands = 60_000;

    /// <summary>
    /// Paints (mode "add") or erases (mode "erase") the head mesh's scalp under a rectangle, lasso or brush stroke:
    /// the library's <see cref="ScalpPaint"/>, through the camera the stroke was drawn with, at the head's pose, the mesh
    /// hiding what lies behind it. One undo step per stroke (<see cref="UndoScalp"/>); the hair changes only on
    /// <see cref="GrowOnScalp"/>.
    /// </summary>
    public string PaintScalp(ScalpPaintRequest request)
    {
        if (_paint == null) throw new ArgumentException(NoMeshHead);
        var camera = request.Camera?.ToStrokeCamera() ?? throw new ArgumentException("A paint stroke needs the camera it was drawn with.");
        var mode = request.Mode switch
        {
            "add" => ScalpPaintMode.Add,
            "erase" => ScalpPaintMode.Remove,
            _ => throw new ArgumentException($"Unknown paint mode '{request.Mode}': use add or erase."),
        };
        var areas = StrokeAreas(request.Shape, StrokeRequest.ParsePoints(request.Points, 1), request.Radius);
        lock (_gate)
        {
            var paint = PaintOrRefuse();
            int n = paint.Paint(camera, areas, mode, _scene.World.Head, _scene.GetComponent<MeshCollider>());
            if (n == 0)
                return Say(mode == ScalpPaintMode.Add
                    ? "The stroke covered no unpainted part of the head facing you: nothing changed."
                    : "The stroke covered no painted part of the head facing you: nothing changed.");
            _scalpRevision++;
            return Say($"{(mode == ScalpPaintMode.Add ? "Painted" : "Erased")} {n:N0} triangles: {DescribeScalp(paint)}.");
        }
    }

    /// <summary>The whole mask at once (undoable): "none" clears it, "all" paints every triangle, "colours" goes back to the mesh's vertex-colour scalp.</summary>
    public string FillScalp(ScalpFillRequest request)
    {
        lock (_gate)
        {
            var paint = PaintOrRefuse();
            var mask = request.To switch
            {
                "none" => new bool[paint.Mesh.TriangleCount],
                "all" => Enumerable.Repeat(true, paint.Mesh.TriangleCount).ToArray(),
                "colours" => ScalpPaint.FromVertexColours(paint.Mesh, StudioGrooms.ScalpMaskThreshold).Triangles.ToArray(),
                _ => throw new ArgumentException($"Unknown scalp fill '{request.To}': use none, all or colours."),
            };
            if (paint.SetMask(mask) == 0) return Say($"Nothing changed: {DescribeScalp(paint)}.");
            _scalpRevision++;
            return Say($"Scalp {(request.To == "none" ? "cleared" : request.To == "all" ? "painted everywhere" : "set from the mesh's colours")}: {DescribeScalp(paint)}.");
        }
    }

    public string UndoScalp() => StepScalpHistory(undo: true);
    public string RedoScalp() => StepScalpHistory(undo: false);

    private string StepScalpHistory(bool undo)
    {
        lock (_gate)
        {
            var paint = PaintOrRefuse();
            if (!(undo ? paint.Undo() : paint.Redo())) return Say($"Nothing to {(undo ? "undo" : "redo")} on the scalp.");
            _scalpRevision++;
            return Say($"Scalp stroke {(undo ? "undone" : "redone")}: {DescribeScalp(paint)}.");
        }
    }

    /// <summary>
    /// Grows the groom again on the painted scalp, at the groom's density (strands per area of its own scalp), with
    /// the current settings; the new hair replaces the old (the haircut and its undo history go, as with a new groom;
    /// the painted scalp and its strokes stay). The growth runs outside the simulation's lock, so the running hair
    /// keeps moving meanwhile, and it is kept if the growth is refused (an empty or too small scalp, too few roots).
    /// </summary>
    public string GrowOnScalp()
    {
        MeshCollider collider;
        MeshGroomSettings settings;
        SimulationSettings simulation;
        double area;
        lock (_gate)
        {
            var paint = PaintOrRefuse();
            if (_growing) throw new ArgumentException("Hair is already growing on the scalp: wait for it to finish.");
            if (paint.Count == 0) throw new ArgumentException("The painted scalp is empty: paint where hair should grow (Paint scalp, add) first. The hair was kept.");
            area = paint.Area;
            var (sheets, strands) = GrowCount(area);
            if (sheets < 1)
                throw new ArgumentException($"The painted scalp ({area * 1e4:F1} cm²) is too small for one sheet of {_meshGroom!.StrandsPerSheet} strands at this density: paint more. The hair was kept.");
            if (strands > MaxGrowStrands)
                throw new ArgumentException($"The painted scalp ({area * 1e4:F0} cm²) would grow {strands:N0} strands at this density, more than {MaxGrowStrands:N0}: erase some or lower the density. The hair was kept.");
            collider = _scene.GetComponent<MeshCollider>()!;
            var g = _meshGroom!;
            settings = new MeshGroomSettings
            {
                SheetCount = sheets, StrandsPerSheet = g.StrandsPerSheet, ParticlesPerStrand = g.ParticlesPerStrand, StrandLength = g.StrandLength,
                PinnedPerStrand = g.PinnedPerStrand, RootLift = g.RootLift, Drape = g.Drape, Seed = g.Seed, Scalp = paint.CopyMask(),
            };
            simulation = _scene.Settings.Clone();
            _growing = true;
        }
        try
        {
            long t0 = Stopwatch.GetTimestamp();
            HairScene scene;
            try { scene = MeshScalp.BuildScene(collider.Mesh!, collider.Field, settings, simulation); }
            catch (ArgumentException e) { throw new ArgumentException($"No hair grown: {e.Message} The hair was kept.", e); }
            lock (_gate)
            {
                if (!ReferenceEquals(_paint?.Mesh, collider.Mesh))
                    throw new ArgumentException("The head changed while the hair grew: the new hair was dropped.");
                Install(scene, scene.World.Clone(), _groomName);
                var took = Stopwatch.GetElapsedTime(t0);
                return Say($"Grew {scene.World.StrandCount:N0} strands on the painted scalp ({area * 1e4:F0} cm²) in " +
                    (took.TotalSeconds < 1 ? $"{took.TotalMilliseconds:F0} ms." : $"{took.TotalSeconds:F1} s."));
            }
        }
        finally { _growing = false; }
    }

    /// <summary>The painted scalp for the page (see <see cref="FrameEncoder.EncodeScalp"/>), or null without a head mesh.</summary>
    public byte[]? ScalpMask()
    {
        lock (_gate) return _paint == null ? null : FrameEncoder.EncodeScalp(_paint, _scalpRevision);
    }

    private const string NoMeshHead = "Only a head mesh's scalp can be painted: grow the 'mesh head' groom first.";

    private ScalpPaint PaintOrRefuse() => _paint ?? throw new ArgumentException(NoMeshHead);

    /// <summary>Sheets and strands a grow on this much scalp makes: the groom's sheets in proportion to its own scalp's area.</summary>
    private (int Sheets, int Strands) GrowCount(double area)
    {
        if (_meshGroom == null || !(_fullScalpArea > 0)) return (0, 0);
        int sheets = (int)Math.Min(int.MaxValue / 2, Math.Round(_meshGroom.SheetCount * area / _fullScalpArea));
        return (sheets, (int)Math.Min(int.MaxValue / 2, (long)sheets * _meshGroom.StrandsPerSheet));
    }

    private string DescribeScalp(ScalpPaint paint)
    {
        double area = paint.Area;
        return $"the scalp is now {area * 1e4:F0} cm² ({paint.Count:N0} triangles) and grows {GrowCount(area).Strands:N0} strands";
    }

    // ---------------- internals ----------------

    private string Say(string message) => _message = message;

    private void LoadGroom(string name, int? strandsPerSheet)
    {
        var scene = StudioGrooms.BuildScene(name, strandsPerSheet, _head);
        Install(scene, scene.World.Clone(), name.ToLowerInvariant());
        if (scene.GetComponent<MeshCollider>()?.Mesh is { } mesh && StudioGrooms.IsMesh(name))
        {
            // Painting starts from the mesh's own scalp, the one the groom grew on.
            _paint = ScalpPaint.FromVertexColours(mesh, StudioGrooms.ScalpMaskThreshold);
            _meshGroom = StudioGrooms.MeshSettings(StudioGrooms.Create(name, strandsPerSheet));
            _fullScalpArea = _paint.Area;
            _scalpRevision++;
        }
        _headPosition = Vector3.Zero; _yaw = _pitch = _roll = 0f; _shake = false;
    }

    // Hair volume outlives a new groom or a loaded haircut: it is a setting of the studio, not of the hair.
    private VolumeSettings _volume = new();
    private bool _volumeOn;

    private void ApplyVolume(HairScene scene)
    {
        if (_volumeOn) scene.SetComponent(_volume.Clone());
        else scene.RemoveComponent<VolumeSettings>();
    }

    private void Install(HairScene scene, HairWorld? groomWorld, string name)
    {
        ApplyVolume(scene);
        _scene = scene;
        _sim = new HairSimulation(scene, dispatcher: _threads);
        _history = new EditHistory();
        scene.SetComponent(_history);
        _groomWorld = groomWorld;
        _groomName = name;
        // The painted scalp belongs to its mesh: hair without that mesh (another groom, another file) drops it.
        if (_paint != null && !ReferenceEquals(scene.GetComponent<MeshCollider>()?.Mesh, _paint.Mesh))
        {
            _paint = null; _meshGroom = null; _fullScalpArea = 0; _scalpRevision++;
        }
        _selection = null;
        _revision++;
        _stepMsWorst = 0;
        _paused = false;
        _metrics = WorldMetrics.Measure(scene);
    }

    private static (float Yaw, float Pitch, float Roll) YawPitchRoll(Quaternion q)
    {
        // Inverse of Quaternion.CreateFromYawPitchRoll (yaw about Y, then pitch about X, then roll about Z).
        float sinPitch = 2f * (q.W * q.X - q.Y * q.Z);
        float pitch = MathF.Abs(sinPitch) >= 1f ? MathF.CopySign(MathF.PI / 2, sinPitch) : MathF.Asin(sinPitch);
        float yaw = MathF.Atan2(2f * (q.W * q.Y + q.X * q.Z), 1f - 2f * (q.X * q.X + q.Y * q.Y));
        float roll = MathF.Atan2(2f * (q.W * q.Z + q.X * q.Y), 1f - 2f * (q.X * q.X + q.Z * q.Z));
        return (yaw, pitch, roll);
    }

    public void Dispose()
    {
        _stop = true;
        _loop?.Join();
        _threads.Dispose();
    }
}
