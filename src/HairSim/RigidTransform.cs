using System.Numerics;

namespace HairSim;

/// <summary>A rotation followed by a translation: the pose of a head (no scale, so lengths are kept).</summary>
public readonly struct RigidTransform : IEquatable<RigidTransform>
{
    public readonly Vector3 Position;
    public readonly Quaternion Rotation;

    public RigidTransform(Vector3 position, Quaternion rotation)
    {
        if (!float.IsFinite(position.X) || !float.IsFinite(position.Y) || !float.IsFinite(position.Z))
            throw new ArgumentException("Head position must be finite.", nameof(position));
        float len = rotation.Length();
        if (!float.IsFinite(len) || len < 1e-6f)
            throw new ArgumentException("Head rotation must be a finite, non-zero quaternion.", nameof(rotation));
        Position = position;
        Rotation = Quaternion.Normalize(rotation);
    }

    public static RigidTransform Identity => new(Vector3.Zero, Quaternion.Identity);

    public Vector3 TransformPoint(Vector3 local) => Position + Vector3.Transform(local, Rotation);
    public Vector3 TransformDirection(Vector3 local) => Vector3.Transform(local, Rotation);
    public Vector3 InverseTransformPoint(Vector3 world) => Vector3.Transform(world - Position, Quaternion.Conjugate(Rotation));
    public Vector3 InverseTransformDirection(Vector3 world) => Vector3.Transform(world, Quaternion.Conjugate(Rotation));

    /// <summary>Pose on the way from a to b (lerp position, slerp rotation).</summary>
    public static RigidTransform Interpolate(in RigidTransform a, in RigidTransform b, float t) =>
        new(Vector3.Lerp(a.Position, b.Position, t), Quaternion.Slerp(a.Rotation, b.Rotation, t));

    /// <summary>The transform that takes a pose-a-relative point to the same pose-b-relative point: b ∘ a⁻¹.</summary>
    public static RigidTransform Delta(in RigidTransform from, in RigidTransform to)
    {
        var rot = Quaternion.Normalize(to.Rotation * Quaternion.Conjugate(from.Rotation));
        return new RigidTransform(to.Position - Vector3.Transform(from.Position, rot), rot);
    }

    /// <summary>Rotation angle in radians (0 … π).</summary>
    public float Angle
    {
        get
        {
            float w = MathF.Min(1f, MathF.Abs(Rotation.W));
            return 2f * MathF.Acos(w);
        }
    }

    public Matrix4x4 ToMatrix() => Matrix4x4.CreateFromQuaternion(Rotation) * Matrix4x4.CreateTranslation(Position);

    public bool Equals(RigidTransform other) => Position.Equals(other.Position) && Rotation.Equals(other.Rotation);
    public override bool Equals(object? obj) => obj is RigidTransform t && Equals(t);
    public override int GetHashCode() => HashCode.Combine(Position, Rotation);
    public override string ToString() => $"RigidTransform({Position}, {Rotation})";
}
