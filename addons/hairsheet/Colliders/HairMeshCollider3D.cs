using Godot;
using HairSheet.Logic;
using HairSim;
using HairSim.Meshes;

namespace HairSheet;

/// <summary>
/// The hair collides with a mesh (a character's head or body) through a baked distance field. Child of a
/// HairSystem3D, which collides with every such child (a head and a body, each with its own Follow); point
/// <see cref="Source"/> at the MeshInstance3D and press "Bake distance field" in the inspector.
/// Without <see cref="Follow"/> the field is in head space and moves with the hair's head, as the other colliders do.
/// With it, the field rides on that node (a BoneAttachment3D for a bone, a body, a prop) or on a Skeleton3D's bone
/// (<see cref="FollowBone"/>) in world space: the hair node sets its place before every step. This node's own
/// transform is not used (the field is where the source mesh was at bake time, relative to its frame).
/// </summary>
[Tool]
[GlobalClass]
public partial class HairMeshCollider3D : Node3D
{
    private HairMeshField? _field;
    private float _margin = 0.001f;
    private Node3D? _follow;
    private string _followBone = "";
    // The component last given to the hair node: while following, its placement is set every physics frame.
    private MeshCollider? _component;
    private int _boneIndex = -1;
    private string? _followProblem;

    /// <summary>The mesh to collide with (its surfaces are read at bake time).</summary>
    [Export] public MeshInstance3D? Source { get; set; }

    /// <summary>Grid cell of the bake: about a quarter of the thinnest part the hair must feel (2.5 mm for 1 cm ears).</summary>
    [Export(PropertyHint.Range, "0.0005,0.05,0.0005,suffix:m")] public float CellSize { get; set; } = 0.0025f;

    /// <summary>Hair keeps at least this far from the surface.</summary>
    [Export(PropertyHint.Range, "0,0.01,0.0001,suffix:m")]
    public float Margin
    {
        get => _margin;
        set { _margin = value; NotifyHair(); }
    }

    /// <summary>The baked field (save it as a .res to share it between scenes: a .tres stores it as text).</summary>
    [Export]
    public HairMeshField? Field
    {
        get => _field;
        set { _field = value; NotifyHair(); }
    }

    [ExportToolButton("Bake distance field")]
    public Callable BakeButton => Callable.From(Bake);

    /// <summary>
    /// The node the field rides on, in world space: a BoneAttachment3D for a bone (it copies the pose the skeleton
    /// ends with), a body, a prop; or a Skeleton3D together with <see cref="FollowBone"/>. Empty = the hair's head.
    /// Its scale is ignored (the mesh's scale is baked in). Bake again after changing it.
    /// </summary>
    [ExportGroup("Follow")]
    [Export]
    public Node3D? Follow
    {
        get => _follow;
        set { _follow = value; NotifyHair(); }
    }

    /// <summary>
    /// With <see cref="Follow"/> = a Skeleton3D: the bone whose pose the field follows (Skeleton3D.get_bone_global_pose,
    /// the pose before the skeleton's modifiers run; use a BoneAttachment3D for the final one). Empty = the skeleton node.
    /// </summary>
    [Export]
    public string FollowBone
    {
        get => _followBone;
        set { _followBone = value ?? ""; NotifyHair(); }
    }

    /// <summary>
    /// Reads the source mesh relative to the frame the field will move with (the hair's head, or the followed node or
    /// bone as it is now) and bakes its field. An editor action; undo by baking again.
    /// </summary>
    public void Bake()
    {
        if (Source?.Mesh is not Mesh mesh || GetParent() is not HairSystem3D hair)
        {
            GD.PushError($"{Name}: set Source to a MeshInstance3D with a mesh, and make this node a child of a HairSystem3D.");
            return;
        }
        RigidTransform frame;
        if (_follow == null) frame = hair.HeadFrame();
        else if (!TryFollowedTransform(out var followed, out string? why) || !ColliderFollowMath.TryFrame(followed.ToNumericsMatrix(), out frame, out _))
        {
            GD.PushError($"{Name}: cannot bake relative to Follow: {why ?? "its transform has no rotation (zero scale)."}");
            return;
        }
        try
        {
            var toFrame = ColliderFollowMath.MeshToFrame(Source.GlobalTransform.ToNumericsMatrix(), frame);
            var field = SignedDistanceField.Bake(MeshSurfaces.ToHeadSpace(mesh.ReadSurfaces(), toFrame), CellSize);
            Field = HairMeshField.From(field, FrameName());
            GD.Print($"{Name}: distance field {field.Nx}×{field.Ny}×{field.Nz} baked in {field.BakeTime.TotalMilliseconds:F0} ms, relative to the {Field.Frame}.");
        }
        catch (ArgumentException e)
        {
            GD.PushError($"{Name}: {e.Message}");
        }
    }

    /// <summary>
    /// The collider component for the hair's scene, or null (no field yet, a corrupt one, a field baked relative to
    /// another frame, a bone that does not exist: each reported). A following collider's component is placed at once.
    /// </summary>
    public MeshCollider? ToComponent()
    {
        _component = null;
        _boneIndex = -1;
        if (_field == null || _field.Distances.Length == 0) return null;
        string frame = FrameName();
        if (_field.Frame != frame)
        {
            GD.PushError($"{Name}: the field was baked relative to the {_field.Frame}, but this collider now follows the {frame}: press Bake distance field again.");
            return null;
        }
        if (_follow != null && !ResolveBone(out string? why))
        {
            GD.PushError($"{Name}: {why}");
            return null;
        }
        try
        {
            var component = new MeshCollider(_field.ToField(), _margin, space: _follow != null ? ColliderSpace.World : ColliderSpace.Head);
            _component = component;
            PlaceField();
            return component;
        }
        catch (ArgumentException e) { GD.PushError($"{Name}: the stored field is unusable ({e.Message}); bake it again."); return null; }
    }

    /// <summary>
    /// Puts a following field where its node or bone is now (world space). The hair node calls it every physics frame
    /// before stepping; it allocates nothing. A transform with no rotation keeps the last place, reported once.
    /// </summary>
    public void PlaceField()
    {
        if (_component == null || _follow == null) return;
        if (!TryFollowedTransform(out var t, out string? why)) { ReportFollow(why); return; }
        if (ColliderFollowMath.TryFrame(t.ToNumericsMatrix(), out var frame, out bool mirrored))
        {
            _component.Placement = frame;
            ReportFollow(mirrored ? FollowMirrored : null);
        }
        else ReportFollow(FollowDegenerate);
    }

    /// <summary>Shown in the editor's Scene dock (nothing here depends on being in the editor).</summary>
    public override string[] _GetConfigurationWarnings()
    {
        var w = new List<string>();
        if (GetParent() is not HairSystem3D) w.Add("Make this node a child of a HairSystem3D.");
        if (_field == null || _field.Distances.Length == 0) w.Add("No distance field yet: set Source and press Bake distance field.");
        else if (_field.Frame != FrameName()) w.Add($"The field was baked relative to the {_field.Frame}, but this collider follows the {FrameName()}: bake it again.");
        if (_follow != null && !ResolveBone(out string? why)) w.Add(why!);
        if (_followProblem != null) w.Add(_followProblem);
        return w.ToArray();
    }

    private const string FollowFreed = "Follow no longer exists: the field stays where it was.";
    private const string FollowMirrored = "Follow's transform is mirrored (negative scale): its reflection is ignored, as at bake time.";
    private const string FollowDegenerate = "Follow's transform has no rotation (zero scale): the field keeps its last place.";
    private const string BoneGone = "Follow Bone is no longer in the skeleton: the field stays where it was.";

    private string FrameName() => ColliderFollowMath.FrameName(_follow?.Name.ToString(), _follow is Skeleton3D ? _followBone : null);

    /// <summary>The index of <see cref="FollowBone"/> when following a skeleton's bone (-1 otherwise); false with the reason if it is not there.</summary>
    private bool ResolveBone(out string? why)
    {
        why = null;
        _boneIndex = -1;
        if (_follow is not Skeleton3D skeleton || _followBone.Length == 0) return true;
        _boneIndex = skeleton.FindBone(_followBone);
        if (_boneIndex >= 0) return true;
        why = $"Follow Bone: {skeleton.Name} has no bone named \"{_followBone}\" (bone names are case-sensitive).";
        return false;
    }

    /// <summary>The followed node's or bone's global transform (Godot composes a bone's as skeleton × bone pose).</summary>
    private bool TryFollowedTransform(out Transform3D t, out string? why)
    {
        t = Transform3D.Identity;
        why = null;
        if (_follow == null || !IsInstanceValid(_follow)) { why = FollowFreed; return false; }
        if (_followBone.Length > 0 && _follow is Skeleton3D skeleton)
        {
            // Resolved when the hair syncs its colliders (FindBone takes a string: not every frame).
            if (_boneIndex < 0) ResolveBone(out _);
            if (_boneIndex < 0 || _boneIndex >= skeleton.GetBoneCount()) { why = BoneGone; return false; }
            t = skeleton.GlobalTransform * skeleton.GetBoneGlobalPose(_boneIndex);
            return true;
        }
        t = _follow.GlobalTransform;
        return true;
    }

    private void ReportFollow(string? problem)
    {
        if (problem == _followProblem) return;
        _followProblem = problem;
        if (problem != null) GD.PushWarning($"{Name}: {problem}");
        if (IsInsideTree()) UpdateConfigurationWarnings();
    }

    private void NotifyHair()
    {
        if (GetParent() is HairSystem3D hair) hair.CollidersChanged();
        if (IsInsideTree()) UpdateConfigurationWarnings();
    }
}
