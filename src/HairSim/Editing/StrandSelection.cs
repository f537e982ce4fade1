using System.Numerics;

namespace HairSim.Editing;

/// <summary>A screen-space area that selects strands: rectangle, lasso (closed polygon) or brush (disc).</summary>
public sealed class SelectionArea
{
    private readonly Vector2[] _polygon;
    private readonly Vector2 _center;
    private readonly float _radius;

    private SelectionArea(Vector2[] polygon, Vector2 center, float radius) { _polygon = polygon; _center = center; _radius = radius; }

    public static SelectionArea Rectangle(Vector2 corner, Vector2 oppositeCorner)
    {
        Finite(corner); Finite(oppositeCorner);
        var lo = Vector2.Min(corner, oppositeCorner); var hi = Vector2.Max(corner, oppositeCorner);
        if (hi.X - lo.X < 1e-3f || hi.Y - lo.Y < 1e-3f) throw new ArgumentException("A selection rectangle needs a non-zero width and height.");
        return new SelectionArea([lo, new(hi.X, lo.Y), hi, new(lo.X, hi.Y)], default, 0f);
    }

    public static SelectionArea Lasso(ReadOnlySpan<Vector2> polygon)
    {
        if (polygon.Length < 3) throw new ArgumentException($"A lasso needs at least 3 points, got {polygon.Length}.", nameof(polygon));
        double area = 0;
        for (int k = 0; k < polygon.Length; k++)
        {
            Finite(polygon[k]);
            var a = polygon[k]; var b = polygon[(k + 1) % polygon.Length];
            area += (double)a.X * b.Y - (double)b.X * a.Y;
        }
        if (Math.Abs(area) < 1e-3) throw new ArgumentException("The lasso encloses no area.", nameof(polygon));
        return new SelectionArea(polygon.ToArray(), default, 0f);
    }

    public static SelectionArea Brush(Vector2 center, float radius)
    {
        Finite(center);
        if (!float.IsFinite(radius) || radius <= 0f) throw new ArgumentOutOfRangeException(nameof(radius), radius, "Brush radius must be positive.");
        return new SelectionArea([], center, radius);
    }

    /// <summary>The most dabs one brush stroke may make (a stroke far longer than its radius is refused, not stalled on).</summary>
    public const int MaxBrushDabs = 100_000;

    /// <summary>
    /// A brush stroke as dabs of <paramref name="radius"/> along its path: its first point, then dabs at most half a
    /// radius apart up to each point at least half a radius past the last dab (between two far-apart points too), so
    /// their union covers the stroke without a gap and without a dab per pixel. Paint or select with all of them at
    /// once. An empty stroke, a non-finite point, a radius that is not positive or more than
    /// <see cref="MaxBrushDabs"/> dabs are refused (ArgumentException).
    /// </summary>
    public static List<SelectionArea> BrushStroke(IReadOnlyList<Vector2> stroke, float radius)
    {
        ArgumentNullException.ThrowIfNull(stroke);
        if (stroke.Count == 0) throw new ArgumentException("A brush stroke needs at least one point.", nameof(stroke));
        var first = Brush(stroke[0], radius);
        var dabs = new List<SelectionArea> { first };
        float step = 0.5f * radius;
        var last = stroke[0];
        for (int i = 1; i < stroke.Count; i++)
        {
            var p = stroke[i];
            Finite(p);
            float distance = Vector2.Distance(last, p);
            if (distance < step) continue;
            int n = (int)MathF.Ceiling(distance / step);
            if (n > MaxBrushDabs - dabs.Count)
                throw new ArgumentException($"The brush stroke is too long for its {radius} px radius (more than {MaxBrushDabs:N0} dabs).", nameof(stroke));
            for (int k = 1; k <= n; k++) dabs.Add(Brush(Vector2.Lerp(last, p, k / (float)n), radius));
            last = p;
        }
        return dabs;
    }

    public bool Contains(Vector2 p)
    {
        if (_polygon.Length == 0) return Vector2.DistanceSquared(p, _center) <= _radius * _radius;
        bool inside = false; // even–odd rule
        for (int i = 0, j = _polygon.Length - 1; i < _polygon.Length; j = i++)
        {
            var a = _polygon[i]; var b = _polygon[j];
            if ((a.Y > p.Y) != (b.Y > p.Y) && p.X < (b.X - a.X) * (p.Y - a.Y) / (b.Y - a.Y) + a.X) inside = !inside;
        }
        return inside;
    }

    private static void Finite(Vector2 p)
    {
        if (!float.IsFinite(p.X) || !float.IsFinite(p.Y)) throw new ArgumentException("Selection points must be finite.");
    }
}

public sealed class SelectionOptions
{
    /// <summary>Select a strand only when its root is in the area (otherwise any live particle counts).</summary>
    public bool RootsOnly { get; set; }
    /// <summary>Ignore strand points hidden behind the head's colliders.</summary>
    public bool VisibleOnly { get; set; }
}

/// <summary>Selected strands of one world, ascending. <see cref="Mask"/> lets a renderer highlight them.</summary>
public sealed class StrandSelection
{
    private readonly int[] _strands;
    private readonly bool[] _mask;

    public StrandSelection(HairWorld world, ReadOnlySpan<int> strands)
    {
        World = world ?? throw new ArgumentNullException(nameof(world));
        _mask = new bool[world.StrandCount];
        foreach (int s in strands)
        {
            if ((uint)s >= (uint)world.StrandCount) throw new ArgumentOutOfRangeException(nameof(strands), s, $"Strand {s} does not exist (the world has {world.StrandCount}).");
            _mask[s] = true;
        }
        var list = new List<int>();
        for (int s = 0; s < _mask.Length; s++) if (_mask[s]) list.Add(s);
        _strands = list.ToArray();
    }

    public HairWorld World { get; }
    public ReadOnlySpan<int> Strands => _strands;
    public int Count => _strands.Length;
    public bool Contains(int strand) => (uint)strand < (uint)_mask.Length && _mask[strand];
    /// <summary>One flag per strand of the world, true when selected (for highlighting).</summary>
    public ReadOnlySpan<bool> Mask => _mask;
}
