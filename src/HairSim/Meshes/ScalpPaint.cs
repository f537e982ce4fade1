using System.Numerics;
using HairSim.Editing;

namespace HairSim.Meshes;

/// <summary>Whether a paint stroke marks triangles as scalp or clears them.</summary>
public enum ScalpPaintMode { Add, Remove }

/// <summary>
/// The scalp of a head mesh painted with strokes: which triangles grow hair. A stroke is a screen-space area
/// (<see cref="SelectionArea"/>: rectangle, lasso or brush) seen through a <see cref="StrokeCamera"/>, the same
/// machinery as cut and fit; it marks the triangles whose centre it covers, that face the camera and (given an
/// occluder) that the mesh itself does not hide, so painting the front of the head does not reach the back. Every
/// stroke that changes something is one undo step. Give it to <see cref="MeshGroomSettings.Scalp"/> to grow there.
/// </summary>
public sealed class ScalpPaint
{
    private readonly bool[] _scalp;
    private readonly List<Step> _undo = [], _redo = [];

    /// <summary>One stroke (or whole-mask change): the triangles it marked and the ones it cleared.</summary>
    private readonly record struct Step(int[] Marked, int[] Cleared)
    {
        public int Count => Marked.Length + Cleared.Length;
    }

    /// <param name="mesh">The head mesh (head space, as the groom and the field use it).</param>
    /// <param name="everywhere">Start with every triangle marked (then paint away), or none (then paint on).</param>
    public ScalpPaint(TriangleMesh mesh, bool everywhere = false)
    {
        ArgumentNullException.ThrowIfNull(mesh);
        Mesh = mesh;
        _scalp = new bool[mesh.TriangleCount];
        if (everywhere) Array.Fill(_scalp, true);
    }

    /// <summary>The scalp a vertex-colour mask gives (red at least <paramref name="threshold"/>; everywhere without colours), to paint on from there.</summary>
    public static ScalpPaint FromVertexColours(TriangleMesh mesh, float threshold)
    {
        ArgumentNullException.ThrowIfNull(mesh);
        if (!float.IsFinite(threshold) || threshold < 0f || threshold > 1f)
            throw new ArgumentOutOfRangeException(nameof(threshold), threshold, "The mask threshold must be 0 … 1.");
        var paint = new ScalpPaint(mesh, everywhere: mesh.Colors == null);
        if (mesh.Colors == null) return paint;
        var c = mesh.Colors; var idx = mesh.Indices;
        for (int t = 0; t < mesh.TriangleCount; t++)
            paint._scalp[t] = (c[idx[3 * t]].X + c[idx[3 * t + 1]].X + c[idx[3 * t + 2]].X) / 3f >= threshold;
        return paint;
    }

    /// <summary>
    /// A scalp painted earlier (e.g. stored with a scene as one flag per triangle), to grow on or paint on from there.
    /// A mask made for a mesh with another triangle count is refused (ArgumentException).
    /// </summary>
    public static ScalpPaint FromMask(TriangleMesh mesh, ReadOnlySpan<bool> triangles)
    {
        ArgumentNullException.ThrowIfNull(mesh);
        if (triangles.Length != mesh.TriangleCount)
            throw new ArgumentException($"The scalp mask has {triangles.Length} triangles but the mesh has {mesh.TriangleCount}: it was painted on another mesh.", nameof(triangles));
        var paint = new ScalpPaint(mesh);
        triangles.CopyTo(paint._scalp);
        return paint;
    }

    public TriangleMesh Mesh { get; }
    /// <summary>Per triangle of <see cref="Mesh"/>: scalp or not.</summary>
    public ReadOnlySpan<bool> Triangles => _scalp;
    public bool IsScalp(int triangle) => _scalp[triangle];

    /// <summary>Scalp triangles.</summary>
    public int Count
    {
        get { int n = 0; foreach (bool b in _scalp) if (b) n++; return n; }
    }

    /// <summary>Scalp area, square metres (head space).</summary>
    public double Area
    {
        get { double a = 0; for (int t = 0; t < _scalp.Length; t++) if (_scalp[t]) a += Mesh.TriangleArea(t); return a; }
    }

    public bool CanUndo => _undo.Count > 0;
    public bool CanRedo => _redo.Count > 0;
    /// <summary>Strokes (and whole-mask changes) that can be undone, and redone.</summary>
    public int UndoCount => _undo.Count;
    public int RedoCount => _redo.Count;

    /// <summary>
    /// Marks (or clears) the triangles under <paramref name="area"/> seen through <paramref name="camera"/>, with the
    /// mesh at <paramref name="head"/> in the world. A triangle counts when its centre projects inside the area, its
    /// face turns towards the camera and, when <paramref name="occluder"/> is given (the mesh's collider), nothing of
    /// the mesh lies between the camera and that centre. Returns how many triangles changed; a stroke that changes
    /// none leaves no undo step. Nothing changes if an argument is invalid.
    /// </summary>
    public int Paint(StrokeCamera camera, SelectionArea area, ScalpPaintMode mode, in RigidTransform head, MeshCollider? occluder = null)
    {
        ArgumentNullException.ThrowIfNull(area);
        return Paint(camera, [area], mode, head, occluder);
    }

    /// <summary>
    /// One stroke made of several areas (their union: a brush's dabs along its path, say), painted as
    /// <see cref="Paint(StrokeCamera, SelectionArea, ScalpPaintMode, in RigidTransform, MeshCollider?)"/> paints one,
    /// and undone as one step.
    /// </summary>
    public int Paint(StrokeCamera camera, IReadOnlyList<SelectionArea> areas, ScalpPaintMode mode, in RigidTransform head, MeshCollider? occluder = null)
    {
        ArgumentNullException.ThrowIfNull(camera);
        ArgumentNullException.ThrowIfNull(areas);
        if (areas.Count == 0) throw new ArgumentException("A stroke needs at least one area.", nameof(areas));
        foreach (var a in areas) if (a == null) throw new ArgumentNullException(nameof(areas), "A stroke's area is null.");
        if (mode is not (ScalpPaintMode.Add or ScalpPaintMode.Remove)) throw new ArgumentOutOfRangeException(nameof(mode), mode, "Unknown paint mode.");
        bool value = mode == ScalpPaintMode.Add;
        var changed = new List<int>();
        for (int t = 0; t < _scalp.Length; t++)
        {
            if (_scalp[t] == value) continue;
            var (a, b, c) = Mesh.Triangle(t);
            var centre = head.TransformPoint((a + b + c) / 3f);
            if (!camera.Project(centre, out var screen, out _) || !AnyContains(areas, screen)) continue;
            var normal = head.TransformDirection(Mesh.FaceNormal(t));
            var toCamera = camera.Kind == CameraProjection.Perspective ? camera.Position - centre : -camera.Forward;
            if (Vector3.Dot(normal, toCamera) <= 0f) continue;
            if (occluder != null && Hidden(occluder, head, camera, centre)) continue;
            changed.Add(t);
        }
        return Record(value ? new Step(changed.ToArray(), []) : new Step([], changed.ToArray()));
    }

    /// <summary>
    /// Replaces the whole mask (one entry per triangle: clear it, fill it, go back to the vertex colours' mask) as one
    /// undo step. Returns how many triangles changed; no change leaves no undo step.
    /// </summary>
    public int SetMask(ReadOnlySpan<bool> triangles)
    {
        if (triangles.Length != _scalp.Length)
            throw new ArgumentException($"The mask has {triangles.Length} entries; the mesh has {_scalp.Length} triangles.", nameof(triangles));
        var marked = new List<int>(); var cleared = new List<int>();
        for (int t = 0; t < _scalp.Length; t++)
            if (triangles[t] != _scalp[t]) (triangles[t] ? marked : cleared).Add(t);
        return Record(new Step(marked.ToArray(), cleared.ToArray()));
    }

    /// <summary>The same mask on the same mesh, without the undo history (to grow from while this one is painted on).</summary>
    public ScalpPaint CopyMask() => FromMask(Mesh, _scalp);

    private static bool AnyContains(IReadOnlyList<SelectionArea> areas, Vector2 p)
    {
        for (int i = 0; i < areas.Count; i++) if (areas[i].Contains(p)) return true;
        return false;
    }

    private int Record(Step step)
    {
        if (step.Count == 0) return 0;
        Apply(step, forward: true);
        _undo.Add(step);
        _redo.Clear();
        return step.Count;
    }

    /// <summary>Takes back the last stroke that changed something.</summary>
    public bool Undo()
    {
        if (_undo.Count == 0) return false;
        var step = _undo[^1];
        _undo.RemoveAt(_undo.Count - 1);
        Apply(step, forward: false);
        _redo.Add(step);
        return true;
    }

    /// <summary>Applies the last undone stroke again.</summary>
    public bool Redo()
    {
        if (_redo.Count == 0) return false;
        var step = _redo[^1];
        _redo.RemoveAt(_redo.Count - 1);
        Apply(step, forward: true);
        _undo.Add(step);
        return true;
    }

    private void Apply(Step step, bool forward)
    {
        // A step only ever marks triangles that were clear and clears ones that were marked, so undoing flips them back.
        foreach (int t in step.Marked) _scalp[t] = forward;
        foreach (int t in step.Cleared) _scalp[t] = !forward;
    }

    /// <summary>Does the mesh cover the point from the camera? (The visible-only cut's test, from the camera's ray.)</summary>
    private static bool Hidden(MeshCollider occluder, in RigidTransform head, StrokeCamera camera, Vector3 point)
    {
        Vector3 origin, dir;
        if (camera.Kind == CameraProjection.Perspective) { origin = camera.Position; dir = Vector3.Normalize(point - origin); }
        else { dir = camera.Forward; origin = point - dir * 1000f * MathF.Max(1f, occluder.Field.CellSize); }
        return HairEditor.MeshHides(occluder, head, origin, dir, Vector3.Dot(point - origin, dir));
    }
}
