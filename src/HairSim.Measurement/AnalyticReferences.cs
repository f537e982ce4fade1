using System.Numerics;

namespace HairSim.Measurement;

/// <summary>Closed-form answers the canonical cases are measured against.</summary>
public static class AnalyticReferences
{
    /// <summary>
    /// Catenary parameter a of a chain of length L hanging between two pins a horizontal distance D apart:
    /// the root of 2a·sinh(D / 2a) = L (the curve is y = a·cosh(x/a) + c).
    /// </summary>
    public static double CatenaryParameter(double length, double span)
    {
        if (!(span > 0) || !(length > span)) throw new ArgumentOutOfRangeException(nameof(length), "A hanging chain needs length > span > 0.");
        // 2a·sinh(D/2a) falls monotonically from ∞ (a → 0) to D (a → ∞): bisect on log a.
        double lo = span * 1e-4, hi = span * 1e4;
        for (int it = 0; it < 200; it++)
        {
            double mid = Math.Sqrt(lo * hi);
            double arc = 2 * mid * Math.Sinh(span / (2 * mid));
            if (double.IsInfinity(arc) || arc > length) lo = mid; else hi = mid;
        }
        return Math.Sqrt(lo * hi);
    }

    /// <summary>Height of the continuous catenary at x, with both pins at height 0 and x = 0 midway between them.</summary>
    public static double CatenaryHeight(double a, double span, double x) => a * (Math.Cosh(x / a) - Math.Cosh(span / (2 * a)));

    /// <summary>
    /// Equilibrium of a chain of <paramref name="links"/> equal rigid links (total length L) with equal weights at
    /// the joints, pinned at (−D/2, 0) and (+D/2, 0), in the x–y plane with gravity along −y. Horizontal tension H is
    /// constant and each joint's weight w changes the vertical tension by w, so link j has slope
    /// (j − (N−1)/2)·w/H; w/H is chosen so the links span D. As N grows the joints approach y = a·cosh(x/a).
    /// This discrete chain is exactly what a strand of N+1 particles models, so it is the reference.
    /// </summary>
    public static Vector3[] DiscreteCatenary(int links, double length, double span)
    {
        if (links < 2) throw new ArgumentOutOfRangeException(nameof(links), links, "A hanging chain needs at least two links.");
        if (!(span > 0) || !(length > span)) throw new ArgumentOutOfRangeException(nameof(length), "A hanging chain needs length > span > 0.");
        double l = length / links;
        double Extent(double c)
        {
            double sum = 0;
            for (int j = 0; j < links; j++) { double s = (j - (links - 1) / 2.0) * c; sum += l / Math.Sqrt(1 + s * s); }
            return sum;
        }
        double lo = 0, hi = 1;
        while (Extent(hi) > span) hi *= 2;
        for (int it = 0; it < 200; it++) { double mid = 0.5 * (lo + hi); if (Extent(mid) > span) lo = mid; else hi = mid; }
        double ratio = 0.5 * (lo + hi);
        var pts = new Vector3[links + 1];
        double x = -span / 2, y = 0;
        pts[0] = new Vector3((float)x, 0f, 0f);
        for (int j = 0; j < links; j++)
        {
            double s = (j - (links - 1) / 2.0) * ratio, norm = Math.Sqrt(1 + s * s);
            x += l / norm; y += l * s / norm;
            pts[j + 1] = new Vector3((float)x, (float)y, 0f);
        }
        pts[links] = new Vector3((float)(span / 2), 0f, 0f); // exact by construction; removes round-off at the far pin
        return pts;
    }

    /// <summary>
    /// Period of a point-mass pendulum of length L (pivot to mass) released from rest at amplitude θ0, with
    /// linear velocity damping d (dv/dt = −d·v): ω0 = √(g/L) / (1 + θ0²/16) (first finite-amplitude term),
    /// ω = √(ω0² − d²/4), T = 2π/ω.
    /// </summary>
    public static double PendulumPeriod(double length, double gravity, double amplitude, double damping)
    {
        double w0 = Math.Sqrt(gravity / length) / (1 + amplitude * amplitude / 16);
        double w2 = w0 * w0 - damping * damping / 4;
        if (w2 <= 0) throw new ArgumentOutOfRangeException(nameof(damping), damping, "The pendulum is over-damped: it has no period.");
        return 2 * Math.PI / Math.Sqrt(w2);
    }

    /// <summary>Energy left after time t by a linearly damped oscillator, compared at the same phase: e^(−d·t).</summary>
    public static double PendulumEnergyRatio(double damping, double time) => Math.Exp(-damping * time);
}
