using Godot;
using HairSheet.Logic;

namespace HairSheet;

/// <summary>An ellipsoid the hair slides over (SPEC A.4): the source's head model. Child of a HairSystem3D.</summary>
[Tool]
[GlobalClass]
public partial class HairEllipsoidCollider3D : Node3D, IHairColliderNode
{
    private Vector3 _radii = new(0.078f, 0.1f, 0.095f);

    /// <summary>Semi-axes in metres (x: ear to ear, y: up, z: forward); the node's scale multiplies them.</summary>
    [Export]
    public Vector3 Radii
    {
        get => _radii;
        set { _radii = value; HairColliderNotify.Changed(this); }
    }

    public override void _Ready() => SetNotifyLocalTransform(true);

    public override void _Notification(int what)
    {
        if (what == NotificationLocalTransformChanged) HairColliderNotify.Changed(this);
    }

    public HairSim.Collider ToCollider(Transform3D t) => HeadPoseMath.Ellipsoid(
        t.Basis.Column0.ToNumerics(), t.Basis.Column1.ToNumerics(), t.Basis.Column2.ToNumerics(), t.Origin.ToNumerics(), _radii.ToNumerics());
}
