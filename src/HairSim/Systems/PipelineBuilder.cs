namespace HairSim;

/// <summary>
/// Builds a scene's pipeline from registered system factories, keeping only the systems whose data the
/// scene has. Order: volume (once per frame, before the substeps), head follow, shape match, integrate, bend, length, collide, mesh collide, segment collide (substeps), strand contacts (after the substeps of each pass), then interpolation.
/// Other libraries (editing tools, wind, …) add their factories with <see cref="Add"/>.
/// </summary>
public sealed class PipelineBuilder
{
    public const int OrderVolume = 50, OrderHeadFollow = 100, OrderShapeMatch = 200, OrderIntegrate = 300, OrderBend = 350, OrderLength = 400,
        OrderCollide = 500, OrderMeshCollide = 520, OrderSegmentCollide = 550, OrderStrandContact = 800, OrderInterpolate = 1000;

    private readonly List<SystemFactory> _factories = new();

    public IReadOnlyList<SystemFactory> Factories => _factories;

    public PipelineBuilder Add(SystemFactory factory)
    {
        if (_factories.Exists(f => f.Name == factory.Name))
            throw new ArgumentException($"A system named '{factory.Name}' is already registered.", nameof(factory));
        _factories.Add(factory);
        return this;
    }

    /// <summary>Replaces a registered factory (for example to supply a fast implementation).</summary>
    public PipelineBuilder Replace(SystemFactory factory)
    {
        int i = _factories.FindIndex(f => f.Name == factory.Name);
        if (i < 0) throw new ArgumentException($"No system named '{factory.Name}' is registered.", nameof(factory));
        _factories[i] = factory;
        return this;
    }

    /// <summary>The core systems of HairSim.</summary>
    public static PipelineBuilder CreateDefault() => CreateDefault(allowAvx512: true);

    /// <summary>
    /// The core systems; with <paramref name="allowAvx512"/> false the fast systems keep to 8-lane (AVX) code even
    /// on CPUs with AVX-512. Both give the same bits; this exists to measure and test the two against each other.
    /// </summary>
    public static PipelineBuilder CreateDefault(bool allowAvx512)
    {
        var b = new PipelineBuilder();
        b.Add(new SystemFactory(VolumeSystem.SystemName, SystemPhase.FrameStart, OrderVolume,
            s => s.HasComponent<VolumeSettings>() && s.World.StrandCount > 0, _ => new VolumeSystem()));
        b.Add(new SystemFactory(HeadFollowSystem.SystemName, SystemPhase.Substep, OrderHeadFollow,
            s => s.World.StrandCount > 0, _ => new HeadFollowSystem()));
        b.Add(new SystemFactory(ShapeMatchSystem.SystemName, SystemPhase.Substep, OrderShapeMatch,
            s => (s.Settings.Bend == BendModel.SourceTriples && s.Settings.Alpha > 0f && s.World.MaxStrandCapacity >= 3) || s.Settings.GlobalShapeStiffness > 0f,
            s => new ShapeMatchSystem(s.World.MaxStrandCapacity)));
        b.Add(new SystemFactory(IntegrateSystem.SystemName, SystemPhase.Substep, OrderIntegrate,
            s => s.World.StrandCount > 0, _ => new IntegrateSystem()));
        b.Add(new SystemFactory(BendSystem.SystemName, SystemPhase.Substep, OrderBend,
            s => s.Settings.Bend == BendModel.RestShape, s => new BendSystem(s.World)));
        // The bend sweep places particles at their rest lengths itself (follow-the-leader fused in).
        b.Add(new SystemFactory(LengthSystem.SystemName, SystemPhase.Substep, OrderLength,
            s => s.Settings.Length != LengthMode.None && !LengthSystem.FusedIntoBend(s.Settings),
            s => new LengthSystem(s.World.MaxStrandCapacity)));
        b.Add(new SystemFactory(CollideSystem.SystemName, SystemPhase.Substep, OrderCollide,
            s => s.Colliders.Count > 0, _ => new CollideSystem()));
        b.Add(new SystemFactory(Meshes.MeshCollideSystem.SystemName, SystemPhase.Substep, OrderMeshCollide,
            s => s.MeshColliders.Count > 0, _ => new Meshes.MeshCollideSystem()));
        b.Add(new SystemFactory(SegmentCollideSystem.SystemName, SystemPhase.Substep, OrderSegmentCollide,
            SegmentCollideSystem.Needed, _ => new SegmentCollideSystem()));
        b.Add(new SystemFactory(StrandContactSystem.SystemName, SystemPhase.PassEnd, OrderStrandContact,
            s => s.HasComponent<StrandContactSettings>() && s.World.StrandCount > 1, _ => new StrandContactSystem()));
        b.Add(new SystemFactory(InterpolateSystem.SystemName, SystemPhase.FrameEnd, OrderInterpolate,
            s => s.Render != null, s => new InterpolateSystem(s)));
        FastPathRegistration.Apply(b, allowAvx512);
        return b;
    }

    public HairPipeline Build(HairScene scene, IThreadDispatcher? dispatcher = null)
    {
        scene.Settings.Validate();
        var chosen = new List<SystemFactory>();
        foreach (var f in _factories) if (f.IsNeeded(scene)) chosen.Add(f);
        chosen.Sort((a, b) => a.Order != b.Order ? a.Order.CompareTo(b.Order) : string.CompareOrdinal(a.Name, b.Name));
        bool fast = scene.Settings.Path == SolverPath.Fast;
        if (scene.Render == null) scene.RenderOutput = null;
        var systems = new List<IHairSystem>(chosen.Count);
        foreach (var f in chosen)
            systems.Add(fast && f.CreateFast != null ? f.CreateFast(scene) : f.CreateReference(scene));
        return new HairPipeline(scene, systems, fast ? dispatcher ?? SequentialDispatcher.Instance : SequentialDispatcher.Instance);
    }
}

/// <summary>Hook for the optimised path to swap in its implementations (see FastPath).</summary>
internal static partial class FastPathRegistration
{
    static partial void ApplyFast(PipelineBuilder builder, bool allowWide);
    public static void Apply(PipelineBuilder builder, bool allowWide) => ApplyFast(builder, allowWide);
}
