using System.Numerics;

namespace HairSim.Editing;

/// <summary>
/// A screen-space polyline in pixels plus the camera that saw it. Consecutive repeated points (a mouse that
/// did not move between events) are merged; a stroke with fewer than two distinct points, a non-finite point
/// or a point outside the viewport is refused with an <see cref="ArgumentException"/>.
/// </summary>
public sealed class Stroke
{
    /// <summary>Points closer than this (pixels) count as repeated.</summary>
    public const float RepeatTolerance = 1e-3f;
    public const int MaxPoints = 100_000;

    private readonly Vector2[] _points;

    public Stroke(ReadOnlySpan<Vector2> points, StrokeCamera camera)
    {
        Camera = camera ?? throw new ArgumentNullException(nameof(camera));
        if (points.Length < 2) throw new ArgumentException($"A stroke needs at least 2 points, got {points.Length}.", nameof(points));
        if (points.Length > MaxPoints) throw new ArgumentException($"A stroke may have at most {MaxPoints} points, got {points.Length}.", nameof(points));
        var kept = new List<Vector2>(points.Length);
        for (int k = 0; k < points.Length; k++)
        {
            var p = points[k];
            if (!float.IsFinite(p.X) || !float.IsFinite(p.Y)) throw new ArgumentException($"Stroke point {k} is not finite.", nameof(points));
            if (!camera.InViewport(p))
                throw new ArgumentException($"Stroke point {k} ({p.X}, {p.Y}) is outside the {camera.ViewportSize.X}×{camera.ViewportSize.Y} viewport.", nameof(points));
            if (kept.Count > 0 && Vector2.Distance(kept[^1], p) < RepeatTolerance) continue;
            kept.Add(p);
        }
        if (kept.Count < 2) throw new ArgumentException("The stroke's points all repeat one position: a stroke needs two distinct points.", nameof(points));
        _points = kept.ToArray();
        float len = 0;
        for (int k = 1; k < _points.Length; k++) len += Vector2.Distance(_points[k - 1], _points[k]);
        ScreenLength = len;
    }

    public Stroke(IEnumerable<Vector2> points, StrokeCamera camera) : this((points ?? throw new ArgumentNullException(nameof(points))).ToArray().AsSpan(), camera) { }

    public StrokeCamera Camera { get; }
    public ReadOnlySpan<Vector2> Points => _points;
    public int Count => _points.Length;
    /// <summary>Length of the polyline in pixels.</summary>
    public float ScreenLength { get; }
}
