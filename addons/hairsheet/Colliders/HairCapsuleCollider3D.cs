using Godot;
using HairSheet.Logic;

namespace HairSheet;

/// <summary>A capsule along the node's local Y (neck, shoulders). Child of a HairSystem3D.</summary>
[Tool]
[GlobalClass]
public partial class HairCapsuleCollider3D : Node3D, IHairColliderNode
{
    private float _radius = 0.06f;
    private float _height = 0.2f;

    [Export(PropertyHint.Range, "0.001,10,0.001,suffix:m")]
    public float Radius
    {
        get => _radius;
        set { _radius = value; HairColliderNotify.Changed(this); }
    }

    /// <summary>Distance between the two end-cap centres.</summary>
    [Export(PropertyHint.Range, "0,10,0.001,suffix:m")]
    public float Height
    {
        get => _height;
        set { _height = value; HairColliderNotify.Changed(this); }
    }

    public override void _Ready() => SetNotifyLocalTransform(true);

    public override void _Notification(int what)
    {
        if (what == NotificationLocalTransformChanged) HairColliderNotify.Changed(this);
    }

    public HairSim.Collider ToCollider(Transform3D t) => HeadPoseMath.Capsule(
        t.Basis.Column0.ToNumerics(), t.Basis.Column1.ToNumerics(), t.Basis.Column2.ToNumerics(), t.Origin.ToNumerics(), _radius, _height * 0.5f);
}
