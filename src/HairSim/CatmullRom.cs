using System.Numerics;

namespace HairSim;

/// <summary>
/// Centripetal Catmull-Rom (knot spacing |ΔP|^½, Barry–Goldman evaluation). Chosen over uniform because
/// strands across a sheet are unevenly spaced (jittered roots, motion bunches them): the centripetal form
/// never forms cusps or self-intersections inside a segment (Yuksel, Schaefer, Keyser 2011), and it still
/// passes through every control point. Coincident control points fall back to unit spacing, never NaN.
/// </summary>
public static class CatmullRom
{
    /// <summary>
    /// Point at t ∈ [0, 1] on the segment p1 → p2, with p0 and p3 the neighbours. Computed in double and rounded to
    /// float once at the end: this is the reference render interpolation (the oracle of the fast one), free of the
    /// cancellation float Barry–Goldman suffers when neighbours nearly coincide (its weights grow like d12/d01).
    /// </summary>
    public static Vector3 Evaluate(Vector3 p0, Vector3 p1, Vector3 p2, Vector3 p3, float t)
    {
        double d01 = Math.Sqrt(Distance(p0, p1)), d12 = Math.Sqrt(Distance(p1, p2)), d23 = Math.Sqrt(Distance(p2, p3));
        const double eps = 1e-6;
        if (d12 < eps) d12 = 1;
        if (d01 < eps) d01 = d12;
        if (d23 < eps) d23 = d12;
        double t1 = d01, t2 = t1 + d12, t3 = t2 + d23, u = t1 + t * d12;
        return new Vector3(
            (float)Axis(p0.X, p1.X, p2.X, p3.X, t1, t2, t3, u),
            (float)Axis(p0.Y, p1.Y, p2.Y, p3.Y, t1, t2, t3, u),
            (float)Axis(p0.Z, p1.Z, p2.Z, p3.Z, t1, t2, t3, u));
    }

    private static double Distance(Vector3 a, Vector3 b)
    {
        double x = (double)a.X - b.X, y = (double)a.Y - b.Y, z = (double)a.Z - b.Z;
        return Math.Sqrt(x * x + y * y + z * z);
    }

    /// <summary>Barry–Goldman on one coordinate, knots 0, t1, t2, t3.</summary>
    private static double Axis(double p0, double p1, double p2, double p3, double t1, double t2, double t3, double u)
    {
        double a1 = ((t1 - u) * p0 + u * p1) / t1;
        double a2 = ((t2 - u) * p1 + (u - t1) * p2) / (t2 - t1);
        double a3 = ((t3 - u) * p2 + (u - t2) * p3) / (t3 - t2);
        double b1 = ((t2 - u) * a1 + u * a2) / t2;
        double b2 = ((t3 - u) * a2 + (u - t1) * a3) / (t3 - t1);
        return ((t2 - u) * b1 + (u - t1) * b2) / (t2 - t1);
    }

    /// <summary>End condition: a phantom neighbour mirrored through the end point.</summary>
    public static Vector3 Mirror(Vector3 end, Vector3 inner) => 2f * end - inner;
}
