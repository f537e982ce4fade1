using System.Numerics;

namespace HairSheet.Logic;

public enum PointerPhase { Down, Move, Up, Cancel }

/// <summary>One pointer event, engine-neutral: mouse (id <see cref="StrokeCapture.MousePointer"/>) or a touch finger (its index).</summary>
public readonly record struct PointerSample(PointerPhase Phase, int PointerId, Vector2 Position);

public enum StrokeEvent
{
    /// <summary>Not part of the stroke (other finger, not drawing, non-finite position).</summary>
    Ignored,
    Started,
    Extended,
    /// <summary>Closer than the minimum spacing to the last point (or a duplicate), or over the point limit.</summary>
    Skipped,
    Completed,
    Cancelled,
    /// <summary>Released, but the polyline is too short to be a stroke (a click or a tap).</summary>
    TooShort,
}

/// <summary>
/// Mouse and touch input → a screen-space stroke polyline. One pointer draws; a second finger touching
/// down cancels (it is a pinch or pan, not a stroke). Points closer than MinSpacing to the last kept point are
/// dropped, so the polyline does not depend on the input rate. The editor tool and the runtime node both use it.
/// </summary>
public sealed class StrokeCapture
{
    public const int MousePointer = -1;
    private readonly List<Vector2> _points = new();
    private Vector2[] _completed = [];

    public StrokeCapture(float minSpacing = 4f, float minLength = 8f, int maxPoints = 4096)
    {
        if (!float.IsFinite(minSpacing) || minSpacing < 0f) throw new ArgumentOutOfRangeException(nameof(minSpacing), minSpacing, "Minimum spacing must be ≥ 0 pixels.");
        if (!float.IsFinite(minLength) || minLength < 0f) throw new ArgumentOutOfRangeException(nameof(minLength), minLength, "Minimum length must be ≥ 0 pixels.");
        if (maxPoints < 2) throw new ArgumentOutOfRangeException(nameof(maxPoints), maxPoints, "A stroke needs room for at least 2 points.");
        MinSpacing = minSpacing; MinLength = minLength; MaxPoints = maxPoints;
    }

    public float MinSpacing { get; }
    public float MinLength { get; }
    public int MaxPoints { get; }
    public bool IsDrawing { get; private set; }
    public int ActivePointer { get; private set; }
    /// <summary>The stroke in progress (for overlay drawing).</summary>
    public IReadOnlyList<Vector2> Points => _points;
    /// <summary>The last completed stroke (empty until one completes).</summary>
    public IReadOnlyList<Vector2> Completed => _completed;

    public StrokeEvent Handle(in PointerSample s)
    {
        bool finite = float.IsFinite(s.Position.X) && float.IsFinite(s.Position.Y);
        switch (s.Phase)
        {
            case PointerPhase.Down:
                if (IsDrawing)
                {
                    if (s.PointerId == ActivePointer) return StrokeEvent.Ignored;
                    Cancel();
                    return StrokeEvent.Cancelled;
                }
                if (!finite) return StrokeEvent.Ignored;
                _points.Clear();
                _points.Add(s.Position);
                IsDrawing = true;
                ActivePointer = s.PointerId;
                return StrokeEvent.Started;
            case PointerPhase.Move:
                if (!IsDrawing || s.PointerId != ActivePointer || !finite) return StrokeEvent.Ignored;
                return Append(s.Position) ? StrokeEvent.Extended : StrokeEvent.Skipped;
            case PointerPhase.Up:
                if (!IsDrawing || s.PointerId != ActivePointer) return StrokeEvent.Ignored;
                if (finite) Finish(s.Position);
                IsDrawing = false;
                if (_points.Count < 2 || PathLength(_points) < Math.Max(MinLength, 1e-6f))
                {
                    _points.Clear();
                    return StrokeEvent.TooShort;
                }
                _completed = _points.ToArray();
                _points.Clear();
                return StrokeEvent.Completed;
            case PointerPhase.Cancel:
                if (!IsDrawing) return StrokeEvent.Ignored;
                Cancel();
                return StrokeEvent.Cancelled;
            default:
                return StrokeEvent.Ignored;
        }
    }

    /// <summary>Drops the stroke in progress (Escape, right click, a second finger, focus lost).</summary>
    public void Cancel()
    {
        _points.Clear();
        IsDrawing = false;
    }

    private bool Append(Vector2 p)
    {
        if (_points.Count >= MaxPoints) return false;
        var last = _points[^1];
        float d = Vector2.Distance(last, p);
        if (d == 0f || d < MinSpacing) return false;
        _points.Add(p);
        return true;
    }

    /// <summary>The release point always ends the stroke (only the last segment may be shorter than the spacing).</summary>
    private void Finish(Vector2 p)
    {
        if (_points[^1] == p) return;
        if (_points.Count < MaxPoints) _points.Add(p);
        else _points[^1] = p;
    }

    public static float PathLength(IReadOnlyList<Vector2> pts)
    {
        float len = 0f;
        for (int i = 1; i < pts.Count; i++) len += Vector2.Distance(pts[i - 1], pts[i]);
        return len;
    }
}
