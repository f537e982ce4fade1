using System.Numerics;

namespace HairSim.Editing;

/// <summary>
/// A uniform grid over the screen rectangle a stroke covers; each cell lists the stroke segments that pass
/// through it (compressed rows: no object per cell). A strand segment only needs to be tested against the
/// stroke segments of the few cells its bounding box touches, so a cut costs one projection per particle.
/// </summary>
internal sealed class StrokeGrid
{
    private const int MaxCellsPerAxis = 128;
    private readonly Vector2[] _p;
    private readonly int[] _cellStart, _items;
    private readonly int _nx, _ny;
    private readonly float _cell;

    public StrokeGrid(ReadOnlySpan<Vector2> points)
    {
        _p = points.ToArray();
        var lo = _p[0]; var hi = _p[0];
        foreach (var q in _p) { lo = Vector2.Min(lo, q); hi = Vector2.Max(hi, q); }
        // Cells about as large as a stroke segment, at most 128 along an axis.
        float size = MathF.Max(hi.X - lo.X, hi.Y - lo.Y);
        _cell = MathF.Max(MathF.Max(size / MaxCellsPerAxis, 1f), size / MathF.Max(1, _p.Length - 1) * 0.5f);
        _nx = Math.Min(MaxCellsPerAxis, (int)((hi.X - lo.X) / _cell) + 1);
        _ny = Math.Min(MaxCellsPerAxis, (int)((hi.Y - lo.Y) / _cell) + 1);
        Min = lo; Max = hi;

        var counts = new int[_nx * _ny + 1];
        ForEachCell((cell, _) => counts[cell]++);
        _cellStart = new int[_nx * _ny + 1];
        for (int c = 0; c < _nx * _ny; c++) _cellStart[c + 1] = _cellStart[c] + counts[c];
        _items = new int[_cellStart[^1]];
        var fill = (int[])_cellStart.Clone();
        ForEachCell((cell, seg) => _items[fill[cell]++] = seg);
    }

    public Vector2 Min { get; }
    public Vector2 Max { get; }
    public ReadOnlySpan<Vector2> Points => _p;

    /// <summary>Registers every stroke segment in the cells its short sub-pieces touch (conservative).</summary>
    private void ForEachCell(Action<int, int> visit)
    {
        var seen = new HashSet<int>();
        for (int s = 0; s + 1 < _p.Length; s++)
        {
            seen.Clear();
            var a = _p[s]; var b = _p[s + 1];
            int pieces = Math.Max(1, (int)MathF.Ceiling(Vector2.Distance(a, b) / (_cell * 0.5f)));
            for (int k = 0; k < pieces; k++)
            {
                var u = Vector2.Lerp(a, b, k / (float)pieces); var v = Vector2.Lerp(a, b, (k + 1) / (float)pieces);
                CellRange(Vector2.Min(u, v), Vector2.Max(u, v), out int x0, out int y0, out int x1, out int y1);
                for (int y = y0; y <= y1; y++)
                    for (int x = x0; x <= x1; x++)
                        if (seen.Add(y * _nx + x)) visit(y * _nx + x, s);
            }
        }
    }

    public void CellRange(Vector2 lo, Vector2 hi, out int x0, out int y0, out int x1, out int y1)
    {
        x0 = Math.Clamp((int)((lo.X - Min.X) / _cell), 0, _nx - 1);
        y0 = Math.Clamp((int)((lo.Y - Min.Y) / _cell), 0, _ny - 1);
        x1 = Math.Clamp((int)((hi.X - Min.X) / _cell), 0, _nx - 1);
        y1 = Math.Clamp((int)((hi.Y - Min.Y) / _cell), 0, _ny - 1);
    }

    public int Columns => _nx;
    public ReadOnlySpan<int> Cell(int x, int y) => _items.AsSpan(_cellStart[y * _nx + x], _cellStart[y * _nx + x + 1] - _cellStart[y * _nx + x]);

    /// <summary>
    /// First crossing (smallest t along a → b) of the screen segment a → b with the stroke, or false.
    /// A stroke segment listed in several cells is simply tested again (cheap and harmless).
    /// </summary>
    public bool FirstCrossing(Vector2 a, Vector2 b, out float t)
    {
        t = float.MaxValue;
        var lo = Vector2.Min(a, b); var hi = Vector2.Max(a, b);
        if (hi.X < Min.X || hi.Y < Min.Y || lo.X > Max.X || lo.Y > Max.Y) return false;
        CellRange(lo, hi, out int x0, out int y0, out int x1, out int y1);
        bool found = false;
        var r = b - a;
        for (int y = y0; y <= y1; y++)
            for (int x = x0; x <= x1; x++)
                foreach (int s in Cell(x, y))
                    if (SegmentCrossing(a, r, _p[s], _p[s + 1] - _p[s], out float ts) && ts < t) { t = ts; found = true; }
        return found;
    }

    /// <summary>Crossing of a + t·r (t ∈ [0, 1]) with c + u·s (u ∈ [0, 1]); parallel segments never cross.</summary>
    public static bool SegmentCrossing(Vector2 a, Vector2 r, Vector2 c, Vector2 s, out float t)
    {
        float denom = r.X * s.Y - r.Y * s.X;
        t = 0f;
        if (MathF.Abs(denom) < 1e-12f * (r.LengthSquared() + s.LengthSquared())) return false;
        var q = c - a;
        t = (q.X * s.Y - q.Y * s.X) / denom;
        float u = (q.X * r.Y - q.Y * r.X) / denom;
        return t >= 0f && t <= 1f && u >= 0f && u <= 1f;
    }
}
