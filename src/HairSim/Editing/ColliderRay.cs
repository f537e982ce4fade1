using System.Numerics;
using HairSim.Meshes;

namespace HairSim.Editing;

/// <summary>Ray casts against head colliders: decides whether a strand point is in front of the head.</summary>
public static class ColliderRay
{
    /// <summary>Nearest hit t ≥ 0 of the ray o + t·d (d unit) with a world-space collider.</summary>
    public static bool Intersect(in Collider c, Vector3 o, Vector3 d, out float t)
    {
        switch (c.Kind)
        {
            case ColliderKind.Ellipsoid:
            {
                var inv = Quaternion.Conjugate(c.Rotation);
                var lo = Vector3.Transform(o - c.Center, inv) / c.Radii;
                var ld = Vector3.Transform(d, inv) / c.Radii;
                return UnitSphere(lo, ld, out t);
            }
            case ColliderKind.Sphere:
                return UnitSphere((o - c.Center) / c.Radius, d / c.Radius, out t);
            case ColliderKind.Plane:
            {
                // Inside (below) counts as a hit at 0, as for the other shapes.
                float h = Vector3.Dot(o - c.Center, c.Normal), dn = Vector3.Dot(d, c.Normal);
                t = 0f;
                if (h <= 0f) return true;
                if (!(dn < 0f)) return false;
                t = -h / dn;
                return true;
            }
            default:
                return Capsule(c.Center, c.End, c.Radius, o, d, out t);
        }
    }

    /// <summary>
    /// First hit t in [0, maxT] of the ray o + t·d (d unit, world space) with a mesh collider whose field is at
    /// <paramref name="head"/> (the head pose, or <see cref="MeshCollider.PoseFor(in RigidTransform)"/> of it for a placed collider): sphere
    /// tracing of its distance field in head space, from where the ray enters the field's grid.
    /// </summary>
    public static bool Intersect(MeshCollider mesh, in RigidTransform head, Vector3 o, Vector3 d, float maxT, out float t)
    {
        var f = mesh.Field;
        var lo = head.InverseTransformPoint(o);
        var ld = head.InverseTransformDirection(d);
        var bmin = f.Origin;
        var bmax = f.Origin + new Vector3(f.Nx - 1, f.Ny - 1, f.Nz - 1) * f.CellSize;
        float t0 = 0f, t1 = maxT;
        for (int a = 0; a < 3; a++)
        {
            float oa = a == 0 ? lo.X : a == 1 ? lo.Y : lo.Z, da = a == 0 ? ld.X : a == 1 ? ld.Y : ld.Z;
            float lo_ = a == 0 ? bmin.X : a == 1 ? bmin.Y : bmin.Z, hi = a == 0 ? bmax.X : a == 1 ? bmax.Y : bmax.Z;
            if (MathF.Abs(da) < 1e-12f) { if (oa < lo_ || oa > hi) { t = 0f; return false; } continue; }
            float ta = (lo_ - oa) / da, tb = (hi - oa) / da;
            if (ta > tb) (ta, tb) = (tb, ta);
            t0 = MathF.Max(t0, ta); t1 = MathF.Min(t1, tb);
        }
        t = t0;
        if (t0 > t1) return false;
        float hit = 0.25f * f.CellSize;
        for (int i = 0; i < 1024 && t <= t1; i++)
        {
            float dist = f.Distance(lo + ld * t);
            if (dist < hit) return true;
            t += MathF.Max(dist, 0.5f * f.CellSize);
        }
        return false;
    }

    /// <summary>First t ≥ 0 where |o + t·d| = 1 (or 0 if o is inside).</summary>
    private static bool UnitSphere(Vector3 o, Vector3 d, out float t)
    {
        double a = Vector3.Dot(d, d), b = Vector3.Dot(o, d), c = Vector3.Dot(o, o) - 1.0;
        t = 0f;
        if (c <= 0) return true;
        double disc = b * b - a * c;
        if (disc < 0 || b > 0 || a < 1e-30) return false;
        t = (float)((-b - Math.Sqrt(disc)) / a);
        return true;
    }

    private static bool Capsule(Vector3 pa, Vector3 pb, float r, Vector3 o, Vector3 d, out float t)
    {
        // Cylinder body, then the two end spheres; keep the nearest hit.
        bool hit = false;
        t = float.MaxValue;
        var ba = pb - pa;
        double baba = Vector3.Dot(ba, ba);
        if (baba > 1e-18)
        {
            var oa = o - pa;
            double bard = Vector3.Dot(ba, d), baoa = Vector3.Dot(ba, oa), rdoa = Vector3.Dot(d, oa), oaoa = Vector3.Dot(oa, oa);
            double a = baba - bard * bard, b = baba * rdoa - baoa * bard, c = baba * oaoa - baoa * baoa - (double)r * r * baba;
            double h = b * b - a * c;
            if (a > 1e-18 && h >= 0)
            {
                double tc = (-b - Math.Sqrt(h)) / a;
                double y = baoa + tc * bard;
                if (tc >= 0 && y > 0 && y < baba) { t = (float)tc; hit = true; }
            }
        }
        if (UnitSphere((o - pa) / r, d / r, out float ta) && ta < t) { t = ta; hit = true; }
        if (UnitSphere((o - pb) / r, d / r, out float tb) && tb < t) { t = tb; hit = true; }
        return hit;
    }
}
