using System.Numerics;

namespace HairSheet.Logic;

/// <summary>
/// Fit is two strokes (SPEC A.5): first the user encloses the strands to shape (an area), then draws the
/// shape stroke the key curve is matched to. This tracks which of the two the next completed stroke is.
/// </summary>
public sealed class FitGesture
{
    public enum Phase { SelectArea, DrawShape }

    public Phase Current { get; private set; } = Phase.SelectArea;
    /// <summary>The area polygon once selected (implicitly closed).</summary>
    public IReadOnlyList<Vector2> Area { get; private set; } = [];

    /// <summary>Feeds a completed stroke. Returns true when both strokes are in (area, shape) and resets for the next fit.</summary>
    public bool Accept(IReadOnlyList<Vector2> stroke, out IReadOnlyList<Vector2> area, out IReadOnlyList<Vector2> shape)
    {
        ArgumentNullException.ThrowIfNull(stroke);
        if (Current == Phase.SelectArea)
        {
            if (stroke.Count < 3 || PolygonArea(stroke) < 1f)
                throw new ArgumentException("A fit selection must enclose an area: draw a loop around the strands (at least 3 points).", nameof(stroke));
            Area = stroke.ToArray();
            Current = Phase.DrawShape;
            area = shape = [];
            return false;
        }
        if (stroke.Count < 2) throw new ArgumentException("A fit stroke needs at least 2 points.", nameof(stroke));
        area = Area;
        shape = stroke.ToArray();
        Reset();
        return true;
    }

    public void Reset()
    {
        Current = Phase.SelectArea;
        Area = [];
    }

    /// <summary>Unsigned area of the closed polygon (shoelace), in square pixels.</summary>
    public static float PolygonArea(IReadOnlyList<Vector2> p)
    {
        double sum = 0;
        for (int i = 0; i < p.Count; i++)
        {
            var a = p[i]; var b = p[(i + 1) % p.Count];
            sum += (double)a.X * b.Y - (double)b.X * a.Y;
        }
        return (float)Math.Abs(sum * 0.5);
    }
}
