namespace HairSim.Measurement;

/// <summary>
/// Scenes that need less than the whole pipeline, for measuring what leaving systems out saves. Each case builds
/// its scene twice: lean (the default builder, which keeps only the systems the scene's data asks for) and kept (the
/// same hair with every core system in the pipeline anyway, doing work that changes nothing). Both give the same
/// particle bits (tested), so any difference in run time is what leaving out saves.
/// </summary>
public sealed record LeaveOutCase(string Name, string Has, Action<HairScene> Strip)
{
    /// <summary>
    /// The cases, from a game character's hair (everything needed) down to particles on a moving head:
    /// no render strands (a server, a capture tool, or a renderer that draws only simulated strands), no collider
    /// (hair that never reaches the head), limp hair (no bending: a follow-the-leader length pass instead of the bend
    /// sweep), limp hair that may stretch (no length pass either), and all of these at once; last, the game character
    /// with hair volume (<see cref="VolumeSettings"/>): a scene that asks for more, so its row shows what the volume
    /// system costs when present (every other row's lean pipeline leaves it out, at no cost).
    /// </summary>
    public static IReadOnlyList<LeaveOutCase> All { get; } =
    [
        new("game character", "head collider, render strands, bend sweep with exact lengths", _ => { }),
        new("no render strands", "nothing drawn from the library's interpolation", s => s.Render = null),
        new("no collider", "nothing to slide over", s => s.ClearColliders()),
        new("limp hair", "no bending (BendModel.Limp): a length pass only", s => { s.Settings.Bend = BendModel.Limp; s.SettingsChanged(); }),
        new("no length pass", "limp and stretchy (BendModel.Limp, LengthMode.None)", s =>
        {
            s.Settings.Bend = BendModel.Limp; s.Settings.Length = LengthMode.None; s.SettingsChanged();
        }),
        new("bare", "all of the above: particles on a moving head", s =>
        {
            s.Render = null; s.ClearColliders();
            s.Settings.Bend = BendModel.Limp; s.Settings.Length = LengthMode.None; s.SettingsChanged();
        }),
        new("hair volume", "the game character plus hair volume (VolumeSettings defaults)", s => s.SetComponent(new VolumeSettings())),
        new("hair volume, layers kept", "the same with a volume pass every 1/32 natural time (MaxStep; 4 per 60 Hz frame)",
            s => s.SetComponent(new VolumeSettings { MaxStep = 1f / 32 })),
    ];

    /// <summary>
    /// The lean scene: <paramref name="groom"/> on the head with render strands (default <see cref="RenderSettings"/>),
    /// then what this case takes away.
    /// </summary>
    public HairScene BuildLean(GroomSettings groom, SimulationSettings settings)
    {
        var scene = GroomBuilder.BuildScene(groom, settings.Clone());
        scene.Render = new RenderSettings();
        Strip(scene);
        return scene;
    }

    /// <summary>
    /// The kept scene: the lean scene's hair and settings, with render strands set (nothing reads them) so
    /// interpolation runs. Build its pipeline with <see cref="KeepEverything"/>.
    /// </summary>
    public HairScene BuildKept(GroomSettings groom, SimulationSettings settings)
    {
        var scene = BuildLean(groom, settings);
        scene.Render ??= new RenderSettings();
        return scene;
    }

    /// <summary>
    /// A builder whose core systems all join every pipeline, needed or not (interpolation only where render settings
    /// exist, since it has nowhere to write otherwise): the pipeline a framework without leaving out would run.
    /// </summary>
    public static PipelineBuilder KeepEverything(PipelineBuilder? from = null)
    {
        var kept = new PipelineBuilder();
        foreach (var f in (from ?? PipelineBuilder.CreateDefault()).Factories)
            kept.Add(f.Name == InterpolateSystem.SystemName ? f : f with { IsNeeded = _ => true });
        return kept;
    }
}
