namespace HairSim;

/// <summary>When a system runs, and over what range.</summary>
public enum SystemPhase
{
    /// <summary>Every substep, over a range of strands (strands never interact, so ranges run in parallel).</summary>
    Substep,
    /// <summary>Once per frame after all substeps, over a range of sheets (e.g. render interpolation).</summary>
    FrameEnd,
    /// <summary>
    /// Once per frame before the substeps, over the whole world, called on the stepping thread: for systems that couple
    /// strands (hair volume). Such a system forks its own parallel passes through <see cref="FrameContext.Dispatcher"/>.
    /// </summary>
    FrameStart,
    /// <summary>
    /// Once per pass after the substeps (a frame stepped in parts runs it after each part), over the whole world, on
    /// the stepping thread: for systems that resolve what the substeps left between strands (strand contacts).
    /// </summary>
    PassEnd,
}

/// <summary>
/// A <see cref="SystemPhase.PassEnd"/> system told when a pass begins, before anything moves (to keep the positions
/// the pass starts from).
/// </summary>
public interface IPassStartListener
{
    /// <param name="firstOfFrame">True at a frame's first pass: nothing has moved yet, so the system may still refuse the frame.</param>
    void PassStarting(HairScene scene, FrameContext ctx, bool firstOfFrame);
}

/// <summary>A behaviour over the world's data. Systems hold no per-particle state of their own.</summary>
public interface IHairSystem
{
    string Name { get; }
    SystemPhase Phase { get; }
    /// <summary>Runs on strands (Substep, FrameStart: all of them) or sheets (FrameEnd) [begin, end). Must not allocate.</summary>
    void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end);
}

/// <summary>Per-frame values shared by the systems; owned and reused by the pipeline (no per-step allocation).</summary>
public sealed class FrameContext
{
    public float Dt { get; internal set; }
    public int Substeps { get; internal set; }
    /// <summary>Substep length h = Dt / Substeps.</summary>
    public float H { get; internal set; }
    public SimulationSettings Settings { get; internal set; } = new();
    public RigidTransform HeadStart { get; internal set; } = RigidTransform.Identity;
    public RigidTransform HeadEnd { get; internal set; } = RigidTransform.Identity;
    /// <summary>True when the head jumped farther than the teleport limits this frame: hair is carried rigidly.</summary>
    public bool Teleported { get; internal set; }
    /// <summary>The rigid jump applied on a teleport frame.</summary>
    public RigidTransform TeleportDelta { get; internal set; } = RigidTransform.Identity;
    /// <summary>The groom's size the scale-free settings are measured against.</summary>
    public GroomScale Scale { get; internal set; }
    /// <summary>The pipeline's dispatcher, for <see cref="SystemPhase.FrameStart"/> systems that fork their own passes.</summary>
    public IThreadDispatcher Dispatcher { get; internal set; } = SequentialDispatcher.Instance;

    internal IStrandMovedListener[] MovedListeners = [];

    /// <summary>For systems outside the substeps: strand s was moved (systems that keep its positions from the last substep take the new ones).</summary>
    internal void StrandMoved(HairWorld world, int strand)
    {
        for (int k = 0; k < MovedListeners.Length; k++) MovedListeners[k].StrandMoved(world, strand);
    }

    internal RigidTransform[] SubstepHeads = new RigidTransform[1];
    internal Collider[] SubstepColliders = [];
    internal int ColliderCount;

    /// <summary>Head pose at the end of substep s (pins are placed there at the start of the substep).</summary>
    public RigidTransform HeadAt(int substep) => SubstepHeads[substep];

    /// <summary>World-space colliders for substep s.</summary>
    public ReadOnlySpan<Collider> CollidersAt(int substep) => SubstepColliders.AsSpan(substep * ColliderCount, ColliderCount);

    internal RigidTransform[] SubstepMeshPoses = [];
    internal Meshes.MeshCollider[] SubstepMeshes = [];

    /// <summary>
    /// World pose of mesh collider m of <paramref name="colliders"/> at the end of substep s: carried across the frame
    /// when the pipeline prepared it for these colliders, else (a context not made by the pipeline, or another
    /// scene's colliders) its placement at the substep's head.
    /// </summary>
    internal RigidTransform MeshPoseAt(int substep, int m, Meshes.MeshCollider[] colliders) =>
        ReferenceEquals(colliders, SubstepMeshes) ? SubstepMeshPoses[substep * colliders.Length + m] : colliders[m].PoseFor(HeadAt(substep));
}

/// <summary>
/// A <see cref="SystemPhase.FrameStart"/> system that needs frames no longer than some time: the pipeline steps a longer
/// frame in that many parts, each running the system once and its share of the substeps.
/// </summary>
public interface IFrameSplitter
{
    /// <summary>Into how many parts a frame of <paramref name="dt"/> seconds must be cut (1 = none). May throw for bad settings, before anything moves.</summary>
    int PartsOf(HairScene scene, float dt, GroomScale scale);

    /// <summary>
    /// The longest part, in seconds, the state this system last measured can take without going unstable (asked before
    /// every part; the rest of the frame is then cut into equal parts no longer than this). Infinity: no limit.
    /// </summary>
    double LongestPart(HairScene scene, GroomScale scale) => double.PositiveInfinity;

    /// <summary>The most parts a frame is ever cut into.</summary>
    public const int MaxParts = 64;
}
