namespace HairSim;

/// <summary>
/// Runs a scene: builds its pipeline, rebuilds it when the scene's contents change, and steps it.
/// This is what a game loop or the Godot node owns.
/// </summary>
public sealed class HairSimulation
{
    private readonly PipelineBuilder _builder;
    private readonly IThreadDispatcher? _dispatcher;
    private HairPipeline? _pipeline;
    private int _builtRevision = -1;
    private HairPipeline? _stepped;

    public HairSimulation(HairScene scene, PipelineBuilder? builder = null, IThreadDispatcher? dispatcher = null)
    {
        Scene = scene ?? throw new ArgumentNullException(nameof(scene));
        _builder = builder ?? PipelineBuilder.CreateDefault();
        _dispatcher = dispatcher;
    }

    public HairScene Scene { get; }
    public HairWorld World => Scene.World;
    public double Time { get; private set; }
    public long Frame { get; private set; }

    /// <summary>
    /// What the last frame had to contain: strands that held a NaN or ±∞ at its end (written by a custom system or a bug)
    /// and were put back at their rest pose on the head; empty before the first frame. Reused every frame.
    /// </summary>
    public FrameReport LastFrameReport => _stepped?.LastFrameReport ?? FrameReport.Empty;

    /// <summary>Strands reset since this simulation was made (the sum of every frame's <see cref="FrameReport.StrandsReset"/>).</summary>
    public long StrandsResetTotal { get; private set; }

    /// <summary>The current pipeline (rebuilt first if the scene changed).</summary>
    public HairPipeline Pipeline
    {
        get
        {
            if (_pipeline == null || _builtRevision != Scene.Revision)
            {
                _pipeline = _builder.Build(Scene, _dispatcher);
                _builtRevision = Scene.Revision;
            }
            return _pipeline;
        }
    }

    /// <summary>One frame with the head held where it is.</summary>
    public void Step(float dt) => Step(dt, World.Head);

    /// <summary>One frame while the head moves to headTarget (pins and colliders follow it across the substeps).</summary>
    public void Step(float dt, RigidTransform headTarget)
    {
        var pipeline = Pipeline;
        pipeline.Step(dt, headTarget);
        _stepped = pipeline;
        StrandsResetTotal += pipeline.LastFrameReport.StrandsReset;
        Time += dt;
        Frame++;
    }
}
