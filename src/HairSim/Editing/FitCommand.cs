using System.Numerics;

namespace HairSim.Editing;

public sealed class FitOptions
{
    /// <summary>If the stroke's last point is nearer the selection's roots (on screen) than its first, read it backwards.</summary>
    public bool OrientFromRoots { get; set; } = true;
}

/// <summary>
/// A planned fit (SPEC A.5, Algorithm 3). The key curve of the selected strands is matched to the stroke
/// (lifted onto the plane through the key curve's centroid facing the camera, and translated to start where the
/// hair leaves the head); each strand keeps its offset from the key curve in the curve's rotation-minimising
/// frame at the same arc length, then its segments are put back to their rest lengths root to tip (hair does
/// not stretch). The result becomes the strands' rest pose (head space) and rest shape, at rest.
/// Stroke shorter than the key curve: the curve continues straight along the stroke's last direction.
/// Stroke that doubles back: followed as drawn (the hair folds back); lengths are still kept.
/// Strands of different lengths: each follows the key curve for its own length from the root.
/// A fitted shape that would enter one of the scene's colliders (a curl drawn into the forehead) is pushed out of
/// it, lengths kept: the bend model holds the rest shape, and one inside the head would be fought by collision forever.
/// </summary>
public sealed class FitCommand : EditCommand
{
    private readonly Vector3[] _positions; // new world positions of the live particles of each strand, concatenated

    private FitCommand(HairWorld world, int[] strands, Vector3[] positions, KeyCurve key, KeyCurve target, float strokeLength)
        : base(world, "Fit", strands)
    {
        _positions = positions; KeyCurve = key; Target = target; StrokeLength = strokeLength;
    }

    /// <summary>The selection's key curve before the fit.</summary>
    public KeyCurve KeyCurve { get; }
    /// <summary>The key curve after matching it to the stroke.</summary>
    public KeyCurve Target { get; }
    /// <summary>Length of the stroke lifted to 3D (metres).</summary>
    public float StrokeLength { get; }
    /// <summary>True when the stroke was shorter than the key curve and the curve was extended straight.</summary>
    public bool Extended => StrokeLength < KeyCurve.Length - RootArc;
    /// <summary>Arc length along the key curve where the stroke takes over (the pinned part of the strands).</summary>
    public float RootArc { get; private init; }
    protected override long PlanBytes => _positions.Length * 12L;

    internal static FitCommand Plan(HairScene scene, StrandSelection selection, Stroke stroke, FitOptions options)
    {
        var w = scene.World;
        var strands = selection.Strands.ToArray();
        var key = KeyCurve.FromStrands(w, strands);
        var cam = stroke.Camera;

        // Lift the stroke onto the plane through the key curve's centroid, facing the camera.
        var centroid = Vector3.Zero;
        foreach (var p in key.Points) centroid += p;
        centroid /= key.Points.Length;
        var normal = cam.Forward;
        var lifted = new Vector3[stroke.Count];
        for (int k = 0; k < lifted.Length; k++)
        {
            var (o, d) = cam.ScreenRay(stroke.Points[k]);
            float dn = Vector3.Dot(d, normal);
            if (MathF.Abs(dn) < 1e-6f) throw new ArgumentException("The stroke cannot be lifted: its rays run along the fitting plane.", nameof(stroke));
            lifted[k] = o + d * (Vector3.Dot(centroid - o, normal) / dn);
        }
        if (options.OrientFromRoots && cam.Project(key.Root, out var rootScreen, out _) &&
            Vector2.Distance(stroke.Points[^1], rootScreen) < Vector2.Distance(stroke.Points[0], rootScreen))
            Array.Reverse(lifted);

        // Where the stroke takes over: past the pinned particles (mean arc length of the last pinned one).
        float rootArc = 0f;
        foreach (int s in strands)
        {
            var pts = w.GetStrandPositions(s);
            var cum = KeyCurve.ArcLengths(pts);
            int first = w.StrandFirst[s], last = 0;
            while (last + 1 < pts.Length && w.InvMass[first + last + 1] == 0f) last++;
            rootArc += cum[last];
        }
        rootArc /= strands.Length;

        int m = key.Points.Length;
        var target = new Vector3[m];
        var liftedArc = KeyCurve.ArcLengths(lifted);
        float strokeLength = liftedArc[^1];
        key.Frame(rootArc, out var anchor, out _, out _, out _);
        for (int k = 0; k < m; k++)
        {
            float s = k * key.Spacing;
            if (s <= rootArc) target[k] = key.Points[k];
            else target[k] = anchor + KeyCurve.Sample(lifted, liftedArc, s - rootArc) - lifted[0];
        }
        // Start the target's frames from the key curve's first frame, turned by the least rotation between their tangents.
        var turn = LeastRotation(key.Tangents[0], Tangent0(target));
        var targetCurve = KeyCurve.FromSamples(target, key.Spacing, Vector3.Transform(key.Normals[0], turn));

        // Each strand: offsets in the key frame → the same offsets in the target frame, then lengths restored.
        int total = 0;
        foreach (int s in strands) total += w.StrandParticleCount[s];
        var colliders = new Collider[scene.Colliders.Count];
        for (int c = 0; c < colliders.Length; c++) colliders[c] = scene.Colliders[c].ToWorld(w.Head);
        var positions = new Vector3[total];
        int o0 = 0;
        foreach (int s in strands)
        {
            var pts = w.GetStrandPositions(s);
            var cum = KeyCurve.ArcLengths(pts);
            int first = w.StrandFirst[s], n = pts.Length;
            for (int k = 0; k < n; k++)
            {
                int i = first + k;
                if (w.InvMass[i] == 0f) { positions[o0 + k] = pts[k]; continue; }
                key.Frame(cum[k], out var kp, out var kt, out var kn, out var kb);
                var d = pts[k] - kp;
                float ot = Vector3.Dot(d, kt), on = Vector3.Dot(d, kn), ob = Vector3.Dot(d, kb);
                targetCurve.Frame(cum[k], out var tp, out var tt, out var tn, out var tb);
                positions[o0 + k] = tp + ot * tt + on * tn + ob * tb;
            }
            RestoreLengths(w, s, pts, positions.AsSpan(o0, n));
            KeepOutside(w, s, colliders, positions.AsSpan(o0, n));
            for (int k = 0; k < n; k++)
            {
                var p = positions[o0 + k];
                if (!float.IsFinite(p.X) || !float.IsFinite(p.Y) || !float.IsFinite(p.Z))
                    throw new ArgumentException($"The fit produced a non-finite position on strand {s}; the stroke is degenerate.", nameof(stroke));
            }
            o0 += n;
        }
        return new FitCommand(w, strands, positions, key, targetCurve, strokeLength) { RootArc = rootArc };
    }

    private static Vector3 Tangent0(Vector3[] pts)
    {
        for (int k = 1; k < pts.Length; k++)
        {
            var d = pts[k] - pts[0];
            if (d.LengthSquared() > 1e-24f) return Vector3.Normalize(d);
        }
        return -Vector3.UnitY;
    }

    private static Quaternion LeastRotation(Vector3 from, Vector3 to)
    {
        float c = Vector3.Dot(from, to);
        if (c > 1f - 1e-7f) return Quaternion.Identity;
        var axis = c < -1f + 1e-7f ? RestShape.AnyPerpendicular(from) : Vector3.Normalize(Vector3.Cross(from, to));
        return Quaternion.CreateFromAxisAngle(axis, MathF.Acos(Math.Clamp(c, -1f, 1f)));
    }

    /// <summary>Follow-the-leader from the root: each free particle goes to its rest length from the previous one.</summary>
    private static void RestoreLengths(HairWorld w, int s, Vector3[] old, Span<Vector3> p)
    {
        int first = w.StrandFirst[s];
        for (int k = 1; k < p.Length; k++)
        {
            int i = first + k;
            if (w.InvMass[i] == 0f) continue;
            var d = p[k] - p[k - 1];
            float len = d.Length();
            if (!(len > 1e-9f))
            {
                d = old[k] - old[k - 1];
                len = d.Length();
                if (!(len > 1e-9f)) { d = -Vector3.UnitY; len = 1f; }
            }
            p[k] = p[k - 1] + d * (w.RestLength[i] / len);
        }
    }

    /// <summary>
    /// Root to tip: a free particle inside a collider goes just outside its surface, then back to its rest length from the
    /// previous particle along the new direction (a few rounds, so the length step cannot leave it deep inside).
    /// </summary>
    private static void KeepOutside(HairWorld w, int s, Collider[] colliders, Span<Vector3> p)
    {
        if (colliders.Length == 0) return;
        int first = w.StrandFirst[s];
        for (int k = 1; k < p.Length; k++)
        {
            int i = first + k;
            if (w.InvMass[i] == 0f) continue;
            float lift = 0.1f * w.RestLength[i];
            // Back to the rest length from the previous particle first (it may have been pushed out itself).
            var e = p[k] - p[k - 1];
            float el = e.Length();
            if (el > 1e-9f) p[k] = p[k - 1] + e * (w.RestLength[i] / el);
            for (int round = 0; round < 8; round++)
            {
                bool moved = false;
                foreach (var c in colliders)
                    if (c.Resolve(p[k], out var surface, out var normal, out _)) { p[k] = surface + normal * lift; moved = true; }
                if (!moved) break;
                var d = p[k] - p[k - 1];
                float len = d.Length();
                if (!(len > 1e-9f)) break;
                p[k] = p[k - 1] + d * (w.RestLength[i] / len);
            }
        }
    }

    protected override void Execute(HairWorld w)
    {
        var head = w.Head;
        int o = 0;
        foreach (int s in Strands)
        {
            int first = w.StrandFirst[s], n = w.StrandParticleCount[s];
            for (int k = 0; k < n; k++)
            {
                int i = first + k;
                if (w.InvMass[i] == 0f) continue;
                var p = _positions[o + k];
                w.SetPosition(i, p);
                w.SetVelocity(i, Vector3.Zero);
                var r = head.InverseTransformPoint(p);
                w.RestX[i] = r.X; w.RestY[i] = r.Y; w.RestZ[i] = r.Z;
            }
            RestShape.SetFromRestPose(w, s);
            o += n;
        }
    }
}
