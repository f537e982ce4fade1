namespace HairSim;

/// <summary>
/// A world plus what the scene contains: colliders, settings, optionally render output and any extra
/// components (edit history, wind, …). The pipeline is built from what is present, nothing else.
/// </summary>
public sealed class HairScene
{
    private readonly List<Collider> _colliders = new();
    // Each collider's placement at the end of the last stepped frame: the pipeline moves it from there across the substeps.
    private readonly List<Collider> _collidersBefore = new();
    private float _longestRest;
    private int _longestRestStamp = -1;
    private readonly Dictionary<Type, object> _components = new();
    // Mesh colliders added with AddMeshCollider, and every mesh collider the pipeline collides with (a new array on each change).
    private readonly List<Meshes.MeshCollider> _meshes = new();
    private Meshes.MeshCollider[] _allMeshes = [];
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

    /// <summary>Adds a collider (rebuilds the pipeline). A value not made by a <see cref="Collider"/> factory (<c>default</c>) is refused.</summary>
    public void AddCollider(Collider c)
    {
        if (!c.IsValid()) throw new ArgumentException("Make colliders with Collider.Ellipsoid, Sphere, Capsule or Plane.", nameof(c));
        _colliders.Add(c); _collidersBefore.Add(c); Revision++;
    }

    public void RemoveColliderAt(int index) { _colliders.RemoveAt(index); _collidersBefore.RemoveAt(index); Revision++; }
    public void ClearColliders() { _colliders.Clear(); _collidersBefore.Clear(); Revision++; }

    /// <summary>
    /// Moves collider <paramref name="index"/> to <paramref name="c"/>'s placement (and size) without rebuilding the pipeline:
    /// call it every frame for a collider on a bone (a shoulder capsule of a skinned body). The next frame carries it from
    /// where the last frame left it to here across its substeps, as the head is carried, so a fast collider sweeps
    /// the hair instead of jumping into it; a move beyond the teleport limits (<see cref="SimulationSettings.TeleportDistance"/>
    /// × the hair's reach, <see cref="SimulationSettings.TeleportAngle"/>), a head teleport or a change between head and
    /// world space places it at once. The kind must stay (remove and add to change it); a bad index or a value not made
    /// by a factory is refused (ArgumentException, nothing changed). Allocates nothing; <see cref="Revision"/> moves only
    /// when a sphere or capsule becomes thinner or thicker than the longest segment (the segment test joins or leaves).
    /// Not while a step runs on another thread.
    /// </summary>
    public void SetCollider(int index, Collider c)
    {
        if ((uint)index >= (uint)_colliders.Count)
            throw new ArgumentOutOfRangeException(nameof(index), index, $"Collider index must be in [0, {_colliders.Count}).");
        if (!c.IsValid()) throw new ArgumentException("Make colliders with Collider.Ellipsoid, Sphere, Capsule or Plane.", nameof(c));
        var old = _colliders[index];
        if (old.Kind != c.Kind)
            throw new ArgumentException($"Collider {index} is a {old.Kind}, not a {c.Kind}: remove it and add the new one.", nameof(c));
        _colliders[index] = c;
        if (old.Radius != c.Radius && IsThin(old) != IsThin(c)) Revision++;
    }

    /// <summary>Where collider c was at the end of the last stepped frame (its start placement for the next).</summary>
    internal Collider ColliderBefore(int index) => _collidersBefore[index];

    /// <summary>A frame has been stepped: the colliders' placements are its end and the next frame's start.</summary>
    internal void CollidersStepped()
    {
        for (int c = 0; c < _colliders.Count; c++) _collidersBefore[c] = _colliders[c];
        foreach (var m in _allMeshes) m.Stepped();
    }

    /// <summary>Whether the segment test handles this collider (<see cref="SegmentCollideSystem.Needed"/>): a sphere or capsule thinner than the longest segment.</summary>
    private bool IsThin(in Collider c)
    {
        if (c.Kind is not (ColliderKind.Sphere or ColliderKind.Capsule)) return false;
        if (_longestRestStamp != World.EditStamp)
        {
            float longest = 0f;
            foreach (float l in World.RestLength) longest = MathF.Max(longest, l);
            _longestRest = longest; _longestRestStamp = World.EditStamp;
        }
        return c.Radius < _longestRest;
    }

    /// <summary>Call after changing <see cref="Settings"/> so the pipeline is rebuilt with them (validated first).</summary>
    public void SettingsChanged() { Settings.Validate(); Revision++; }

    public void SetComponent<T>(T component) where T : class
    {
        _components[typeof(T)] = component;
        if (typeof(T) == typeof(Meshes.MeshCollider)) MeshesChanged();
        Revision++;
    }

    public bool RemoveComponent<T>() where T : class
    {
        bool r = _components.Remove(typeof(T));
        if (r && typeof(T) == typeof(Meshes.MeshCollider)) MeshesChanged();
        if (r) Revision++;
        return r;
    }

    /// <summary>
    /// Every mesh the hair collides with, in the order they act: the one set as a component
    /// (<c>SetComponent(new MeshCollider(…))</c>, e.g. the scalp's head mesh) first, then those added with
    /// <see cref="AddMeshCollider"/> (a body, a prop), each with its own placement and space.
    /// </summary>
    public IReadOnlyList<Meshes.MeshCollider> MeshColliders => _allMeshes;

    /// <summary>The same, as the array the systems read (replaced, never changed, when the list changes).</summary>
    internal Meshes.MeshCollider[] MeshColliderArray => _allMeshes;

    /// <summary>Adds a mesh collider beside any others (rebuilds the pipeline); one already in the scene is refused.</summary>
    public void AddMeshCollider(Meshes.MeshCollider collider)
    {
        ArgumentNullException.ThrowIfNull(collider);
        if (Array.IndexOf(_allMeshes, collider) >= 0) throw new ArgumentException("This mesh collider is already in the scene.", nameof(collider));
        _meshes.Add(collider);
        MeshesChanged();
        Revision++;
    }

    /// <summary>Removes a mesh collider, whichever way it was added; false if it is not in the scene.</summary>
    public bool RemoveMeshCollider(Meshes.MeshCollider collider)
    {
        if (ReferenceEquals(GetComponent<Meshes.MeshCollider>(), collider)) return RemoveComponent<Meshes.MeshCollider>();
        if (!_meshes.Remove(collider)) return false;
        MeshesChanged();
        Revision++;
        return true;
    }

    /// <summary>Removes every mesh collider (the component too).</summary>
    public void ClearMeshColliders()
    {
        _components.Remove(typeof(Meshes.MeshCollider));
        _meshes.Clear();
        MeshesChanged();
        Revision++;
    }

    private void MeshesChanged()
    {
        var component = GetComponent<Meshes.MeshCollider>();
        var all = new List<Meshes.MeshCollider>(_meshes.Count + 1);
        if (component != null) all.Add(component);
        foreach (var m in _meshes) if (!ReferenceEquals(m, component)) all.Add(m);
        // A collider that joins (or is listed again) starts where it is placed, not carried from an older placement.
        foreach (var m in all) if (Array.IndexOf(_allMeshes, m) < 0) m.Stepped();
        _allMeshes = all.ToArray();
    }
    public bool HasComponent<T>() where T : class => _components.ContainsKey(typeof(T));
    public T? GetComponent<T>() where T : class => _components.TryGetValue(typeof(T), out var c) ? (T)c : null;
}
