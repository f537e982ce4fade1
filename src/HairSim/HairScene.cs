namespace HairSim;

/// <summary>
/// A world plus what the scene contains: colliders, settings, optionally render output and any extra
/// components (edit history, wind, …). The pipeline is built from what is present, nothing else.
/// </summary>
public sealed class HairScene
{
    private readonly List<Collider> _colliders = new();
    private readonly Dictionary<Type, object> _components = new();
    private RenderSettings? _render;

    public HairScene(HairWorld world, SimulationSettings? settings = null)
    {
        World = world ?? throw new ArgumentNullException(nameof(world));
        Settings = settings ?? new SimulationSettings();
        Settings.Validate();
    }

    public HairWorld World { get; }
    public SimulationSettings Settings { get; }
    public IReadOnlyList<Collider> Colliders => _colliders;

    /// <summary>Render interpolation settings; null means nothing is drawn (no interpolation system).</summary>
    public RenderSettings? Render
    {
        get => _render;
        set { value?.Validate(); _render = value; Revision++; }
    }

    /// <summary>Render strands, filled by the interpolation system when <see cref="Render"/> is set.</summary>
    public RenderStrands? RenderOutput { get; internal set; }

    /// <summary>Bumped whenever the scene's contents change, so the pipeline knows to rebuild.</summary>
    public int Revision { get; private set; }

    public void AddCollider(Collider c) { _colliders.Add(c); Revision++; }
    public void RemoveColliderAt(int index) { _colliders.RemoveAt(index); Revision++; }
    public void ClearColliders() { _colliders.Clear(); Revision++; }

    /// <summary>Call after changing <see cref="Settings"/> so the pipeline is rebuilt with them (validated first).</summary>
    public void SettingsChanged() { Settings.Validate(); Revision++; }

    public void SetComponent<T>(T component) where T : class { _components[typeof(T)] = component; Revision++; }
    public bool RemoveComponent<T>() where T : class { bool r = _components.Remove(typeof(T)); if (r) Revision++; return r; }
    public bool HasComponent<T>() where T : class => _components.ContainsKey(typeof(T));
    public T? GetComponent<T>() where T : class => _components.TryGetValue(typeof(T), out var c) ? (T)c : null;
}
