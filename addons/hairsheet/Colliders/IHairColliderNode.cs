using Godot;

namespace HairSheet;

/// <summary>A node that gives the hair node one head-space collider (see HairSystem3D.Colliders).</summary>
public interface IHairColliderNode
{
    /// <summary>The collider, given this node's transform relative to the head.</summary>
    HairSim.Collider ToCollider(Transform3D relativeToHead);
}

/// <summary>Shared plumbing: collider nodes tell their hair node when they move or change shape.</summary>
internal static class HairColliderNotify
{
    public static void Changed(Node3D collider)
    {
        collider.UpdateGizmos();
        if (collider.GetParent() is HairSystem3D hair) hair.CollidersChanged();
    }
}
