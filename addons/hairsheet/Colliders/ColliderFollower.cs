using Godot;
using HairSheet.Logic;
using HairSim;

namespace HairSheet;

/// <summary>
/// A sphere, capsule or ellipsoid node that follows a node or a bone instead of the head (see HairSystem3D): a
/// world-space collider the hair node moves before every step with HairScene.SetCollider (no pipeline rebuild), the
/// library carrying it across the substeps. Where it sits on the followed frame is its <see cref="Offset"/>, taken in the
/// editor from where the node is placed; at run time the node itself does not move.
/// </summary>
public interface IHairFollowingCollider : IHairColliderNode
{
    /// <summary>Whether it follows a node or bone (else it is a head collider, <see cref="IHairColliderNode.ToCollider"/>).</summary>
    bool Follows { get; }

    /// <summary>
    /// The collider where its frame is now (world space); false, keeping the last place and reporting why once, if the
    /// frame cannot be read. Allocates nothing (called every physics frame).
    /// </summary>
    bool TryPlace(out Collider collider);
}

/// <summary>The Follow / Follow Bone plumbing shared by the primitive collider nodes.</summary>
internal sealed class ColliderFollower(Node3D owner)
{
    private int _boneIndex = -1;
    private string? _problem;

    public Node3D? Follow;
    public string Bone = "";
    /// <summary>The node's transform relative to the followed frame (its scale sizes the collider).</summary>
    public Transform3D Offset = Transform3D.Identity;

    /// <summary>
    /// In the editor, with the node in the tree: keep the node's present place on its frame as the offset (called when
    /// the node moves or Follow changes). Never at run time, where the frame moves and the node does not.
    /// </summary>
    public void TakeOffsetInEditor()
    {
        if (!Engine.IsEditorHint() || !owner.IsInsideTree() || Follow == null) return;
        _boneIndex = -1;
        if (!TryFollowedTransform(out var t, out _) || !ColliderFollowMath.TryFrame(t.ToNumericsMatrix(), out var frame, out _)) return;
        var m = ColliderFollowMath.OffsetIn(owner.GlobalTransform.ToNumericsMatrix(), frame);
        Offset = new Transform3D(new Vector3(m.M11, m.M12, m.M13), new Vector3(m.M21, m.M22, m.M23), new Vector3(m.M31, m.M32, m.M33),
            new Vector3(m.M41, m.M42, m.M43));
    }

    /// <summary>The collider at the frame's present pose, or false (the reason reported once).</summary>
    public bool TryPlace(in PrimitiveShape shape, out Collider collider)
    {
        collider = default;
        if (!TryFollowedTransform(out var t, out string? why)) { Report(why); return false; }
        if (!ColliderFollowMath.TryFrame(t.ToNumericsMatrix(), out var frame, out bool mirrored)) { Report(FollowDegenerate); return false; }
        try { collider = ColliderFollowMath.Place(shape, Offset.ToNumericsMatrix(), frame); }
        catch (ArgumentException e) { Report($"Follow Offset: {e.Message}"); return false; }
        Report(mirrored ? FollowMirrored : null);
        return true;
    }

    /// <summary>What the node's configuration warnings add.</summary>
    public void AddWarnings(List<string> warnings)
    {
        if (Follow != null && !ResolveBone(out string? why)) warnings.Add(why!);
        if (_problem != null) warnings.Add(_problem);
    }

    private const string FollowFreed = "Follow no longer exists: the collider stays where it was.";
    private const string FollowMirrored = "Follow's transform is mirrored (negative scale): its reflection is ignored.";
    private const string FollowDegenerate = "Follow's transform has no rotation (zero scale): the collider keeps its last place.";
    private const string BoneGone = "Follow Bone is no longer in the skeleton: the collider stays where it was.";

    /// <summary>The index of the bone when following a skeleton's bone (-1 otherwise); false with the reason if it is not there.</summary>
    public bool ResolveBone(out string? why)
    {
        why = null;
        _boneIndex = -1;
        if (Follow is not Skeleton3D skeleton || Bone.Length == 0) return true;
        _boneIndex = skeleton.FindBone(Bone);
        if (_boneIndex >= 0) return true;
        why = $"Follow Bone: {skeleton.Name} has no bone named \"{Bone}\" (bone names are case-sensitive).";
        return false;
    }

    /// <summary>The followed node's or bone's global transform (a bone's: skeleton × bone pose, as Godot composes them).</summary>
    private bool TryFollowedTransform(out Transform3D t, out string? why)
    {
        t = Transform3D.Identity;
        why = null;
        if (Follow == null || !GodotObject.IsInstanceValid(Follow)) { why = FollowFreed; return false; }
        if (Bone.Length > 0 && Follow is Skeleton3D skeleton)
        {
            if (_boneIndex < 0) ResolveBone(out _); // FindBone takes a string: resolved once, not every frame
            if (_boneIndex < 0 || _boneIndex >= skeleton.GetBoneCount()) { why = BoneGone; return false; }
            t = skeleton.GlobalTransform * skeleton.GetBoneGlobalPose(_boneIndex);
            return true;
        }
        t = Follow.GlobalTransform;
        return true;
    }

    private void Report(string? problem)
    {
        if (problem == _problem) return;
        _problem = problem;
        if (problem != null) GD.PushWarning($"{owner.Name}: {problem}");
        if (owner.IsInsideTree()) owner.UpdateConfigurationWarnings();
    }
}
