namespace HairSim;

/// <summary>
/// The systems a scene needs, in order, and the frame loop that runs them: one fork/join per frame,
/// each job taking a block of strands through all substeps (strands do not interact).
/// </summary>
public sealed class HairPipeline
{
    private readonly HairScene _scene;
    private readonly IHairSystem[] _substep;
    private readonly Fast.StrandChunkRunner? _chunks;
    private bool _chunkFrame;
    private readonly IHairSystem[] _frameEnd;
    private readonly IHairSystem[] _frameStart;
    private readonly IHairSystem[] _passEnd;
    private readonly IPassStartListener[] _passStart;
    private readonly IHairSystem[] _all;
    private readonly IThreadDispatcher _dispatcher;
    private readonly FrameContext _ctx = new();
    private readonly SimulationSettings _guarded = new();
    private GroomScale _scale;
    private int _reachStamp;
    private readonly Action<int> _substepJob, _frameEndJob;
    private int _jobCount;
    private readonly NonFiniteContainment _containment;
    private readonly FrameReport _report = new();
    // Per collider this frame: whether it moves across the substeps (false: it is at its new placement throughout).
    private bool[] _meshMoves = [];
    private bool[] _colliderMoves = [];
    // The farthest a moved collider's surface travels this frame: the guards' substeps keep it within a head's travel.
    private float _colliderTravel;

    /// <summary>
    /// Particles per substep job: ~8192 particles × the ≈ 44 bytes a substep touches (positions, velocities, masses,
    /// rest lengths, rest shape) ≈ 360 KB, which stays in a core's L2 through all substeps. Jobs of 4096 gave the
    /// same one-thread times but were ≈ 7 % slower on two threads on the 100k-strand scene (A/B in one process).
    /// </summary>
    public const int ParticlesPerJob = 8192;

    internal HairPipeline(HairScene scene, List<IHairSystem> systems, IThreadDispatcher dispatcher)
    {
        _scene = scene;
        _all = systems.ToArray();
        _substep = systems.FindAll(s => s.Phase == SystemPhase.Substep).ToArray();
        _chunks = Fast.StrandChunkRunner.TryCreate(_substep);
        _frameEnd = systems.FindAll(s => s.Phase == SystemPhase.FrameEnd).ToArray();
        _frameStart = systems.FindAll(s => s.Phase == SystemPhase.FrameStart).ToArray();
        _passEnd = systems.FindAll(s => s.Phase == SystemPhase.PassEnd).ToArray();
        _passStart = systems.OfType<IPassStartListener>().ToArray();
        _ctx.MovedListeners = systems.OfType<IStrandMovedListener>().ToArray();
        _dispatcher = dispatcher;
        _substepJob = RunSubstepJob;
        _frameEndJob = RunFrameEndJob;
        SystemNames = Array.ConvertAll(_all, s => s.Name);
        _scale = GroomScale.Of(scene.World);
        _reachStamp = scene.World.EditStamp;
        _containment = new NonFiniteContainment(scene.World, _all);
    }

    public IReadOnlyList<IHairSystem> Systems => _all;
    public IReadOnlyList<string> SystemNames { get; }
    public bool Contains(string systemName) => Array.IndexOf((string[])SystemNames, systemName) >= 0;
    public HairScene Scene => _scene;

    /// <summary>
    /// Run uncut 16-particle strands in 32-strand chunks, transposed into rows once per frame, through all substeps
    /// (fast path with AVX-512; default on). The same bits as running the systems one by one over the world, which
    /// is what turning this off does; it exists to measure and test the two against each other.
    /// </summary>
    public bool UseStrandChunks { get; set; } = true;

    /// <summary>
    /// On chunks, the bend sweep integrates each row just before it sweeps it, in place of the integration's own pass
    /// (default on; the same bits). Exists to measure and test the two against each other.
    /// </summary>
    internal bool FuseChunkIntegration
    {
        get => _chunks?.FuseIntegration ?? false;
        set { if (_chunks != null) _chunks.FuseIntegration = value; }
    }

    /// <summary>Whether the last frame ran on chunks with the integration taken into the bend sweep (<see cref="FuseChunkIntegration"/>).</summary>
    internal bool LastFrameIntegratedInSweep => _chunkFrame && _chunks!.IntegratesInSweep;

    /// <summary>
    /// On chunks, the bend sweep tests each row it finishes against the ellipsoid's far sphere, and the collision just
    /// after it takes only the rows with a free lane inside (default on; the same bits). Exists to measure and test the two against each other.
    /// </summary>
    internal bool FuseChunkFarRows
    {
        get => _chunks?.FuseFarRows ?? false;
        set { if (_chunks != null) _chunks.FuseFarRows = value; }
    }

    /// <summary>Whether the last frame ran on chunks whose collision took the sweep's far rows (<see cref="FuseChunkFarRows"/>).</summary>
    internal bool LastFrameTestedFarRowsInSweep => _chunkFrame && _chunks!.TestsFarRowsInSweep;

    /// <summary>Whether frames take the chunked path: <see cref="UseStrandChunks"/>, the fast path on AVX-512, and every substep system able to run on chunks.</summary>
    public bool UsesStrandChunks => UseStrandChunks && _chunks != null;

    /// <summary>Chunks stepped in the last frame, and how many of them went back to the system-by-system path midway (coinciding particles).</summary>
    public (int Stepped, int HandedBack) LastFrameChunks => _chunkFrame ? _chunks!.Counts : default;
    /// <summary>Into how many parts the last frame was stepped (1 unless a system such as the hair volume asked for shorter ones).</summary>
    public int LastFrameParts { get; private set; } = 1;
    /// <summary>
    /// Substeps stepped in the last frame, over all its parts: the requested <see cref="SimulationSettings.Substeps"/>
    /// unless the stability guards added some (a fast head on short segments) or the frame was stepped in parts.
    /// </summary>
    public int LastFrameSubsteps { get; private set; }
    /// <summary>The context of the last frame (teleport flag, substep length, …).</summary>
    public FrameContext LastFrame => _ctx;

    /// <summary>The strands the last frame reset because they held a non-finite value (see <see cref="FrameReport"/>).</summary>
    public FrameReport LastFrameReport => _report;

    /// <summary>The groom's size the scale-free settings are measured against (updated after each edit).</summary>
    public GroomScale Scale => _scale;

    /// <summary>Advances the scene by dt seconds while the head moves to <paramref name="headTarget"/>.</summary>
    public void Step(float dt, RigidTransform headTarget)
    {
        if (!float.IsFinite(dt) || dt <= 0f || dt > 1f)
            throw new ArgumentOutOfRangeException(nameof(dt), dt, "Frame time must be in (0, 1] seconds.");
        HairWorld.CheckHead(headTarget, nameof(headTarget));
        var world = _scene.World;
        var ctx = _ctx;
        var delta = RigidTransform.Delta(world.Head, headTarget);
        var requested = _scene.Settings;
        float headMove = (headTarget.Position - world.Head.Position).Length();
        // Settings are checked every frame, however they were changed (a property set after the first step included),
        // and rest data after every edit: before anything moves, so a refused frame leaves the world as it was.
        requested.Validate();
        if (world.EditStamp != _reachStamp) { world.ValidateRestData(); _scale = GroomScale.Of(world); _reachStamp = world.EditStamp; } // only after edits
        world.EnsureFreeStrands(); // before the jobs, which only read it
        bool teleported = headMove > requested.TeleportDistance * _scale.Reach || delta.Angle > requested.TeleportAngle;
        // A system that couples strands once per frame may ask for shorter frames (hair volume: a fixed share of the
        // hair's natural time), so it behaves the same at 30 and 240 Hz and on a doll or a giant: the frame is then
        // stepped in parts, the head moving a part of the way each time and the substeps shared out between them.
        int parts = 1;
        bool splits = false;
        if (!teleported)
            foreach (var system in _frameStart)
                if (system is IFrameSplitter splitter) { parts = Math.Max(parts, splitter.PartsOf(_scene, dt, _scale)); splits = true; }
        PrepareColliderMotion(teleported, requested);
        LastFrameSubsteps = 0;
        if (parts <= 1 && !splits) { StepPart(dt, headTarget, headMove, delta, teleported, requested.Substeps, 0f, 1f); LastFrameParts = 1; }
        else LastFrameParts = StepInParts(dt, headTarget, parts, requested.Substeps);
        _scene.CollidersStepped();
        _containment.Collect(_report);
    }

    /// <summary>
    /// Steps a frame in parts: <paramref name="parts"/> equal parts to begin with; before each part, a splitter that
    /// measured a stiff state (<see cref="IFrameSplitter.LongestPart"/>) may cut the rest of the frame finer, into
    /// equal parts again. The head moves its share of the way each part; the substeps are shared out by time.
    /// </summary>
    private int StepInParts(float dt, RigidTransform headTarget, int parts, int requestedSubsteps)
    {
        var world = _scene.World;
        var start = world.Head;
        int done = 0;
        double elapsed = 0;
        while (done < parts)
        {
            double remaining = dt - elapsed;
            double longest = double.PositiveInfinity;
            foreach (var system in _frameStart)
                if (system is IFrameSplitter splitter) longest = Math.Min(longest, splitter.LongestPart(_scene, _scale));
            if (remaining / (parts - done) > longest * (1 + 1e-6))
                parts = done + (int)Math.Min(IFrameSplitter.MaxParts - done, Math.Ceiling(remaining / longest - 1e-6));
            int left = parts - done;
            bool last = left <= 1;
            double part = last ? remaining : remaining / left;
            int substeps = parts == 1 ? requestedSubsteps
                : Math.Max(1, (int)Math.Ceiling(requestedSubsteps * part / dt - 1e-6));
            float from = (float)(elapsed / dt);
            elapsed += part;
            float to = last ? 1f : (float)(elapsed / dt);
            var target = last ? headTarget : RigidTransform.Interpolate(start, headTarget, to);
            StepPart((float)part, target, (target.Position - world.Head.Position).Length(), RigidTransform.Delta(world.Head, target), false, substeps, from, to);
            done++;
        }
        return parts;
    }

    /// <summary>
    /// Which colliders were moved since the last frame (<see cref="HairScene.SetCollider"/>) and are carried across the
    /// substeps; a head teleport, a jump beyond the teleport limits or a change of space places them at once, as a
    /// teleported head is.
    /// </summary>
    private void PrepareColliderMotion(bool teleported, SimulationSettings st)
    {
        int nc = _scene.Colliders.Count;
        if (_colliderMoves.Length < nc) _colliderMoves = new bool[nc];
        _colliderTravel = 0f;
        for (int c = 0; c < nc; c++)
        {
            var from = _scene.ColliderBefore(c);
            var to = _scene.Colliders[c];
            bool moves = !teleported && from.InWorld == to.InWorld && !SamePlacement(from, to);
            if (moves)
            {
                Collider.Motion(from, to, out float distance, out float angle);
                moves = !(distance > st.TeleportDistance * _scale.Reach || angle > st.TeleportAngle);
                // A turning ellipsoid's surface moves by the angle × its largest radius; a growing one by the change of size.
                if (moves)
                    _colliderTravel = MathF.Max(_colliderTravel, distance + angle * MathF.Max(to.Radii.X, MathF.Max(to.Radii.Y, to.Radii.Z))
                        + MathF.Abs(to.Radii.X - from.Radii.X) + MathF.Abs(to.Radii.Y - from.Radii.Y) + MathF.Abs(to.Radii.Z - from.Radii.Z));
            }
            _colliderMoves[c] = moves;
        }
        // Mesh colliders whose placement changed: carried the same way (a head-space placement moves with the head anyway).
        var meshes = _scene.MeshColliderArray;
        if (_meshMoves.Length < meshes.Length) _meshMoves = new bool[meshes.Length];
        for (int m = 0; m < meshes.Length; m++)
        {
            var mc = meshes[m];
            var a = mc.PlacementBefore; var b = mc.Placement;
            bool moves = !teleported && (a.Position != b.Position || a.Rotation != b.Rotation);
            if (moves)
            {
                float distance = System.Numerics.Vector3.Distance(a.Position, b.Position), angle = RigidTransform.Delta(a, b).Angle;
                moves = !(distance > st.TeleportDistance * _scale.Reach || angle > st.TeleportAngle);
                // A turning field's surface moves by at most the angle × its farthest corner's distance from the origin.
                if (moves) _colliderTravel = MathF.Max(_colliderTravel, distance + angle * mc.Reach);
            }
            _meshMoves[m] = moves;
        }
    }

    private static bool SamePlacement(in Collider a, in Collider b) =>
        a.Center == b.Center && a.End == b.End && a.Radii == b.Radii && a.Rotation == b.Rotation;

    /// <param name="from">How far into the frame this part starts (0 … 1), for the colliders' motion.</param>
    /// <param name="to">How far into the frame it ends (1: the frame's end).</param>
    private void StepPart(float dt, RigidTransform headTarget, float headMove, RigidTransform delta, bool teleported, int substeps, float from, float to)
    {
        var world = _scene.World;
        var ctx = _ctx;
        var requested = _scene.Settings;
        // Systems read the guarded copy (α clamp, automatic substeps), so every implementation inherits the guards.
        StabilityGuards.Apply(requested, _guarded, dt, MathF.Max(headMove, _colliderTravel * (to - from)), delta.Angle, teleported, _scale, substeps);
        var st = _guarded;
        LastFrameSubsteps += st.Substeps;
        ctx.Settings = st;
        ctx.Dt = dt;
        ctx.Substeps = st.Substeps;
        ctx.H = dt / st.Substeps;
        ctx.HeadStart = world.Head;
        ctx.HeadEnd = headTarget;
        ctx.Teleported = teleported;
        ctx.TeleportDelta = ctx.Teleported ? delta : RigidTransform.Identity;
        ctx.Scale = _scale;
        ctx.Dispatcher = _dispatcher;

        if (ctx.SubstepHeads.Length < st.Substeps) ctx.SubstepHeads = new RigidTransform[st.Substeps];
        for (int s = 0; s < st.Substeps; s++)
            ctx.SubstepHeads[s] = ctx.Teleported || s == st.Substeps - 1 ? headTarget // exact at the frame's end
                : RigidTransform.Interpolate(world.Head, headTarget, (s + 1) / (float)st.Substeps);

        var colliders = _scene.Colliders;
        int nc = colliders.Count;
        if (ctx.SubstepColliders.Length < nc * st.Substeps) ctx.SubstepColliders = new Collider[nc * st.Substeps];
        ctx.ColliderCount = nc;
        for (int s = 0; s < st.Substeps; s++)
        {
            // A moved collider goes the same share of its way as the head does of its own (exact at the frame's end).
            float f = s == st.Substeps - 1 ? to : from + (to - from) * ((s + 1) / (float)st.Substeps);
            for (int c = 0; c < nc; c++)
            {
                var placed = _colliderMoves[c] ? Collider.Interpolate(_scene.ColliderBefore(c), colliders[c], f) : colliders[c];
                ctx.SubstepColliders[s * nc + c] = placed.ToWorld(ctx.SubstepHeads[s]);
            }
        }

        var meshes = _scene.MeshColliderArray;
        if (ctx.SubstepMeshPoses.Length < meshes.Length * st.Substeps) ctx.SubstepMeshPoses = new RigidTransform[meshes.Length * st.Substeps];
        ctx.SubstepMeshes = meshes;
        for (int s = 0; s < st.Substeps; s++)
        {
            float f = s == st.Substeps - 1 ? to : from + (to - from) * ((s + 1) / (float)st.Substeps);
            for (int m = 0; m < meshes.Length; m++)
            {
                var mc = meshes[m];
                ctx.SubstepMeshPoses[s * meshes.Length + m] = _meshMoves[m]
                    ? mc.PoseFor(ctx.SubstepHeads[s], RigidTransform.Interpolate(mc.PlacementBefore, mc.Placement, f))
                    : mc.PoseFor(ctx.SubstepHeads[s]);
            }
        }

        for (int k = 0; k < _passStart.Length; k++)
            _passStart[k].PassStarting(_scene, ctx, from == 0f);
        // Systems that couple strands (volume) see the state the last frame left and change velocities before any substep.
        for (int k = 0; k < _frameStart.Length; k++)
            _frameStart[k].Run(_scene, ctx, 0, 0, world.StrandCount);
        if (_substep.Length > 0)
        {
            _chunkFrame = UsesStrandChunks && _chunks!.BeginFrame(ctx, world);
            if (_chunkFrame) _chunks!.ResetCounts();
            // Small blocks (~ParticlesPerJob) keep a block's data in L2 across all its substeps and systems.
            long blocks = (world.ParticleCount + ParticlesPerJob - 1) / ParticlesPerJob;
            _jobCount = (int)Math.Max(1, Math.Min(world.StrandCount, Math.Max(blocks, _dispatcher.ThreadCount == 1 ? 1 : _dispatcher.ThreadCount * 4)));
            _dispatcher.Run(_jobCount, _substepJob); // each job also contains non-finite values in its strands
        }
        else _containment.Scan(world, headTarget, 0, world.StrandCount);
        // Systems that resolve what the substeps left between strands (contacts) see the pass's end.
        for (int k = 0; k < _passEnd.Length; k++)
            _passEnd[k].Run(_scene, ctx, 0, 0, world.StrandCount);
        world.Head = headTarget;
        if (_frameEnd.Length > 0)
        {
            _jobCount = Math.Max(1, Math.Min(world.SheetCount, _dispatcher.ThreadCount == 1 ? 1 : _dispatcher.ThreadCount * 4));
            _dispatcher.Run(_jobCount, _frameEndJob);
        }
    }

    private void RunSubstepJob(int job)
    {
        int n = _scene.World.StrandCount;
        int begin = (int)((long)n * job / _jobCount), end = (int)((long)n * (job + 1) / _jobCount);
        if (_chunkFrame)
        {
            // Job bounds on whole chunks, so a small scene split across threads still fills chunks.
            const int L = Fast.StrandChunk.Lanes;
            long groups = (n + L - 1) / L;
            begin = (int)Math.Min(n, L * (groups * job / _jobCount));
            end = (int)Math.Min(n, L * (groups * (job + 1) / _jobCount));
            // The runner scans each chunk's rows before storing them, and the other strands right after their steps.
            _chunks!.Run(_scene, _ctx, begin, end, _containment);
            return;
        }
        for (int s = 0; s < _ctx.Substeps; s++)
            for (int k = 0; k < _substep.Length; k++)
                _substep[k].Run(_scene, _ctx, s, begin, end);
        // A strand left non-finite goes back to its rest pose.
        _containment.Scan(_scene.World, _ctx.HeadEnd, begin, end);
    }

    private void RunFrameEndJob(int job)
    {
        int n = _scene.World.SheetCount;
        int begin = (int)((long)n * job / _jobCount), end = (int)((long)n * (job + 1) / _jobCount);
        for (int k = 0; k < _frameEnd.Length; k++)
            _frameEnd[k].Run(_scene, _ctx, 0, begin, end);
    }
}
