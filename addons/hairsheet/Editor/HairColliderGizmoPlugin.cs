#if TOOLS
using System.Collections.Generic;
using Godot;

namespace HairSheet;

/// <summary>Wireframe gizmos for the hair collider nodes (drawn in the node's local space, so its scale shows).</summary>
[Tool]
public partial class HairColliderGizmoPlugin : EditorNode3DGizmoPlugin
{
    private const int Segments = 48;

    public HairColliderGizmoPlugin() => CreateMaterial("hair_collider", new Color(0.35f, 0.85f, 1f));

    public override string _GetGizmoName() => "Hair Collider";

    public override bool _HasGizmo(Node3D forNode3D) => forNode3D is IHairColliderNode;

    public override void _Redraw(EditorNode3DGizmo gizmo)
    {
        gizmo.Clear();
        var lines = new List<Vector3>();
        switch (gizmo.GetNode3D())
        {
            case HairEllipsoidCollider3D e:
                Ellipse(lines, Vector3.Zero, Vector3.Right * e.Radii.X, Vector3.Up * e.Radii.Y);
                Ellipse(lines, Vector3.Zero, Vector3.Up * e.Radii.Y, Vector3.Back * e.Radii.Z);
                Ellipse(lines, Vector3.Zero, Vector3.Right * e.Radii.X, Vector3.Back * e.Radii.Z);
                break;
            case HairSphereCollider3D s:
                Ellipse(lines, Vector3.Zero, Vector3.Right * s.Radius, Vector3.Up * s.Radius);
                Ellipse(lines, Vector3.Zero, Vector3.Up * s.Radius, Vector3.Back * s.Radius);
                Ellipse(lines, Vector3.Zero, Vector3.Right * s.Radius, Vector3.Back * s.Radius);
                break;
            case HairCapsuleCollider3D c:
                var top = Vector3.Up * (c.Height * 0.5f);
                float r = c.Radius;
                Ellipse(lines, top, Vector3.Right * r, Vector3.Back * r);
                Ellipse(lines, -top, Vector3.Right * r, Vector3.Back * r);
                Ellipse(lines, top, Vector3.Right * r, Vector3.Up * r, half: true);
                Ellipse(lines, top, Vector3.Back * r, Vector3.Up * r, half: true);
                Ellipse(lines, -top, Vector3.Right * r, Vector3.Down * r, half: true);
                Ellipse(lines, -top, Vector3.Back * r, Vector3.Down * r, half: true);
                foreach (var side in new[] { Vector3.Right, Vector3.Left, Vector3.Back, Vector3.Forward })
                {
                    lines.Add(top + side * r);
                    lines.Add(-top + side * r);
                }
                break;
            default:
                return;
        }
        gizmo.AddLines(lines.ToArray(), GetMaterial("hair_collider", gizmo));
    }

    /// <summary>Line pairs along centre + cos·a + sin·b (half: only the b-positive half).</summary>
    private static void Ellipse(List<Vector3> lines, Vector3 centre, Vector3 a, Vector3 b, bool half = false)
    {
        int n = half ? Segments / 2 : Segments;
        float span = half ? Mathf.Pi : Mathf.Tau;
        for (int i = 0; i < n; i++)
        {
            float t0 = span * i / n, t1 = span * (i + 1) / n;
            lines.Add(centre + a * Mathf.Cos(t0) + b * Mathf.Sin(t0));
            lines.Add(centre + a * Mathf.Cos(t1) + b * Mathf.Sin(t1));
        }
    }
}
#endif
