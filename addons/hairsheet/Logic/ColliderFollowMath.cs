using System.Numerics;
using HairSim;

namespace HairSheet.Logic;

/// <summary>
/// A mesh collider that rides on a node or a bone instead of the head: the frames involved, engine-free. Godot's
/// transforms come in as System.Numerics matrices (row vectors, <c>GodotConvert.ToNumericsMatrix</c>), so Godot's
/// <c>a * b</c> (b first) is <c>b * a</c> here. The simulation's world is Godot's global space (the head pose is the head
/// node's global transform), so a followed frame is the collider's world placement as it is.
/// <para>
/// A frame is rigid: scale is stripped (a character imported at 0.01 with a skeleton scaled 100× is common) and a
/// reflection (mirrored bones) too, the same way at bake time and every frame, so the baked field keeps its place on
/// the bone. The mesh's own scale goes into the baked vertices instead. A bone whose scale animates moves the field
/// but does not resize it.
/// </para>
/// </summary>
public static class ColliderFollowMath
{
    /// <summary>
    /// The rigid frame of a global transform: scale removed, a reflection stripped (<paramref name="mirrored"/>). False,
    /// with <paramref name="frame"/> left at identity, for a transform no rotation can be taken from (zero scale, NaN):
    /// the caller keeps its last frame. Allocates nothing (called every physics frame).
    /// </summary>
    public static bool TryFrame(in Matrix4x4 global, out RigidTransform frame, out bool mirrored)
    {
        frame = RigidTransform.Identity;
        mirrored = false;
        var x = new Vector3(global.M11, global.M12, global.M13);
        var y = new Vector3(global.M21, global.M22, global.M23);
        var z = new Vector3(global.M31, global.M32, global.M33);
        var t = new Vector3(global.M41, global.M42, global.M43);
        if (!Finite(x) || !Finite(y) || !Finite(z) || !Finite(t)) return false;
        float lx = x.LengthSquared(), ly = y.LengthSquared(), lz = z.LengthSquared();
        if (lx < 1e-20f || ly < 1e-20f || lz < 1e-20f) return false;
        // X and Y must span a plane (HeadPoseMath takes the rotation from them by Gram–Schmidt).
        float c = Vector3.Cross(x, y).LengthSquared();
        if (c < 1e-12f * lx * ly || c < 1e-20f * lx) return false;
        frame = HeadPoseMath.HeadPose(x, y, z, t, out mirrored);
        return true;
    }

    /// <summary>A bone's global transform: the skeleton's global transform × the bone's pose relative to the skeleton (Skeleton3D.GetBoneGlobalPose).</summary>
    public static Matrix4x4 BoneGlobal(in Matrix4x4 skeletonGlobal, in Matrix4x4 bonePose) => bonePose * skeletonGlobal;

    /// <summary>
    /// What the bake reads the source mesh through: its vertices to global space (scale included), then into the
    /// frame. Placing the baked field at the same frame gives back the mesh where it was at bake time.
    /// </summary>
    public static Matrix4x4 MeshToFrame(in Matrix4x4 sourceGlobal, in RigidTransform frame) => sourceGlobal * Inverse(frame);

    /// <summary>The inverse of a rigid frame as a matrix (exact: the rotation's conjugate, no general inversion).</summary>
    public static Matrix4x4 Inverse(in RigidTransform frame) =>
        Matrix4x4.CreateTranslation(-frame.Position) * Matrix4x4.CreateFromQuaternion(Quaternion.Conjugate(frame.Rotation));

    /// <summary>
    /// The name of the frame a field is baked in, stored with the field: "head", a followed node's name, or
    /// "node:bone". A field whose name differs from the collider's present frame would sit in the wrong place: it is
    /// refused until baked again.
    /// </summary>
    public static string FrameName(string? followNode, string? bone)
    {
        if (string.IsNullOrEmpty(followNode)) return "head";
        return string.IsNullOrEmpty(bone) ? followNode : followNode + ":" + bone;
    }

    /// <summary>
    /// Where a primitive collider node sits relative to the frame it follows: its global transform in that frame (its
    /// scale kept: it sizes the collider as a head collider's does). Taken in the editor, stored with the node.
    /// </summary>
    public static Matrix4x4 OffsetIn(in Matrix4x4 colliderGlobal, in RigidTransform frame) => colliderGlobal * Inverse(frame);

    /// <summary>
    /// A primitive collider that follows <paramref name="frame"/> (a bone's or node's rigid frame, <see cref="TryFrame"/>):
    /// its offset carried by the frame, as a world-space collider (<see cref="Collider.InWorldSpace"/>), sized by the
    /// offset's scale as <see cref="HeadPoseMath"/> sizes head colliders. Throws ArgumentException for a degenerate
    /// offset or size (checked when the hair node gathers its colliders; the frame itself is rigid). Allocates nothing.
    /// </summary>
    public static Collider Place(in PrimitiveShape shape, in Matrix4x4 offset, in RigidTransform frame)
    {
        var m = offset * frame.ToMatrix();
        var x = new Vector3(m.M11, m.M12, m.M13);
        var y = new Vector3(m.M21, m.M22, m.M23);
        var z = new Vector3(m.M31, m.M32, m.M33);
        var t = new Vector3(m.M41, m.M42, m.M43);
        var placed = shape.Kind switch
        {
            ColliderKind.Sphere => HeadPoseMath.Sphere(x, y, z, t, shape.Size.X),
            ColliderKind.Capsule => HeadPoseMath.Capsule(x, y, z, t, shape.Size.X, shape.Size.Y),
            ColliderKind.Ellipsoid => HeadPoseMath.Ellipsoid(x, y, z, t, shape.Size),
            _ => throw new ArgumentException($"A {shape.Kind} collider cannot follow a bone.", nameof(shape)),
        };
        return placed.InWorldSpace();
    }

    private static bool Finite(Vector3 v) => float.IsFinite(v.X) && float.IsFinite(v.Y) && float.IsFinite(v.Z);
}

/// <summary>A collider node's shape: a sphere (Size.X = radius), a capsule along local Y (X = radius, Y = half height) or an ellipsoid (Size = radii).</summary>
public readonly record struct PrimitiveShape(ColliderKind Kind, Vector3 Size);
