using Godot;
using HairSheet.Logic;

namespace HairSheet;

/// <summary>An ellipsoid the hair slides over (SPEC A.4): the source's head model. Child of a HairSystem3D.</summary>
[Tool]
[GlobalClass]
public partial class HairEllipsoidCollider3D : Node3D, IHairFollowingCollider
{
    private readonly ColliderFollower _follower;

    public HairEllipsoidCollider3D() => _follower = new ColliderFollower(this);

    private Vector3 _radii = new(0.078f, 0.1f, 0.095f);

    /// <summary>Semi-axes in metres (x: ear to ear, y: up, z: forward); the node's scale multiplies them.</summary>
    [Export]
    public Vector3 Radii
    {
        get => _radii;
        set { _radii = value; HairColliderNotify.Changed(this); }
    }

    /// <summary>
    /// The node or bone this collider rides on in world space (a BoneAttachment3D, a body, a prop; or a Skeleton3D with
    /// <see cref="FollowBone"/>), for shoulders and a neck on a skinned body. Empty = on the head, as before.
    /// </summary>
    [ExportGroup("Follow")]
    [Export]
    public Node3D? Follow
    {
        get => _follower.Follow;
        set { _follower.Follow = value; _follower.TakeOffsetInEditor(); HairColliderNotify.Changed(this); }
    }

    /// <summary>With <see cref="Follow"/> = a Skeleton3D: the bone followed (Skeleton3D.get_bone_global_pose). Empty = the skeleton node.</summary>
    [Export]
    public string FollowBone
    {
        get => _follower.Bone;
        set { _follower.Bone = value ?? ""; _follower.TakeOffsetInEditor(); HairColliderNotify.Changed(this); }
    }

    /// <summary>Where this node sits on the followed frame: taken in the editor whenever the node is moved or Follow changes.</summary>
    [Export]
    public Transform3D FollowOffset
    {
        get => _follower.Offset;
        set { _follower.Offset = value; HairColliderNotify.Changed(this); }
    }

    public override void _Ready() => SetNotifyLocalTransform(true);

    public override void _Notification(int what)
    {
        if (what != NotificationLocalTransformChanged) return;
        _follower.TakeOffsetInEditor();
        HairColliderNotify.Changed(this);
    }

    public bool Follows => _follower.Follow != null;

    public bool TryPlace(out HairSim.Collider collider) => _follower.TryPlace(new PrimitiveShape(HairSim.ColliderKind.Ellipsoid, _radii.ToNumerics()), out collider);

    public override string[] _GetConfigurationWarnings()
    {
        var w = new List<string>();
        if (GetParent() is not HairSystem3D) w.Add("Make this node a child of a HairSystem3D.");
        _follower.AddWarnings(w);
        return w.ToArray();
    }

    public HairSim.Collider ToCollider(Transform3D t) => HeadPoseMath.Ellipsoid(
        t.Basis.Column0.ToNumerics(), t.Basis.Column1.ToNumerics(), t.Basis.Column2.ToNumerics(), t.Origin.ToNumerics(), _radii.ToNumerics());
}
