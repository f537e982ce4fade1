using System.Numerics;

namespace HairSim;

public enum ColliderKind
{
    Ellipsoid,
    Sphere,
    Capsule,
    /// <summary>A plane through <see cref="Collider.Center"/> with unit normal <see cref="Collider.Normal"/>: the half-space below it is solid (a floor, a table top, a wall).</summary>
    Plane,
}

/// <summary>
/// A collider in head space (it moves with the head), or, made with <see cref="InWorldSpace"/>, fixed in the world (a
/// floor, a table, shoulders the caller places each frame). Plain data: the collide system turns it into world space once
/// per substep. Constructors validate; a degenerate shape is refused.
/// </summary>
public readonly struct Collider
{
    public readonly ColliderKind Kind;
    /// <summary>Ellipsoid/sphere centre, or capsule end A.</summary>
    public readonly Vector3 Center;
    /// <summary>Capsule end B; a plane's unit normal (see <see cref="Normal"/>); unused otherwise.</summary>
    public readonly Vector3 End;
    /// <summary>Ellipsoid semi-axes; for sphere and capsule X holds the radius.</summary>
    public readonly Vector3 Radii;
    /// <summary>Ellipsoid orientation relative to the head (to the world when <see cref="InWorld"/>).</summary>
    public readonly Quaternion Rotation;
    /// <summary>True for a collider given in world space: the head's pose does not move it.</summary>
    public readonly bool InWorld;

    private Collider(ColliderKind kind, Vector3 center, Vector3 end, Vector3 radii, Quaternion rotation, bool inWorld = false)
    {
        Kind = kind; Center = center; End = end; Radii = radii; Rotation = rotation; InWorld = inWorld;
    }

    /// <summary>The same shape read as world coordinates: it stays where it is while the head moves.</summary>
    public Collider InWorldSpace() => new(Kind, Center, End, Radii, Rotation, inWorld: true);

    public float Radius => Radii.X;

    /// <summary>A plane's unit normal, pointing out of the solid half-space (zero for the other kinds).</summary>
    public Vector3 Normal => Kind == ColliderKind.Plane ? End : Vector3.Zero;

    public static Collider Ellipsoid(Vector3 center, Vector3 radii) => Ellipsoid(center, radii, Quaternion.Identity);

    public static Collider Ellipsoid(Vector3 center, Vector3 radii, Quaternion rotation)
    {
        FiniteVec(center, nameof(center));
        FiniteVec(radii, nameof(radii));
        if (radii.X <= 1e-6f || radii.Y <= 1e-6f || radii.Z <= 1e-6f)
            throw new ArgumentOutOfRangeException(nameof(radii), radii, "Ellipsoid radii must all be positive (> 1e-6).");
        float len = rotation.Length();
        if (!float.IsFinite(len) || len < 1e-6f) throw new ArgumentException("Ellipsoid rotation must be a finite non-zero quaternion.", nameof(rotation));
        return new Collider(ColliderKind.Ellipsoid, center, center, radii, Quaternion.Normalize(rotation));
    }

    public static Collider Sphere(Vector3 center, float radius)
    {
        FiniteVec(center, nameof(center));
        if (!(radius > 0f && radius <= HairWorld.MaxCoordinate)) throw new ArgumentOutOfRangeException(nameof(radius), radius, $"Sphere radius must be in (0, {HairWorld.MaxCoordinate:G}] m.");
        return new Collider(ColliderKind.Sphere, center, center, new Vector3(radius), Quaternion.Identity);
    }

    /// <summary>A capsule between a and b; a == b is allowed and behaves as a sphere.</summary>
    public static Collider Capsule(Vector3 a, Vector3 b, float radius)
    {
        FiniteVec(a, nameof(a)); FiniteVec(b, nameof(b));
        if (!(radius > 0f && radius <= HairWorld.MaxCoordinate)) throw new ArgumentOutOfRangeException(nameof(radius), radius, $"Capsule radius must be in (0, {HairWorld.MaxCoordinate:G}] m.");
        return new Collider(ColliderKind.Capsule, a, b, new Vector3(radius), Quaternion.Identity);
    }

    /// <summary>
    /// A plane through <paramref name="point"/> whose solid side is below <paramref name="normal"/> (a floor: normal +Y).
    /// The normal is normalised; a zero, tiny (&lt; 1e-6) or non-finite one is refused. On the head by default, like every
    /// collider; <see cref="InWorldSpace"/> fixes it in the world.
    /// </summary>
    public static Collider Plane(Vector3 point, Vector3 normal)
    {
        FiniteVec(point, nameof(point)); FiniteVec(normal, nameof(normal));
        float len = normal.Length();
        if (!(len >= 1e-6f) || !float.IsFinite(len))
            throw new ArgumentException($"A plane's normal must be a non-zero direction (length ≥ 1e-6), got {normal}.", nameof(normal));
        // A normal that is already unit within float rounding is kept bit for bit (a hairstyle file's round trip is exact).
        return new Collider(ColliderKind.Plane, point, MathF.Abs(len - 1f) <= 1e-6f ? normal : normal / len, Vector3.Zero, Quaternion.Identity);
    }

    /// <summary>Finite and within ±<see cref="HairWorld.MaxCoordinate"/> (a point, a size or a normal before it is normalised).</summary>
    private static void FiniteVec(Vector3 v, string name)
    {
        if (!HairWorld.InRange(v))
            throw new ArgumentException($"{name} must be finite and within ±{HairWorld.MaxCoordinate:G}, got {v}.", name);
    }

    /// <summary>This collider placed by a head pose (a world-space collider is already placed).</summary>
    public Collider ToWorld(in RigidTransform head) => InWorld ? this :
        new(Kind, head.TransformPoint(Center), Kind == ColliderKind.Plane ? head.TransformDirection(End) : head.TransformPoint(End), Radii,
            Quaternion.Normalize(head.Rotation * Rotation));

    /// <summary>
    /// If p is inside, the surface point it is pushed to and the outward unit normal there; otherwise false.
    /// The ellipsoid uses the source's radial projection (SPEC A.4: towards the point on the surface in the
    /// direction of p from the centre). A particle exactly at the centre is pushed along the collider's local +Y.
    /// Double precision: this is the reference, and the fast path must agree with it.
    /// </summary>
    public bool Resolve(Vector3 p, out Vector3 surface, out Vector3 normal, out float depth)
    {
        switch (Kind)
        {
            case ColliderKind.Ellipsoid:
            {
                var inv = Quaternion.Conjugate(Rotation);
                var l = Vector3.Transform(p - Center, inv);
                double qx = l.X / (double)Radii.X, qy = l.Y / (double)Radii.Y, qz = l.Z / (double)Radii.Z;
                double r = Math.Sqrt(qx * qx + qy * qy + qz * qz);
                if (r >= 1.0) { surface = p; normal = default; depth = 0; return false; }
                double sx, sy, sz; // local surface point
                if (r < 1e-12) { sx = 0; sy = Radii.Y; sz = 0; }
                else { sx = l.X / r; sy = l.Y / r; sz = l.Z / r; }
                double nx = sx / ((double)Radii.X * Radii.X), ny = sy / ((double)Radii.Y * Radii.Y), nz = sz / ((double)Radii.Z * Radii.Z);
                double nl = Math.Sqrt(nx * nx + ny * ny + nz * nz);
                var sLocal = new Vector3((float)sx, (float)sy, (float)sz);
                surface = Center + Vector3.Transform(sLocal, Rotation);
                normal = Vector3.Transform(new Vector3((float)(nx / nl), (float)(ny / nl), (float)(nz / nl)), Rotation);
                double ddx = sx - l.X, ddy = sy - l.Y, ddz = sz - l.Z;
                depth = (float)Math.Sqrt(ddx * ddx + ddy * ddy + ddz * ddz);
                return true;
            }
            case ColliderKind.Sphere:
                return PushOutOfSphere(p, Center, Radius, Vector3.UnitY, out surface, out normal, out depth);
            case ColliderKind.Plane:
            {
                // Signed height above the plane; below it, straight up to the plane.
                double nx = End.X, ny = End.Y, nz = End.Z;
                double d = (p.X - (double)Center.X) * nx + (p.Y - (double)Center.Y) * ny + (p.Z - (double)Center.Z) * nz;
                if (!(d < 0)) { surface = p; normal = default; depth = 0; return false; }
                surface = new Vector3((float)(p.X - d * nx), (float)(p.Y - d * ny), (float)(p.Z - d * nz));
                normal = End;
                depth = (float)-d;
                return true;
            }
            default:
            {
                var ab = End - Center;
                double len2 = Vector3.Dot(ab, ab);
                double t = len2 < 1e-18 ? 0 : Math.Clamp(Vector3.Dot(p - Center, ab) / len2, 0.0, 1.0);
                var closest = Center + (float)t * ab;
                // On the axis itself, push out sideways (perpendicular to the axis), not along it.
                var fallback = len2 < 1e-18 ? Vector3.UnitY : RestShape.AnyPerpendicular(Vector3.Normalize(ab));
                return PushOutOfSphere(p, closest, Radius, fallback, out surface, out normal, out depth);
            }
        }
    }

    private static bool PushOutOfSphere(Vector3 p, Vector3 c, float radius, Vector3 fallbackNormal, out Vector3 surface, out Vector3 normal, out float depth)
    {
        var d = p - c;
        double dist = Math.Sqrt((double)d.X * d.X + (double)d.Y * d.Y + (double)d.Z * d.Z);
        if (dist >= radius) { surface = p; normal = default; depth = 0; return false; }
        normal = dist < 1e-12 ? fallbackNormal : new Vector3((float)(d.X / dist), (float)(d.Y / dist), (float)(d.Z / dist));
        surface = c + normal * radius;
        depth = (float)(radius - dist);
        return true;
    }

    /// <summary>
    /// Whether this value could have come from a factory: finite, in range, positive sizes, a unit rotation, a unit
    /// plane normal. False for <c>default(Collider)</c> (an ellipsoid with zero radii), which no factory makes.
    /// </summary>
    internal bool IsValid()
    {
        if (!Enum.IsDefined(Kind) || !HairWorld.InRange(Center) || !HairWorld.InRange(End) || !HairWorld.InRange(Radii)) return false;
        if (!(MathF.Abs(Rotation.Length() - 1f) < 1e-3f)) return false;
        return Kind switch
        {
            ColliderKind.Ellipsoid => Radii.X > 1e-6f && Radii.Y > 1e-6f && Radii.Z > 1e-6f,
            ColliderKind.Plane => MathF.Abs(End.Length() - 1f) < 1e-3f,
            _ => Radii.X > 0f,
        };
    }

    /// <summary>
    /// The placement a fraction t of the way from a to b (same kind): ends, centre and sizes lerped, rotation slerped, a
    /// plane's normal lerped and normalised. t ≥ 1 gives b exactly. Used per substep for a collider moved between frames.
    /// </summary>
    internal static Collider Interpolate(in Collider a, in Collider b, float t)
    {
        if (t >= 1f) return b;
        var center = Vector3.Lerp(a.Center, b.Center, t);
        var end = Vector3.Lerp(a.End, b.End, t);
        if (b.Kind == ColliderKind.Plane)
        {
            float len = end.Length();
            if (!(len > 1e-3f)) return b; // opposite normals: no way between them, so the new one
            end /= len;
        }
        var rotation = b.Kind == ColliderKind.Ellipsoid ? Quaternion.Normalize(Quaternion.Slerp(a.Rotation, b.Rotation, t)) : b.Rotation;
        return new Collider(b.Kind, center, end, Vector3.Lerp(a.Radii, b.Radii, t), rotation, b.InWorld);
    }

    /// <summary>How far a point of the collider moved from a to b (the larger of the two ends; a plane: its point), and the angle it turned (radians).</summary>
    internal static void Motion(in Collider a, in Collider b, out float distance, out float angle)
    {
        distance = Vector3.Distance(a.Center, b.Center);
        angle = 0f;
        if (b.Kind == ColliderKind.Plane)
            angle = MathF.Acos(Math.Clamp(Vector3.Dot(a.End, b.End), -1f, 1f));
        else
        {
            if (b.Kind == ColliderKind.Capsule) distance = MathF.Max(distance, Vector3.Distance(a.End, b.End));
            if (b.Kind == ColliderKind.Ellipsoid)
                angle = new RigidTransform(Vector3.Zero, Quaternion.Normalize(b.Rotation * Quaternion.Conjugate(a.Rotation))).Angle;
        }
    }

    /// <summary>How deep p is inside (0 if outside), measured to the point Resolve would move it to.</summary>
    public float Penetration(Vector3 p) => Resolve(p, out _, out _, out float d) ? d : 0f;
}
