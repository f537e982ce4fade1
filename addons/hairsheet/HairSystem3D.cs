using System;
using System.Collections.Generic;
using System.Diagnostics;
using Godot;
using HairSheet.Logic;
using HairSim;

namespace HairSheet;

/// <summary>
/// The hair node. Owns a HairScene and its HairSimulation, builds the pipeline its settings and child
/// collider nodes call for, steps it in _PhysicsProcess with a fixed step, and pins the roots to a head
/// node's global transform (a game character's head bone or an AR-tracked head). The groom comes from the
/// assigned <see cref="Hairstyle"/> if any, else from the Groom properties. Edits (cut, fit) go through
/// <see cref="ApplyEdit"/> at run time, or through the editor's undo manager (StageEdit + RedoEditIn/UndoEditIn, which
/// name the hair generation the edit was made on: see <see cref="Generation"/>).
/// </summary>
[Tool]
[GlobalClass]
public partial class HairSystem3D : Node3D
{
    [Signal] public delegate void SceneRebuiltEventHandler();
    [Signal] public delegate void StyleChangedEventHandler();
    /// <summary>An editor undo or redo entry did nothing because its hair is not the one shown; the message says why.</summary>
    [Signal] public delegate void EditSkippedEventHandler(string message);

    /// <summary>
    /// One growth: the scene, its edit history and the ellipsoid groom it was grown from; or, grown on a scalp mesh, no
    /// groom and the mesh collider of the scalp's field.
    /// </summary>
    private sealed record GrownHair(HairScene Scene, HairEditSession Edits, GroomSettings? Groom, HairSim.Meshes.MeshCollider? ScalpCollider);

    /// <summary>A scalp mesh as read for one growth: its surfaces, their transform into head space and its key.</summary>
    private sealed record ScalpInput(List<MeshSurfaces.Surface> Surfaces, System.Numerics.Matrix4x4 MeshToHead, string Key);

    private readonly HairNodeSettings _settings = new();
    // Each exported value has its own field with an initializer equal to HairNodeSettings' default: Godot's source
    // generator takes an exported property's default from its backing field's initializer, and records default(T)
    // for a getter like `_settings.X`, so a value of 0 would not be saved and every property would show a revert
    // arrow to 0 (godot #90872, #105348). Checked against HairNodeSettings by ExportDefaultsTests.
    private int _sheets = 435;
    private int _strandsPerSheet = 40;
    private int _particlesPerStrand = 16;
    private float _strandLength = 0.25f;
    private Vector3 _headRadii = new Vector3(0.078f, 0.1f, 0.095f);
    private BendModel _bend = BendModel.RestShape;
    private float _sag = 0.01f;
    private float _bendDamping = 0.5f;
    private float _stiffness = 1f;
    private float _damping = 0.32f;
    private int _substeps = 4;
    private float _staticFriction = 0f;
    private float _kineticFriction = 0f;
    private Vector3 _gravity = new Vector3(0f, -9.81f, 0f);
    private int _stepsPerSecond = 60;
    private bool _hairVolume = false;
    private float _volumeStiffness = 8f;
    private float _volumeDensity = 1f;
    private float _volumeFriction = 50f;
    private float _volumeMaxStep = 0.125f;
    private bool _strandContacts = false;
    private float _contactThickness = 0.25f;
    private float _contactFriction = 0.3f;
    private int _renderDensity = 1;
    private Color _rootColor = new Color(0.16f, 0.10f, 0.06f, 1f);
    private Color _tipColor = new Color(0.45f, 0.32f, 0.20f, 1f);
    private float _rootWidth = 0.0012f;
    private float _tipWidth = 0.0002f;
    private Hairstyle? _hairstyle;
    private MeshInstance3D? _scalpMesh;
    private HairMeshField? _scalpField;
    private HairScalpMask? _scalpMask;
    // What the live hair grown on a Scalp Mesh was grown from, as a haircut's key (Logic/ScalpGrowth.StyleKey; null: the
    // ellipsoid groom), and whether the Hairstyle resource may take this hair's style (not when it holds another's).
    private string? _styleKey;
    private bool _styleWritable = true;
    private MeshInstance3D? _scalpOverlay;
    private float _scalpMaskThreshold = 0.5f;
    private float _scalpRootLift = 0.002f;
    private float _scalpDrape = 1f;
    private float _scalpCellSize = 0.0025f;
    // The last field baked for a scalp (its field key): a regrow with other groom values does not bake again.
    private (string Key, HairSim.Meshes.SignedDistanceField Field)? _bakedScalpField;
    private HairSim.Meshes.MeshCollider? _scalpCollider;
    private Node3D? _head;
    private bool _useHeadEllipsoid = true;
    private bool _simulateInEditor = true;
    private bool _stepOnWorker = false;
    private BackgroundStepper? _stepper;
    private HairScene? _scene;
    private HairSimulation? _simulation;
    private IDisposableDispatcher? _dispatcher;
    private HairEditSession? _edits;
    private HairEdit? _pendingEdit;
    // Earlier growths that hold edits are kept (two: each is a whole scene), so undoing the value change that regrew
    // the hair brings them back with their history (Logic/HairGenerations).
    private readonly HairGenerations<GrownHair> _generations = new(maxKept: 2);
    private FixedStepClock _clock = new(1.0 / 60);
    private GroomSettings? _groom;   // null for hair grown on a scalp mesh
    private HairMultiMeshRenderer? _renderer;
    private IReadOnlyList<string> _problems = Array.Empty<string>();
    private bool _needsRebuild = true, _collidersDirty = true;
    private readonly Stopwatch _stepTimer = new();
    private RigidTransform _lastHeadPose = RigidTransform.Identity;
    private string? _headProblem;
    // The mesh collider nodes whose fields follow a node or bone in world space: placed before every step.
    private HairMeshCollider3D[] _followingFields = [];
    // Primitive collider nodes that follow a node or bone, and their indices in the scene's colliders: moved before every step.
    private IHairFollowingCollider[] _followers = [];
    private int[] _followerIndices = [];

    // ---- Groom ----
    /// <summary>A saved groom (overrides the Groom numbers below when set); for hair grown on a Scalp Mesh, its haircut.</summary>
    [ExportGroup("Groom")]
    [Export] public Hairstyle? Hairstyle
    {
        get => _hairstyle;
        set
        {
            // Follow the resource's edits in the inspector (its groom setters emit Changed; StyleData, which this node
            // writes after every edit, does not, so there is no loop through OnStyleChanged).
            if (_hairstyle != null) _hairstyle.Changed -= Invalidate;
            _hairstyle = value;
            if (_hairstyle != null) _hairstyle.Changed += Invalidate;
            Invalidate();
        }
    }
    [Export(PropertyHint.Range, "1,2000,1")] public int Sheets { get => _sheets; set { _sheets = value; _settings.Sheets = value; Invalidate(); } }
    [Export(PropertyHint.Range, "1,256,1")] public int StrandsPerSheet { get => _strandsPerSheet; set { _strandsPerSheet = value; _settings.StrandsPerSheet = value; Invalidate(); } }
    [Export(PropertyHint.Range, "3,64,1")] public int ParticlesPerStrand { get => _particlesPerStrand; set { _particlesPerStrand = value; _settings.ParticlesPerStrand = value; Invalidate(); } }
    [Export(PropertyHint.Range, "0.01,2,0.005,suffix:m")] public float StrandLength { get => _strandLength; set { _strandLength = value; _settings.StrandLength = value; Invalidate(); } }
    [Export] public Vector3 HeadRadii { get => _headRadii; set { _headRadii = value; _settings.HeadRadii = value.ToNumerics(); Invalidate(); } }

    // ---- Scalp ----
    /// <summary>
    /// Grow the hair on this mesh (a character's head) instead of the Head Radii ellipsoid, and collide with it through
    /// its distance field. Its surfaces are read in the head's frame each time the hair grows; where hair grows is
    /// painted in the vertex colours' red channel. Sheets, Strands Per Sheet, Particles Per Strand, Strand Length and
    /// the Scalp values below shape the groom. A Hairstyle resource then keeps this hair's haircut (cuts and fits), not a
    /// groom: it is applied again whenever the hair grows from the same scalp, painted scalp and groom values.
    /// </summary>
    [ExportGroup("Scalp")]
    [Export] public MeshInstance3D? ScalpMesh { get => _scalpMesh; set { _scalpMesh = value; Invalidate(); } }
    /// <summary>A vertex is scalp where its colour's red channel is at least this (0 = the whole mesh; a mesh without colours grows everywhere).</summary>
    [Export(PropertyHint.Range, "0,1,0.01")] public float ScalpMaskThreshold { get => _scalpMaskThreshold; set { _scalpMaskThreshold = value; _settings.ScalpMaskThreshold = value; Invalidate(); } }
    /// <summary>Hair starts this far above the scalp; the collision keeps hair half of it off the surface.</summary>
    [Export(PropertyHint.Range, "0,0.02,0.0001,suffix:m")] public float ScalpRootLift { get => _scalpRootLift; set { _scalpRootLift = value; _settings.ScalpRootLift = value; Invalidate(); } }
    /// <summary>0: strands stand out along the surface normal; 1: they turn to hang down.</summary>
    [Export(PropertyHint.Range, "0,1,0.01")] public float ScalpDrape { get => _scalpDrape; set { _scalpDrape = value; _settings.ScalpDrape = value; Invalidate(); } }
    /// <summary>Cell of the scalp's distance field: about a quarter of the thinnest part the hair must feel (2.5 mm for 1 cm ears; coarser lets hair into them).</summary>
    [Export(PropertyHint.Range, "0.0005,0.02,0.0005,suffix:m")] public float ScalpCellSize { get => _scalpCellSize; set { _scalpCellSize = value; _settings.ScalpCellSize = value; Invalidate(); } }
    /// <summary>
    /// The scalp's stored distance field (Bake Scalp Field writes one next to the scene): used when it was baked from
    /// this mesh, in this place, at this cell size; otherwise the field is baked whenever the hair grows (about a second
    /// for a 25k-triangle head), at run time too.
    /// </summary>
    [Export] public HairMeshField? ScalpField { get => _scalpField; set => _scalpField = value; }
    /// <summary>
    /// Where hair grows, painted with the editor's Paint scalp / Erase scalp tools (a brush on the Scalp Mesh, undoable):
    /// used instead of the vertex colours when it was painted on this mesh in this place; otherwise the colours decide
    /// and the Output panel says why. Clear it to go back to the colours.
    /// </summary>
    [Export] public HairScalpMask? ScalpMask { get => _scalpMask; set { _scalpMask = value; Invalidate(); RefreshScalpOverlay(); } }
    [ExportToolButton("Bake scalp field")]
    public Callable BakeScalpFieldButton => Callable.From(BakeScalpField);
    /// <summary>Reads the scalp mesh again (after it was edited or reimported): regrows if it changed, keeps the hair and its edits if not.</summary>
    [ExportToolButton("Read scalp again")]
    public Callable RereadScalpButton => Callable.From(() => Rebuild());

    // ---- Simulation ----
    /// <summary>The head the roots follow; empty = this node's own transform.</summary>
    [ExportGroup("Simulation")]
    [Export] public Node3D? Head { get => _head; set { _head = value; _collidersDirty = true; } }
    /// <summary>What keeps the shape: the rest shape (styles hold), the source's triples, or nothing (limp).</summary>
    [Export] public BendModel Bend { get => _bend; set { _bend = value; _settings.Bend = value; Invalidate(); } }
    /// <summary>Tip sag of a horizontal strand under 1 g, share of its length: 0.01 holds a style, 0.1 soft, 1 nearly limp. Same look at any size and rate.</summary>
    [Export(PropertyHint.Range, "0,1,0.001,exp")] public float Sag { get => _sag; set { _sag = value; _settings.Sag = value; Invalidate(); } }
    /// <summary>Damping ratio of bending: 0 rings, 1 returns without overshoot.</summary>
    [Export(PropertyHint.Range, "0,2,0.01")] public float BendDamping { get => _bendDamping; set { _bendDamping = value; _settings.BendDamping = value; Invalidate(); } }
    /// <summary>The source's triple shape-matching α (Bend = SourceTriples only): 0 = limp, 1 = stiffest.</summary>
    [Export(PropertyHint.Range, "0,1,0.01")] public float Stiffness { get => _stiffness; set { _stiffness = value; _settings.Stiffness = value; Invalidate(); } }
    /// <summary>Air drag per natural time √(length / 1 g): 0.32 = 2/s on 25 cm hair; the same look at any size.</summary>
    [Export(PropertyHint.Range, "0,10,0.01")] public float Damping { get => _damping; set { _damping = value; _settings.Damping = value; Invalidate(); } }
    [Export(PropertyHint.Range, "1,32,1")] public int Substeps { get => _substeps; set { _substeps = value; _settings.Substeps = value; Invalidate(); } }
    /// <summary>Coulomb friction against the colliders: 0 = frictionless; 0.5 rests on a head turned ~25°, 1 clings up to ~45°.</summary>
    [Export(PropertyHint.Range, "0,2,0.01")] public float StaticFriction { get => _staticFriction; set { _staticFriction = value; _settings.StaticFriction = value; Invalidate(); } }
    /// <summary>Friction while sliding: 0 = frictionless; usually a little below Static Friction.</summary>
    [Export(PropertyHint.Range, "0,2,0.01")] public float KineticFriction { get => _kineticFriction; set { _kineticFriction = value; _settings.KineticFriction = value; Invalidate(); } }
    [Export] public Vector3 Gravity { get => _gravity; set { _gravity = value; _settings.Gravity = value.ToNumerics(); Invalidate(); } }
    [Export(PropertyHint.Range, "10,240,1,suffix:Hz")] public int StepsPerSecond { get => _stepsPerSecond; set { _stepsPerSecond = value; _settings.StepsPerSecond = value; Invalidate(); } }
    /// <summary>Collide with the groom's head ellipsoid (in addition to child collider nodes). Hair grown on a Scalp Mesh has no ellipsoid: it collides with the mesh.</summary>
    [Export] public bool UseHeadEllipsoid { get => _useHeadEllipsoid; set { _useHeadEllipsoid = value; _collidersDirty = true; } }
    [Export] public bool SimulateInEditor { get => _simulateInEditor; set => _simulateInEditor = value; }
    /// <summary>
    /// Run time: step the hair on a worker thread while the frame renders, drawing the previous step's result (one
    /// physics frame of latency), so the hair's cost leaves the main thread. Off: step in _PhysicsProcess.
    /// </summary>
    [Export] public bool StepOnWorker { get => _stepOnWorker; set { Settle(); _stepOnWorker = value; } }

    // ---- Rendering ----
    /// <summary>Interpolated render strands between neighbouring simulated strands (Catmull-Rom across the sheet).</summary>
    // ---- Hair volume ----
    /// <summary>Strands push apart where packed and drag one another along (docs/volume.md).</summary>
    [ExportGroup("Hair Volume")]
    [Export] public bool HairVolume { get => _hairVolume; set { _hairVolume = value; _settings.HairVolume = value; Invalidate(); } }
    /// <summary>g of push per unit of over-density per cell: 8 = a layer dropped on another rests on it.</summary>
    [Export(PropertyHint.Range, "0,100,0.1")] public float VolumeStiffness { get => _volumeStiffness; set { _volumeStiffness = value; _settings.VolumeStiffness = value; Invalidate(); } }
    /// <summary>Friction between strands per natural time: 50 = strands that touch move together.</summary>
    [Export(PropertyHint.Range, "0,1000,0.1,exp")] public float VolumeFriction { get => _volumeFriction; set { _volumeFriction = value; _settings.VolumeFriction = value; Invalidate(); } }
    /// <summary>Density hair may pack to before it pushes, as a multiple of its median rest density: 1 = the default; 0.5 = limp hair keeps its grown thickness on the crown (about twice the passes).</summary>
    [Export(PropertyHint.Range, "0.05,4,0.01,exp")] public float VolumeDensity { get => _volumeDensity; set { _volumeDensity = value; _settings.VolumeDensity = value; Invalidate(); } }
    /// <summary>Longest time between volume passes in natural times: 0.125 = once per 60 Hz frame for 25 cm hair; 0.03 keeps layers apart (about 3× the cost).</summary>
    [Export(PropertyHint.Range, "0.01,1,0.005,exp")] public float VolumeMaxStep { get => _volumeMaxStep; set { _volumeMaxStep = value; _settings.VolumeMaxStep = value; Invalidate(); } }

    // ---- Strand contacts ----
    /// <summary>Strands of different sheets never pass through each other (docs/volume.md); for hair of a few layers, not a full head.</summary>
    [ExportGroup("Strand Contacts")]
    [Export] public bool StrandContacts { get => _strandContacts; set { _strandContacts = value; _settings.StrandContacts = value; Invalidate(); } }
    /// <summary>How far apart layers are kept, in mean segments: 0.25 = a quarter segment.</summary>
    [Export(PropertyHint.Range, "0.01,2,0.01,exp")] public float ContactThickness { get => _contactThickness; set { _contactThickness = value; _settings.ContactThickness = value; Invalidate(); } }
    /// <summary>Friction between touching layers (μ): 0.3 = a layer rests on another up to about 17°.</summary>
    [Export(PropertyHint.Range, "0,2,0.01")] public float ContactFriction { get => _contactFriction; set { _contactFriction = value; _settings.ContactFriction = value; Invalidate(); } }

    [ExportGroup("Rendering")]
    [Export(PropertyHint.Range, "0,16,1")] public int RenderDensity { get => _renderDensity; set { _renderDensity = value; _settings.RenderDensity = value; Invalidate(); } }
    [Export] public Color RootColor { get => _rootColor; set { _rootColor = value; _settings.RootColor = value.ToNumerics(); PushLook(); } }
    [Export] public Color TipColor { get => _tipColor; set { _tipColor = value; _settings.TipColor = value.ToNumerics(); PushLook(); } }
    [Export(PropertyHint.Range, "0.0001,0.01,0.0001,suffix:m")] public float RootWidth { get => _rootWidth; set { _rootWidth = value; _settings.RootWidth = value; Invalidate(); } }
    [Export(PropertyHint.Range, "0,0.01,0.0001,suffix:m")] public float TipWidth { get => _tipWidth; set { _tipWidth = value; _settings.TipWidth = value; Invalidate(); } }

    /// <summary>The hair's scene; with <see cref="StepOnWorker"/>, reading it first waits for the step under way.</summary>
    public HairScene? Scene { get { Settle(); return _scene; } }
    public HairSimulation? Simulation { get { Settle(); return _simulation; } }
    /// <summary>
    /// The live hair's generation (a regrow starts a new one); the editor's undo entries carry it. Reading it first
    /// applies a pending regrow, so an edit computed after reading it is made on the hair it names.
    /// </summary>
    public int Generation
    {
        get
        {
            Settle();
            if (_needsRebuild) Rebuild();
            return _generations.Current;
        }
    }
    /// <summary>Wall time of the last physics frame's hair steps, in milliseconds.</summary>
    public double LastStepMilliseconds { get; private set; }
    public HairNodeSettings Settings => _settings;

    public override void _Ready()
    {
        _renderer = FindRenderer();
        Rebuild();
    }

    public override void _ExitTree()
    {
        // No threads may outlive the node. The editor's C# rebuilds unload this assembly without calling _ExitTree
        // (godot #78513): DispatcherRegistry disposes every dispatcher when the assembly starts unloading.
        StopWorker();
        _simulation = null;
        DispatcherRegistry.Release(_dispatcher);
        _dispatcher = null;
    }

    public override void _EnterTree()
    {
        // Back in the tree after _ExitTree stopped the workers: the same inputs reinstall the live hair with its edits
        // and history (Rebuild), they do not regrow it.
        if (_scene != null && _dispatcher == null) _needsRebuild = true;
    }

    public override void _PhysicsProcess(double delta)
    {
        if (_needsRebuild) Rebuild();
        // With editor simulation off the hair is shown as grown (Rebuild steps once) and stays still.
        if (Engine.IsEditorHint() && !_simulateInEditor) return;
        if (_simulation == null || _scene == null) return;
        if (_collidersDirty) SyncColliders(_scene);
        int steps = _clock.Advance(delta);
        if (_stepOnWorker && !Engine.IsEditorHint())
        {
            // Finish the step started last frame, draw it, and start this frame's: the worker runs while the engine renders.
            _stepper ??= new BackgroundStepper(_simulation);
            try { _stepper.Wait(); }
            catch (Exception e) when (e is ArgumentException or InvalidOperationException) { GD.PushError($"{Name}: {e.Message}"); }
            LastStepMilliseconds = _stepper.LastStepMilliseconds;
            Draw();
            if (steps > 0)
            {
                PlaceFollowingColliders(); // between the steps: the worker reads the placement
                _stepper.Start((float)_clock.Step, steps, HeadPose());
            }
            return;
        }
        if (steps == 0) return;
        _stepTimer.Restart();
        var head = HeadPose();
        PlaceFollowingColliders();
        float dt = (float)_clock.Step;
        try { for (int i = 0; i < steps; i++) _simulation.Step(dt, head); }
        catch (Exception e) when (e is ArgumentException or InvalidOperationException) { GD.PushError($"{Name}: {e.Message}"); }
        LastStepMilliseconds = _stepTimer.Elapsed.TotalMilliseconds;
        Draw();
    }

    /// <summary>
    /// Shown only in the editor's Scene dock, so nothing here may depend on running in the editor: invalid values and
    /// a mirrored or degenerate head. A missing renderer child is not a problem (the node creates one), so it is not
    /// reported.
    /// </summary>
    public override string[] _GetConfigurationWarnings()
    {
        var w = new List<string>(_problems);
        if (_headProblem != null) w.Add(_headProblem);
        return w.ToArray();
    }

    /// <summary>Called by child collider nodes when they move or change shape.</summary>
    public void CollidersChanged() => _collidersDirty = true;

    /// <summary>
    /// The rigid frame head-space colliders are given in: the head's global pose with scale and any reflection
    /// stripped, exactly what the simulation places the head at (so a field baked in it lands where the mesh is).
    /// </summary>
    public RigidTransform HeadFrame() => HeadPose();

    /// <summary>Regrows the groom (drops unsaved edits) on the next physics frame.</summary>
    public void Invalidate()
    {
        _needsRebuild = true;
        if (IsInsideTree()) UpdateConfigurationWarnings();
    }

    /// <summary>
    /// Grows the hair the settings call for; invalid settings keep the running hair and report every problem. Inputs
    /// equal to the live hair's keep it (with its edits); inputs of a kept earlier generation bring that one back with
    /// its history; <paramref name="fresh"/> regrows even for the live hair's inputs (a reset to the groom as grown).
    /// </summary>
    public void Rebuild(bool fresh = false)
    {
        _needsRebuild = false;
        StopWorker(); // the worker belongs to the simulation being replaced
        _problems = _settings.Validate();
        if (IsInsideTree()) UpdateConfigurationWarnings();
        if (_problems.Count > 0)
        {
            GD.PushError($"{Name}: " + string.Join(" ", _problems));
            return;
        }
        ScalpInput? scalp = null;
        if (_scalpMesh != null)
        {
            if (!TryReadScalp(out scalp, out string? why)) scalp = null;
            if (why != null)
            {
                _problems = new[] { why };
                GD.PushError($"{Name}: {why}");
                if (IsInsideTree()) UpdateConfigurationWarnings();
                return;
            }
        }
        var painted = scalp != null ? PaintedMask(scalp, warn: true) : null;
        // A painted mask is part of what grows: painting regrows, undoing a stroke brings the earlier hair back.
        string? scalpKey = scalp == null ? null : painted == null ? scalp.Key : scalp.Key + "|mask=" + Logic.ScalpMask.Key(painted);
        _styleKey = scalp == null ? null : ScalpGrowth.StyleKey(_settings, scalp.Key, painted);
        _styleWritable = StyleFits(warn: true);
        string key = GrowthKey.Of(_settings, _hairstyle?.ToRecord(), _hairstyle?.GetInstanceId() ?? 0, scalpKey);
        bool keepLive = _edits?.HasEntries == true;
        if (!fresh && key == _generations.CurrentKey && _generations.Live is { } live)
        {
            if (_simulation == null) Install(live, restored: false); // back in the tree: new workers, same hair
            return;
        }
        if (!fresh && _generations.TryRestore(key, keepLive, out var kept) && kept != null)
        {
            Install(kept, restored: true);
            return;
        }
        HairScene scene;
        GroomSettings? groom;
        HairSim.Meshes.MeshCollider? scalpCollider = null;
        try
        {
            var simSettings = _settings.ToSimulation();
            if (scalp != null)
            {
                groom = null;
                scene = GrowOnScalp(scalp, painted);
                scalpCollider = scene.GetComponent<HairSim.Meshes.MeshCollider>();
                // A haircut styled on this same scalp, mask and groom: applied as the ellipsoid groom's style is.
                if (_hairstyle != null && _styleWritable && _hairstyle.ToRecord() is { IsScalpStyle: true, HasStyle: true } style)
                    HairStyleIO.Load(scene, style.StyleData);
            }
            else if (_hairstyle != null)
            {
                groom = _hairstyle.ToRecord().ToGroom();
                scene = _hairstyle.BuildScene(simSettings);
            }
            else
            {
                groom = _settings.ToGroom();
                scene = GroomBuilder.BuildScene(groom, simSettings);
            }
            scene.Render = _settings.ToRender();
            if (_settings.ToVolume() is { } volume) scene.SetComponent(volume);
            if (_settings.ToContacts() is { } contacts) scene.SetComponent(contacts);
        }
        catch (Exception e) when (e is ArgumentException or System.IO.InvalidDataException)
        {
            string why = scalp != null ? $"Scalp Mesh: {e.Message}" : e.Message;
            _problems = new[] { why };
            GD.PushError($"{Name}: {why}");
            if (IsInsideTree()) UpdateConfigurationWarnings();
            return;
        }
        var grown = new GrownHair(scene, new HairEditSession(scene), groom, scalpCollider);
        _generations.Adopt(key, grown, keepLive);
        Install(grown, restored: false);
    }

    /// <summary>Makes grown (or kept) hair the node's: head pose, colliders, a new simulation, the renderer.</summary>
    private void Install(GrownHair hair, bool restored)
    {
        _groom = hair.Groom;
        _scalpCollider = hair.ScalpCollider;
        var scene = hair.Scene;
        scene.World.PlaceHead(HeadPose());
        SyncColliders(scene);
        _dispatcher ??= DispatcherRegistry.Create();
        _scene = scene;
        _simulation = new HairSimulation(scene, dispatcher: _dispatcher);
        _edits = hair.Edits;
        _pendingEdit = null;
        _clock = new FixedStepClock(_settings.FixedStep);
        // One step so the render strands exist before the first frame is drawn. Contacts refuse hair packed too densely
        // for them (a full head): said once, and the hair runs without them.
        try { _simulation.Step((float)_clock.Step, HeadPose()); }
        catch (InvalidOperationException e) when (scene.HasComponent<StrandContactSettings>())
        {
            GD.PushError($"{Name}: {e.Message} Strand Contacts are off for this hair.");
            scene.RemoveComponent<StrandContactSettings>();
            _simulation.Step((float)_clock.Step, HeadPose());
        }
        _renderer ??= FindRenderer() ?? CreateRenderer();
        _renderer.Bind(scene.RenderOutput!, _settings.ToLook(), RootColor, TipColor);
        Draw();
        EmitSignal(SignalName.SceneRebuilt);
        // A kept generation's style is what the scene file must save again.
        if (restored) OnStyleChanged();
    }

    // ---- edits ----

    /// <summary>Run time: apply an edit now (undo with <see cref="UndoEdit"/>).</summary>
    public void ApplyEdit(HairEdit edit)
    {
        Settle();
        if (_edits == null) throw new InvalidOperationException("The hair node has no scene yet.");
        _edits.Do(edit);
        OnStyleChanged();
    }

    /// <summary>Editor: remember an edit so the undo manager's first do-call (RedoEditIn) applies it.</summary>
    public void StageEdit(HairEdit edit) => _pendingEdit = edit;

    /// <summary>Applies the staged edit, or redoes the last undone one.</summary>
    public void RedoEdit()
    {
        Settle();
        if (_edits == null) return;
        if (_pendingEdit != null)
        {
            var edit = _pendingEdit;
            _pendingEdit = null;
            // An edit is computed on one world; staged on hair that was regrown since, it would change the old world.
            if (!_edits.Owns(edit)) { Skip($"\"{edit.Name}\" was computed on hair that has been regrown since: not applied."); return; }
            _edits.Do(edit);
        }
        else if (!_edits.Redo()) return;
        OnStyleChanged();
    }

    /// <summary>Undoes the last edit of the live hair (the run-time Undo button).</summary>
    public void UndoEdit()
    {
        Settle();
        if (_edits != null && _edits.Undo()) OnStyleChanged();
    }

    /// <summary>
    /// Editor undo manager do-method: <see cref="RedoEdit"/> when <paramref name="generation"/> is the live hair's;
    /// otherwise nothing changes and <see cref="EditSkipped"/> (and the Output panel) says why.
    /// </summary>
    public void RedoEditIn(int generation, string editName)
    {
        if (IsLiveForEditor(generation, editName, undo: false)) RedoEdit();
        else _pendingEdit = null;
    }

    /// <summary>Editor undo manager undo-method: <see cref="UndoEdit"/> on the hair the entry was made on, or a message.</summary>
    public void UndoEditIn(int generation, string editName)
    {
        if (IsLiveForEditor(generation, editName, undo: true)) UndoEdit();
    }

    private bool IsLiveForEditor(int generation, string editName, bool undo)
    {
        Settle();
        // An undone or redone value change regrows on the next physics frame; the entries after it in the same undo
        // sequence must see that hair (or the kept generation it brings back) first.
        if (_needsRebuild) Rebuild();
        string? why = _generations.Explain(generation, editName, undo);
        if (why == null) return true;
        Skip(why);
        return false;
    }

    private void Skip(string why)
    {
        GD.PushWarning($"{Name}: {why}");
        EmitSignal(SignalName.EditSkipped, why);
    }

    /// <summary>Back to the groom as grown (the style data is cleared).</summary>
    public void ResetStyle()
    {
        if (_hairstyle != null && !Engine.IsEditorHint())
            _hairstyle = (Hairstyle)_hairstyle.Duplicate();   // never clear a shared resource at run time
        // A Hairstyle holding another scalp's haircut is left as it is (the hair grew unstyled anyway).
        if (_hairstyle != null && _styleWritable) _hairstyle.StyleData = Array.Empty<byte>();
        Rebuild(fresh: true);
        EmitSignal(SignalName.StyleChanged);
    }

    /// <summary>Saves groom + style as a Hairstyle resource; written to a temporary name, then renamed.</summary>
    public void SaveHairstyle(string path)
    {
        Settle();
        if (_scene == null) throw new InvalidOperationException("Nothing to save: the hair node has no scene.");
        var res = new Hairstyle();
        // Hair grown on a Scalp Mesh: the style and what it was styled on (the node's groom numbers are kept for reading only).
        res.SetFrom(HairstyleRecord.FromGroom(_groom ?? _settings.ToGroom(), HairStyleIO.Save(_scene)) with { ScalpStyleKey = _groom == null ? _styleKey ?? "" : "" });
        string ext = System.IO.Path.GetExtension(path);
        string tmp = path[..^ext.Length] + ".tmp" + ext;
        var err = ResourceSaver.Save(res, tmp);
        if (err != Error.Ok) throw new System.IO.IOException($"Could not write {tmp}: {err}.");
        err = DirAccess.RenameAbsolute(ProjectSettings.GlobalizePath(tmp), ProjectSettings.GlobalizePath(path));
        if (err != Error.Ok) throw new System.IO.IOException($"Could not replace {path}: {err}.");
    }

    /// <summary>Loads a Hairstyle file; a missing or corrupt file throws and the current hair stays as it is.</summary>
    public void LoadHairstyle(string path)
    {
        Settle();
        if (!ResourceLoader.Exists(path)) throw new System.IO.FileNotFoundException($"No hairstyle at {path}.");
        // Untyped load and `as`: Load<T> casts, so a resource of another type would throw InvalidCastException
        // instead of this message.
        var res = ResourceLoader.Load(path, "", ResourceLoader.CacheMode.Ignore) as Hairstyle
                  ?? throw new System.IO.InvalidDataException($"{path} is not a Hairstyle resource.");
        var record = res.ToRecord();
        if (_scalpMesh != null)
        {
            // A haircut of scalp-grown hair applies to hair grown from the same scalp, mask and groom values only.
            if (!record.IsScalpStyle) throw new InvalidOperationException("This Hairstyle holds a groom grown on the Head Radii ellipsoid: clear Scalp Mesh to use it.");
            if (_scene == null || record.ScalpStyleKey != _styleKey)
                throw new InvalidOperationException("This Hairstyle was styled on another Scalp Mesh, painted scalp or groom (Sheets, Strands Per Sheet, Particles Per Strand, Strand Length, Seed, Scalp values): set those as they were.");
            // Checked on the live hair, which grew from the same inputs: a corrupt style throws and changes nothing.
            if (record.HasStyle) HairStyleIO.Load(_scene, record.StyleData);
        }
        // Build first: if the file is bad, nothing here has changed yet.
        else res.BuildScene(_settings.ToSimulation());
        Hairstyle = res; // through the setter, so the node follows the resource's edits
        Rebuild();
        EmitSignal(SignalName.StyleChanged);
    }

    private void OnStyleChanged()
    {
        if (_scene == null) return;
        // In the editor the resource is what the scene file saves: keep it in step with every edit, undo and redo.
        if (Engine.IsEditorHint() && _hairstyle != null && _styleWritable)
        {
            _hairstyle.StyleData = HairStyleIO.Save(_scene);
            // A Hairstyle that held nothing takes this scalp's haircut from now on (and says what it was styled on).
            if (_styleKey != null) _hairstyle.ScalpStyleKey = _styleKey;
        }
        Draw();
        EmitSignal(SignalName.StyleChanged);
    }

    // ---- scalp ----

    /// <summary>
    /// Bakes the scalp's distance field and stores it as a binary resource beside the scene (a field is about a million
    /// floats, which a .tscn would hold as text), so the hair grows without baking when the scene opens or runs.
    /// </summary>
    public void BakeScalpField()
    {
        var problems = _settings.Validate();
        if (problems.Count > 0) { GD.PushError($"{Name}: " + string.Join(" ", problems)); return; }
        if (_scalpMesh == null) { GD.PushError($"{Name}: set Scalp Mesh first."); return; }
        if (!TryReadScalp(out var scalp, out string? why) || scalp == null) { GD.PushError($"{Name}: {why}"); return; }
        try
        {
            var mesh = ScalpGrowth.HeadSpaceMesh(scalp.Surfaces, scalp.MeshToHead);
            var field = ScalpGrowth.BakeField(mesh, _settings);
            string fieldKey = ScalpGrowth.FieldKey(scalp.Key, _settings.ScalpCellSize);
            _bakedScalpField = (fieldKey, field);
            var stored = HairMeshField.From(field, "head", fieldKey);
            string scenePath = (Owner ?? this).SceneFilePath;
            if (string.IsNullOrEmpty(scenePath))
            {
                GD.PushWarning($"{Name}: the scene has not been saved yet, so the field is kept inside it (large). Save the scene and bake again to store it as a file.");
                ScalpField = stored;
                return;
            }
            string path = $"{scenePath.GetBaseDir()}/{Name}_scalp_field.res";
            var err = ResourceSaver.Save(stored, path, ResourceSaver.SaverFlags.ChangePath | ResourceSaver.SaverFlags.Compress);
            if (err != Error.Ok) { GD.PushError($"{Name}: could not write {path}: {err}."); return; }
            ScalpField = stored;
            GD.Print($"{Name}: scalp field {field.Nx}×{field.Ny}×{field.Nz} baked in {field.BakeTime.TotalMilliseconds:F0} ms and saved to {path}.");
        }
        catch (ArgumentException e) { GD.PushError($"{Name}: Scalp Mesh: {e.Message}"); }
    }

    /// <summary>Reads the scalp mesh's surfaces in the head's frame (the one the simulation places the head at).</summary>
    private bool TryReadScalp(out ScalpInput? scalp, out string? why)
    {
        scalp = null;
        why = null;
        if (_scalpMesh == null || !IsInstanceValid(_scalpMesh) || _scalpMesh.Mesh is not Mesh mesh)
        {
            why = "Scalp Mesh has no mesh: assign a MeshInstance3D with a mesh (an imported .obj, or a mesh inside an imported glTF scene), or clear Scalp Mesh.";
            return false;
        }
        if (!IsInsideTree() || !_scalpMesh.IsInsideTree())
        {
            why = "Scalp Mesh must be in the scene tree with the hair node (its place relative to the head is read).";
            return false;
        }
        try
        {
            var surfaces = mesh.ReadSurfaces();
            var toHead = ColliderFollowMath.MeshToFrame(_scalpMesh.GlobalTransform.ToNumericsMatrix(), HeadPose());
            scalp = new ScalpInput(surfaces, toHead, ScalpGrowth.Key(surfaces, toHead));
            return true;
        }
        catch (ArgumentException e)
        {
            why = $"Scalp Mesh: {e.Message}";
            return false;
        }
    }

    /// <summary>Grows the hair on the scalp: its field from Scalp Field when that matches, else from the last bake, else baked now.</summary>
    private HairScene GrowOnScalp(ScalpInput scalp, byte[]? painted)
    {
        var mesh = ScalpGrowth.HeadSpaceMesh(scalp.Surfaces, scalp.MeshToHead);
        string fieldKey = ScalpGrowth.FieldKey(scalp.Key, _settings.ScalpCellSize);
        HairSim.Meshes.SignedDistanceField? field = null;
        if (_scalpField != null && _scalpField.SourceKey == fieldKey)
        {
            try { field = _scalpField.ToField(); }
            catch (ArgumentException e) { GD.PushWarning($"{Name}: Scalp Field is unusable ({e.Message}): baking the field again."); }
        }
        else if (_scalpField != null)
            GD.PushWarning($"{Name}: Scalp Field was baked from another mesh, place or cell size: baking the field again (press Bake scalp field to store the new one).");
        if (field == null && _bakedScalpField is { } baked && baked.Key == fieldKey) field = baked.Field;
        if (field == null)
        {
            field = ScalpGrowth.BakeField(mesh, _settings);
            _bakedScalpField = (fieldKey, field);
            GD.Print($"{Name}: scalp field {field.Nx}×{field.Ny}×{field.Nz} baked in {field.BakeTime.TotalMilliseconds:F0} ms" +
                     (_scalpField == null ? "; press Bake scalp field in the editor to store it and skip this when the scene opens." : "."));
        }
        return ScalpGrowth.Grow(mesh, field, _settings, painted);
    }

    /// <summary>The Scalp Mask's bits when it was painted on this scalp (same mesh, same place on the head), else null.</summary>
    private byte[]? PaintedMask(ScalpInput scalp, bool warn)
    {
        if (_scalpMask == null || _scalpMask.Triangles.Length == 0) return null;
        if (_scalpMask.ScalpKey == scalp.Key) return _scalpMask.Triangles;
        if (warn) GD.PushWarning($"{Name}: Scalp Mask was painted on another mesh or with the mesh elsewhere on the head: the vertex colours decide where hair grows (paint again, or clear Scalp Mask).");
        return null;
    }

    /// <summary>
    /// Whether the Hairstyle may hold the live hair's style: always for the ellipsoid groom; for hair grown on a Scalp
    /// Mesh, when it is empty or was styled on the same scalp, mask and groom (<see cref="_styleKey"/>). Otherwise its
    /// style is left as it is, and the hair grows unstyled.
    /// </summary>
    private bool StyleFits(bool warn)
    {
        if (_hairstyle == null || _styleKey == null) return true;
        var record = _hairstyle.ToRecord();
        if (record.IsScalpStyle ? record.ScalpStyleKey == _styleKey : !record.HasStyle) return true;
        if (warn)
            GD.PushWarning(record.IsScalpStyle
                ? $"{Name}: the Hairstyle was styled on another Scalp Mesh, painted scalp or groom: the hair grows unstyled and the Hairstyle is left as it is (set those as they were, or assign a new Hairstyle to keep this hair's haircut)."
                : $"{Name}: the Hairstyle holds a haircut of the Head Radii ellipsoid groom: it is not applied to hair grown on the Scalp Mesh and is left as it is (assign a new Hairstyle to keep this hair's haircut).");
        return false;
    }

    /// <summary>A scalp paint stroke, computed but not applied: the mask before (null: none, the vertex colours) and after.</summary>
    public sealed record ScalpStroke(byte[]? Before, byte[] After, int TriangleCount, string ScalpKey);

    /// <summary>
    /// Paints (or erases) the scalp under a brush stroke seen through <paramref name="camera"/>, starting from the Scalp
    /// Mask or, without one, from the vertex colours. Returns the stroke to apply with <see cref="SetScalpMask"/> (the
    /// editor does it through its undo history), or null with <paramref name="why"/> when there is nothing to paint on
    /// or the stroke changed nothing. Changes nothing itself.
    /// </summary>
    public ScalpStroke? PaintScalp(IReadOnlyList<System.Numerics.Vector2> stroke, CameraMatrices camera, float radius, bool erase, out string? why)
    {
        why = null;
        if (_scalpMesh == null) { why = "Set Scalp Mesh first: the scalp is painted on it."; return null; }
        if (!TryReadScalp(out var scalp, out why) || scalp == null) return null;
        try
        {
            var mesh = ScalpGrowth.HeadSpaceMesh(scalp.Surfaces, scalp.MeshToHead);
            var before = PaintedMask(scalp, warn: false);
            var after = Logic.ScalpMask.Paint(mesh, before, _settings.ScalpMaskThreshold, stroke, radius,
                erase ? HairSim.Meshes.ScalpPaintMode.Remove : HairSim.Meshes.ScalpPaintMode.Add, camera, HeadPose(), _scalpCollider);
            if (after == null) { why = "The stroke changed nothing (painted already, facing away, or hidden behind the head)."; return null; }
            return new ScalpStroke(before, after, mesh.TriangleCount, scalp.Key);
        }
        catch (ArgumentException e) { why = $"Scalp Mesh: {e.Message}"; return null; }
    }

    /// <summary>
    /// Sets the Scalp Mask to these bits (empty: no mask, the vertex colours decide): the do and undo step of a paint
    /// stroke. A new resource each time, so the undo history keeps the earlier one untouched.
    /// </summary>
    public void SetScalpMask(byte[] triangles, int triangleCount, string scalpKey) =>
        ScalpMask = triangles.Length == 0 ? null : new HairScalpMask { Triangles = triangles, TriangleCount = triangleCount, ScalpKey = scalpKey };

    /// <summary>Shows where hair grows (the painted mask, else the vertex colours') as a red film over the Scalp Mesh, while a scalp tool is active.</summary>
    public void ShowScalpMask(bool show)
    {
        if (!show)
        {
            _scalpOverlay?.QueueFree();
            _scalpOverlay = null;
            return;
        }
        if (_scalpOverlay == null)
        {
            // Not owned by the scene: never saved, only drawn while painting.
            _scalpOverlay = new MeshInstance3D
            {
                Name = "ScalpMaskOverlay",
                CastShadow = GeometryInstance3D.ShadowCastingSetting.Off,
                MaterialOverride = new StandardMaterial3D
                {
                    ShadingMode = BaseMaterial3D.ShadingModeEnum.Unshaded,
                    Transparency = BaseMaterial3D.TransparencyEnum.Alpha,
                    CullMode = BaseMaterial3D.CullModeEnum.Disabled,
                    AlbedoColor = new Color(1f, 0.15f, 0.1f, 0.45f),
                },
            };
            AddChild(_scalpOverlay);
        }
        RefreshScalpOverlay();
    }

    private void RefreshScalpOverlay()
    {
        if (_scalpOverlay == null || !IsInstanceValid(_scalpOverlay)) return;
        _scalpOverlay.Mesh = null;
        if (_scalpMesh == null || !TryReadScalp(out var scalp, out _) || scalp == null) return;
        try
        {
            var mesh = ScalpGrowth.HeadSpaceMesh(scalp.Surfaces, scalp.MeshToHead);
            var flags = Logic.ScalpMask.Start(mesh, PaintedMask(scalp, warn: false), _settings.ScalpMaskThreshold).Triangles;
            var vertices = Logic.ScalpMask.Overlay(mesh, flags, lift: 0.0005f);
            if (vertices.Length == 0) return;
            var godot = new Vector3[vertices.Length];
            for (int i = 0; i < vertices.Length; i++) godot[i] = vertices[i].ToGodot();
            Godot.Collections.Array arrays = [];
            arrays.Resize((int)Mesh.ArrayType.Max);
            arrays[(int)Mesh.ArrayType.Vertex] = godot;
            var film = new ArrayMesh();
            film.AddSurfaceFromArrays(Mesh.PrimitiveType.Triangles, arrays);
            _scalpOverlay.Mesh = film;
            // The film's vertices are in head space: it sits where the head is.
            _scalpOverlay.GlobalTransform = HeadTransform();
        }
        catch (ArgumentException e) { GD.PushWarning($"{Name}: the scalp overlay cannot be drawn: {e.Message}"); }
    }

    // ---- helpers ----

    /// <summary>
    /// The head's pose for the simulation. A mirrored head (negative scale) has its reflection stripped and a
    /// degenerate one (zero scale) keeps the last good pose; either is reported once, as an error and a
    /// configuration warning, instead of throwing from every physics frame.
    /// </summary>
    private RigidTransform HeadPose()
    {
        try
        {
            var pose = HeadTransform().ToHeadPose(out bool mirrored);
            ReportHead(mirrored ? "The head's transform is mirrored (negative scale): its reflection is ignored." : null);
            _lastHeadPose = pose;
            return pose;
        }
        catch (ArgumentException e)
        {
            ReportHead($"The head's transform has no rotation ({e.Message}): the last good pose is kept.");
            return _lastHeadPose;
        }
    }

    private void ReportHead(string? problem)
    {
        if (problem == _headProblem) return;
        _headProblem = problem;
        if (problem != null) GD.PushError($"{Name}: {problem}");
        if (IsInsideTree()) UpdateConfigurationWarnings();
    }

    private Transform3D HeadTransform()
    {
        var t = _head != null && IsInstanceValid(_head) ? _head.GlobalTransform : GlobalTransform;
        return new Transform3D(t.Basis.Orthonormalized(), t.Origin);
    }

    /// <summary>Waits for a background step, so the scene can be read or edited (a no-op when stepping in place).</summary>
    private void Settle()
    {
        try { _stepper?.Wait(); }
        catch (Exception e) when (e is ArgumentException or InvalidOperationException) { GD.PushError($"{Name}: {e.Message}"); }
    }

    private void StopWorker()
    {
        _stepper?.Dispose();
        _stepper = null;
    }

    private void SyncColliders(HairScene scene)
    {
        _collidersDirty = false;
        var list = new List<Collider>();
        var followers = new List<(IHairFollowingCollider Node, int Index)>();
        try
        {
            if (_useHeadEllipsoid && _groom != null) list.Add(Collider.Ellipsoid(_groom.HeadCenter, _groom.HeadRadii));
            var headInverse = HeadTransform().AffineInverse();
            foreach (var child in GetChildren())
            {
                if (child is not IHairColliderNode c || child is not Node3D n || !n.Visible) continue;
                if (c is IHairFollowingCollider f && f.Follows)
                {
                    // World space, where its frame is now; a frame that cannot be read leaves it out (the node says why).
                    if (!f.TryPlace(out var placed)) continue;
                    followers.Add((f, list.Count));
                    list.Add(placed);
                }
                else list.Add(c.ToCollider(headInverse * n.GlobalTransform));
            }
        }
        catch (ArgumentException e)
        {
            GD.PushError($"{Name}: collider ignored: {e.Message}");
            return;
        }
        scene.ClearColliders();
        foreach (var c in list) scene.AddCollider(c);
        _followers = followers.Select(x => x.Node).ToArray();
        _followerIndices = followers.Select(x => x.Index).ToArray();
        // Mesh colliders: the scalp's field (hair grown on a mesh) is the scene's component; every visible HairMeshCollider3D
        // with a usable field is added beside it (a head, a body, a prop: as many as there are).
        foreach (var old in scene.MeshColliders.ToArray())
            if (!ReferenceEquals(old, _scalpCollider)) scene.RemoveMeshCollider(old);
        if (_scalpCollider != null && !scene.HasComponent<HairSim.Meshes.MeshCollider>()) scene.SetComponent(_scalpCollider);
        var following = new List<HairMeshCollider3D>();
        foreach (var child in GetChildren())
        {
            if (child is not HairMeshCollider3D m || !m.Visible || m.ToComponent() is not { } component) continue;
            scene.AddMeshCollider(component);
            if (component.Space == HairSim.Meshes.ColliderSpace.World) following.Add(m);
        }
        _followingFields = following.ToArray();
    }

    /// <summary>Places the colliders that follow a node or bone (fields and primitives) where their frames are now (before the steps; allocates nothing).</summary>
    private void PlaceFollowingColliders()
    {
        foreach (var field in _followingFields)
            if (IsInstanceValid(field)) field.PlaceField();
        // Following primitives move without a rebuild; the library carries them across the substeps from the last frame's place.
        if (_scene == null) return;
        for (int i = 0; i < _followers.Length; i++)
        {
            if (_followers[i] is not GodotObject node || !IsInstanceValid(node) || !_followers[i].TryPlace(out var collider)) continue;
            try { _scene.SetCollider(_followerIndices[i], collider); }
            catch (ArgumentException e) { GD.PushError($"{Name}: {e.Message}"); }
        }
    }

    private void Draw()
    {
        if (_scene?.RenderOutput is { } output && _renderer != null && IsInstanceValid(_renderer)) _renderer.Render(output);
    }

    private void PushLook()
    {
        if (_renderer != null && IsInstanceValid(_renderer)) _renderer.SetColors(RootColor, TipColor);
    }

    private HairMultiMeshRenderer? FindRenderer()
    {
        // Internal children too: the renderer this node creates is one (kept out of the saved scene).
        foreach (var child in GetChildren(includeInternal: true))
            if (child is HairMultiMeshRenderer r) return r;
        return null;
    }

    private HairMultiMeshRenderer CreateRenderer()
    {
        // Not owned by the edited scene, so it is never saved into the .tscn.
        var r = new HairMultiMeshRenderer { Name = "HairRenderer" };
        AddChild(r, forceReadableName: false, InternalMode.Front);
        return r;
    }

}
