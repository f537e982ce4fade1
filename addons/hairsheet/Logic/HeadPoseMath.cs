using System.Numerics;
using HairSim;

namespace HairSheet.Logic;

/// <summary>
/// Godot transforms (basis columns + origin, possibly scaled) → HairSim's rigid head pose and head-space
/// colliders. A scaled head node must not scale the hair: scale is stripped from the pose, and a collider
/// node's own scale goes into its radii instead.
/// </summary>
public static class HeadPoseMath
{
    public static RigidTransform ToRigid(Vector3 basisX, Vector3 basisY, Vector3 basisZ, Vector3 origin)
    {
        var q = Rotation(basisX, basisY, basisZ);
        return new RigidTransform(origin, q);
    }

    /// <summary>
    /// A head pose from any invertible transform: scale removed, and a reflection (negative scale, as mirrored bones
    /// have) stripped by keeping X and Y and taking Z = X × Y. <paramref name="mirrored"/> says whether one was
    /// stripped, so the node can say so once. Throws only for a basis no rotation can be taken from (zero scale, NaN).
    /// </summary>
    public static RigidTransform HeadPose(Vector3 basisX, Vector3 basisY, Vector3 basisZ, Vector3 origin, out bool mirrored)
    {
        mirrored = Finite(basisZ) && Vector3.Dot(Vector3.Cross(basisX, basisY), basisZ) < 0f;
        return ToRigid(basisX, basisY, mirrored ? -basisZ : basisZ, origin);
    }

    /// <summary>The rotation of a basis with its scale removed (Gram–Schmidt on X then Y).</summary>
    public static Quaternion Rotation(Vector3 basisX, Vector3 basisY, Vector3 basisZ)
    {
        if (!Finite(basisX) || !Finite(basisY) || !Finite(basisZ)) throw new ArgumentException("Transform basis must be finite.");
        if (basisX.LengthSquared() < 1e-20f || basisY.LengthSquared() < 1e-20f || basisZ.LengthSquared() < 1e-20f)
            throw new ArgumentException("Transform basis has a zero-length axis (zero scale): no rotation can be taken from it.");
        var x = Vector3.Normalize(basisX);
        var y = basisY - Vector3.Dot(basisY, x) * x;
        if (y.LengthSquared() < 1e-20f) throw new ArgumentException("Transform basis is degenerate (X and Y parallel).");
        y = Vector3.Normalize(y);
        var z = Vector3.Cross(x, y);
        if (Vector3.Dot(z, basisZ) < 0f) throw new ArgumentException("Transform basis is mirrored (negative scale); a head pose must be a rotation.");
        // System.Numerics rows are the basis axes (row-vector convention).
        var m = new Matrix4x4(x.X, x.Y, x.Z, 0, y.X, y.Y, y.Z, 0, z.X, z.Y, z.Z, 0, 0, 0, 0, 1);
        return Quaternion.Normalize(Quaternion.CreateFromRotationMatrix(m));
    }

    /// <summary>Ellipsoid from a collider node's transform relative to the head: radii scaled by the node's axis lengths.</summary>
    public static Collider Ellipsoid(Vector3 basisX, Vector3 basisY, Vector3 basisZ, Vector3 origin, Vector3 radii) =>
        Collider.Ellipsoid(origin, radii * new Vector3(basisX.Length(), basisY.Length(), basisZ.Length()), Rotation(basisX, basisY, basisZ));

    /// <summary>Sphere: the largest axis scale wins, so the sphere never shrinks inside a non-uniformly scaled node.</summary>
    public static Collider Sphere(Vector3 basisX, Vector3 basisY, Vector3 basisZ, Vector3 origin, float radius) =>
        Collider.Sphere(origin, radius * MaxScale(basisX, basisY, basisZ));

    /// <summary>Capsule along the node's local Y: ends at ±halfHeight, radius scaled by the largest axis scale.</summary>
    public static Collider Capsule(Vector3 basisX, Vector3 basisY, Vector3 basisZ, Vector3 origin, float radius, float halfHeight)
    {
        if (!float.IsFinite(halfHeight) || halfHeight < 0f) throw new ArgumentOutOfRangeException(nameof(halfHeight), halfHeight, "Capsule half height must be ≥ 0.");
        var axis = basisY * halfHeight;
        return Collider.Capsule(origin - axis, origin + axis, radius * MaxScale(basisX, basisY, basisZ));
    }

    private static float MaxScale(Vector3 x, Vector3 y, Vector3 z) => MathF.Max(x.Length(), MathF.Max(y.Length(), z.Length()));

    private static bool Finite(Vector3 v) => float.IsFinite(v.X) && float.IsFinite(v.Y) && float.IsFinite(v.Z);
}
