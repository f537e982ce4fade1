using System.Numerics;

namespace HairSim.Editing;

/// <summary>
/// A curve sampled at equal arc-length spacing, with rotation-minimising frames (T, N, B) at every sample
/// (double reflection, Wang et al. 2008), so offsets stored in the frame turn with the curve but never twist
/// about it. The key curve of a selection is the mean of its strands sampled at the same arc length from the
/// root (a strand shorter than that is extended straight along its last segment, so the mean stays continuous).
/// </summary>
public sealed class KeyCurve
{
    public const int MaxSamples = 1024;

    private readonly Vector3[] _p, _t, _n, _b;

    private KeyCurve(Vector3[] points, float spacing, Vector3? initialNormal)
    {
        _p = points;
        Spacing = spacing;
        int m = points.Length;
        _t = new Vector3[m]; _n = new Vector3[m]; _b = new Vector3[m];
        for (int k = 0; k < m; k++)
        {
            var d = points[Math.Min(k + 1, m - 1)] - points[Math.Max(k - 1, 0)];
            _t[k] = d.LengthSquared() > 1e-24f ? Vector3.Normalize(d) : k > 0 ? _t[k - 1] : -Vector3.UnitY;
        }
        var r = initialNormal ?? RestShape.AnyPerpendicular(_t[0]);
        _n[0] = Orthonormal(r, _t[0]);
        for (int k = 0; k + 1 < m; k++)
        {
            var v1 = points[k + 1] - points[k];
            float c1 = v1.LengthSquared();
            if (c1 < 1e-24f) { _n[k + 1] = Orthonormal(_n[k], _t[k + 1]); continue; }
            var rl = _n[k] - 2f / c1 * Vector3.Dot(v1, _n[k]) * v1;
            var tl = _t[k] - 2f / c1 * Vector3.Dot(v1, _t[k]) * v1;
            var v2 = _t[k + 1] - tl;
            float c2 = v2.LengthSquared();
            _n[k + 1] = Orthonormal(c2 < 1e-24f ? rl : rl - 2f / c2 * Vector3.Dot(v2, rl) * v2, _t[k + 1]);
        }
        for (int k = 0; k < m; k++) _b[k] = Vector3.Cross(_t[k], _n[k]);
    }

    public ReadOnlySpan<Vector3> Points => _p;
    public ReadOnlySpan<Vector3> Tangents => _t;
    public ReadOnlySpan<Vector3> Normals => _n;
    public float Spacing { get; }
    public float Length => Spacing * (_p.Length - 1);
    public Vector3 Root => _p[0];

    /// <summary>A curve through points already spaced <paramref name="spacing"/> apart.</summary>
    public static KeyCurve FromSamples(Vector3[] points, float spacing, Vector3? initialNormal = null)
    {
        if (points.Length < 2) throw new ArgumentException("A key curve needs at least 2 samples.", nameof(points));
        if (!float.IsFinite(spacing) || spacing <= 0f) throw new ArgumentOutOfRangeException(nameof(spacing), spacing, "Sample spacing must be positive.");
        return new KeyCurve(points, spacing, initialNormal);
    }

    /// <summary>The mean of the strands (live particles, current positions) at equal arc length from the root.</summary>
    public static KeyCurve FromStrands(HairWorld w, ReadOnlySpan<int> strands)
    {
        if (strands.Length == 0) throw new ArgumentException("A key curve needs at least one strand.", nameof(strands));
        float longest = 0f;
        int most = 2;
        foreach (int s in strands)
        {
            longest = MathF.Max(longest, StrandLength(w, s));
            most = Math.Max(most, w.StrandParticleCount[s]);
        }
        if (!(longest > 1e-6f) || !float.IsFinite(longest)) throw new ArgumentException("The selected strands have no length.", nameof(strands));
        int m = Math.Clamp(2 * most - 1, 2, MaxSamples);
        float ds = longest / (m - 1);
        var sum = new Vector3[m];
        foreach (int s in strands)
        {
            var pts = w.GetStrandPositions(s);
            var cum = ArcLengths(pts);
            for (int k = 0; k < m; k++) sum[k] += Sample(pts, cum, k * ds);
        }
        for (int k = 0; k < m; k++) sum[k] /= strands.Length;
        return new KeyCurve(sum, ds, null);
    }

    /// <summary>Resamples a polyline at equal spacing for count samples; past its end it continues straight.</summary>
    public static Vector3[] Resample(ReadOnlySpan<Vector3> polyline, float spacing, int count, float startArc = 0f)
    {
        var pts = polyline.ToArray();
        var cum = ArcLengths(pts);
        var result = new Vector3[count];
        for (int k = 0; k < count; k++) result[k] = Sample(pts, cum, startArc + k * spacing);
        return result;
    }

    /// <summary>Point and frame at arc length s (linear between samples, extended straight past the end).</summary>
    public void Frame(float s, out Vector3 point, out Vector3 t, out Vector3 n, out Vector3 b)
    {
        int m = _p.Length;
        float f = s / Spacing;
        if (f >= m - 1)
        {
            t = _t[m - 1]; n = _n[m - 1]; b = _b[m - 1];
            point = _p[m - 1] + t * ((f - (m - 1)) * Spacing);
            return;
        }
        if (f < 0f) f = 0f;
        int k = (int)f;
        float u = f - k;
        point = Vector3.Lerp(_p[k], _p[k + 1], u);
        t = Vector3.Normalize(Vector3.Lerp(_t[k], _t[k + 1], u) + 1e-30f * _t[k]);
        if (!float.IsFinite(t.X)) t = _t[k];
        n = Orthonormal(Vector3.Lerp(_n[k], _n[k + 1], u), t);
        b = Vector3.Cross(t, n);
    }

    internal static float StrandLength(HairWorld w, int s)
    {
        float len = 0f;
        for (int i = w.StrandFirst[s] + 1, end = w.StrandFirst[s] + w.StrandParticleCount[s]; i < end; i++)
            len += Vector3.Distance(w.GetPosition(i - 1), w.GetPosition(i));
        return len;
    }

    internal static float[] ArcLengths(ReadOnlySpan<Vector3> pts)
    {
        var cum = new float[pts.Length];
        for (int k = 1; k < pts.Length; k++) cum[k] = cum[k - 1] + Vector3.Distance(pts[k - 1], pts[k]);
        return cum;
    }

    internal static Vector3 Sample(Vector3[] pts, float[] cum, float s)
    {
        int n = pts.Length;
        if (s <= 0f) return pts[0];
        if (s >= cum[n - 1])
        {
            // Past the tip: continue along the last non-degenerate segment.
            for (int k = n - 1; k > 0; k--)
            {
                var d = pts[k] - pts[k - 1];
                if (d.LengthSquared() > 1e-24f) return pts[n - 1] + Vector3.Normalize(d) * (s - cum[n - 1]);
            }
            return pts[n - 1];
        }
        int lo = 0, hi = n - 1; // cum[lo] ≤ s < cum[hi]
        while (hi - lo > 1) { int mid = (lo + hi) >> 1; if (cum[mid] <= s) lo = mid; else hi = mid; }
        float seg = cum[hi] - cum[lo];
        return seg > 0f ? Vector3.Lerp(pts[lo], pts[hi], (s - cum[lo]) / seg) : pts[lo];
    }

    private static Vector3 Orthonormal(Vector3 v, Vector3 t)
    {
        var r = v - Vector3.Dot(v, t) * t;
        float l = r.Length();
        return l > 1e-12f && float.IsFinite(l) ? r / l : RestShape.AnyPerpendicular(t);
    }
}
