using System.Numerics;

namespace HairSim;

/// <summary>
/// The rest shape of a strand, stored per triple (p[k-1], p[k], p[k+1]) centred at particle k.
/// In the triple's own frame — e1 along p[k+1] − p[k-1], e2 towards the middle particle's offset
/// across that axis — the offsets from the triple's centroid are
///   prev = ShapePrev·e1 − ½·ShapeBend·e2,  mid = ShapeMid·e1 + ShapeBend·e2,  next = ShapeNext·e1 − ½·ShapeBend·e2.
/// (The e2 parts must sum to zero about the centroid, and prev/next differ only along e1.)
/// A straight strand with equal edges l0 stores (−l0, 0, +l0, 0): exactly the goals of the source (SPEC A.3).
/// The bend direction e2 is not stored: it is taken from the head-space rest pose (RestX/Y/Z), turned with the
/// head and made perpendicular to the current axis (ShapeMatchSystem.BendDirection), so twist is held too.
/// </summary>
public static class RestShape
{
    /// <summary>Computes the rest shape of every triple of a strand from its rest pose.</summary>
    public static void SetFromRestPose(HairWorld w, int strand)
    {
        int first = w.StrandFirst[strand], n = w.StrandParticleCount[strand], cap = w.StrandCapacity[strand];
        for (int k = 0; k < cap; k++)
        {
            int i = first + k;
            if (k == 0 || k >= n - 1) { w.ShapePrev[i] = w.ShapeMid[i] = w.ShapeNext[i] = w.ShapeBend[i] = 0f; continue; }
            var a = w.GetRest(i - 1); var b = w.GetRest(i); var c = w.GetRest(i + 1);
            Compute(a, b, c, out w.ShapePrev[i], out w.ShapeMid[i], out w.ShapeNext[i], out w.ShapeBend[i]);
        }
    }

    /// <summary>A straight rest shape from the rest lengths alone (the source's model, bit-exact).</summary>
    public static void SetStraight(HairWorld w, int strand)
    {
        int first = w.StrandFirst[strand], n = w.StrandParticleCount[strand], cap = w.StrandCapacity[strand];
        for (int k = 0; k < cap; k++)
        {
            int i = first + k;
            if (k == 0 || k >= n - 1) { w.ShapePrev[i] = w.ShapeMid[i] = w.ShapeNext[i] = w.ShapeBend[i] = 0f; continue; }
            Straight(w.RestLength[i], w.RestLength[i + 1], out w.ShapePrev[i], out w.ShapeMid[i], out w.ShapeNext[i]);
            w.ShapeBend[i] = 0f;
        }
    }

    /// <summary>Straight triple with edges la (prev→mid) and lb (mid→next): offsets from the centroid along the axis.</summary>
    public static void Straight(float la, float lb, out float prev, out float mid, out float next)
    {
        float m = (lb - la) / 3f; // centroid's distance past the middle particle
        prev = -la - m; mid = -m; next = lb - m;
    }

    /// <summary>Rest shape of one triple in its own frame.</summary>
    public static void Compute(Vector3 a, Vector3 b, Vector3 c, out float prev, out float mid, out float next, out float bend)
    {
        var centroid = (a + b + c) / 3f;
        var axis = c - a;
        float len = axis.Length();
        var e1 = len > 1e-12f ? axis / len : Vector3.Normalize(b - a);
        var u = b - centroid;
        mid = Vector3.Dot(u, e1);
        bend = (u - mid * e1).Length();
        prev = Vector3.Dot(a - centroid, e1);
        next = Vector3.Dot(c - centroid, e1);
    }

    /// <summary>A unit vector perpendicular to the unit vector e (deterministic, continuous away from the switch).</summary>
    public static Vector3 AnyPerpendicular(Vector3 e)
    {
        var t = MathF.Abs(e.X) < 0.9f ? Vector3.UnitX : Vector3.UnitY;
        return Vector3.Normalize(Vector3.Cross(e, t));
    }
}
