using System.Numerics;

namespace HairSim.Editing;

/// <summary>
/// The editing operations (SPEC A.5 / B.4). Each returns a command with its plan computed and validated;
/// nothing changes until the command is applied, usually through <see cref="EditHistory.Do"/>:
/// <code>
/// var cam = StrokeCamera.Perspective(view, projection, viewportSize);
/// history.Do(HairEditor.Cut(scene, new Stroke(points, cam)));
/// </code>
/// Camera and stroke math is in world space; rest data is written in head space.
/// </summary>
public static class HairEditor
{
    /// <summary>A new tip closer than this (metres) to the previous particle snaps back onto it.</summary>
    public const float MinTipSegment = 1e-5f;

    /// <summary>
    /// A crossing within this share of a segment's rest length past the segment's first particle moves that particle
    /// onto the stroke as the new tip, instead of leaving a sliver of a last segment (say 0.02 mm of a 17 mm one) that
    /// the next collision push would stretch many times over.
    /// </summary>
    public const float MinTipShare = 0.1f;

    // ---------------- cut ----------------

    /// <summary>Plans a cut of every strand the stroke crosses (as seen from its camera).</summary>
    public static CutCommand Cut(HairScene scene, Stroke stroke, CutOptions? options = null)
    {
        ArgumentNullException.ThrowIfNull(scene);
        ArgumentNullException.ThrowIfNull(stroke);
        options ??= new CutOptions();
        options.Validate();
        var w = scene.World;
        var cam = stroke.Camera;
        var grid = new StrokeGrid(stroke.Points);
        var colliders = new Collider[options.Reach == CutReach.VisibleOnly ? scene.Colliders.Count : 0];
        for (int c = 0; c < colliders.Length; c++) colliders[c] = scene.Colliders[c].ToWorld(w.Head);
        var mesh = options.Reach == CutReach.VisibleOnly ? scene.MeshColliderArray : [];
        var m = cam.ViewProjection;
        float vw = cam.ViewportSize.X * 0.5f, vh = cam.ViewportSize.Y * 0.5f;
        var cuts = new List<StrandCut>();
        float[] px = w.PosX, py = w.PosY, pz = w.PosZ;

        for (int s = 0; s < w.StrandCount; s++)
        {
            int first = w.StrandFirst[s], n = w.StrandParticleCount[s];
            bool okA = Project(m, vw, vh, px[first], py[first], pz[first], out var sa);
            double cum = 0;
            for (int k = 1; k < n; k++)
            {
                int i = first + k;
                bool okB = Project(m, vw, vh, px[i], py[i], pz[i], out var sb);
                double cumPrev = cum;
                cum += w.RestLength[i];
                if (okA && okB && w.InvMass[i] != 0f && grid.FirstCrossing(sa, sb, out float t2)
                    && TryCutAt(w, cam, colliders, mesh, options, s, k, Vector2.Lerp(sa, sb, t2), t2, cumPrev, out var cut))
                {
                    cuts.Add(cut);
                    break;
                }
                sa = sb; okA = okB;
            }
        }
        return new CutCommand(w, cuts.ToArray());
    }

    private static bool Project(in Matrix4x4 m, float vw, float vh, float x, float y, float z, out Vector2 screen)
    {
        float cw = x * m.M14 + y * m.M24 + z * m.M34 + m.M44;
        if (!(cw > 1e-9f)) { screen = default; return false; }
        float inv = 1f / cw;
        screen = new Vector2((x * m.M11 + y * m.M21 + z * m.M31 + m.M41) * inv * vw + vw,
                             vh - (x * m.M12 + y * m.M22 + z * m.M32 + m.M42) * inv * vh);
        return true;
    }

    /// <summary>Lifts a screen crossing onto strand segment (k−1, k) and checks the cut's rules.</summary>
    private static bool TryCutAt(HairWorld w, StrokeCamera cam, Collider[] colliders, Meshes.MeshCollider[] meshes, CutOptions o, int s, int k,
        Vector2 screen, float t2, double cumPrev, out StrandCut cut)
    {
        cut = default;
        int i = w.StrandFirst[s] + k, n = w.StrandParticleCount[s];
        var a = w.GetPosition(i - 1); var b = w.GetPosition(i);
        var (origin, dir) = cam.ScreenRay(screen);
        float u = ClosestOnSegmentToRay(a, b, origin, dir, t2);
        if (k == n - 1 && u >= 1f - 1e-6f) return false; // crossing at the tip itself: nothing to remove
        if (cumPrev + u * w.RestLength[i] < o.MinRemainingLength) return false;
        var p = Vector3.Lerp(a, b, u);
        if (colliders.Length > 0)
        {
            float tp = Vector3.Dot(p - origin, dir);
            foreach (var c in colliders)
                if (ColliderRay.Intersect(c, origin, dir, out float th) && th < tp - 1e-4f) return false;
        }
        foreach (var hiding in meshes)
            if (MeshHides(hiding, w.Head, origin, dir, Vector3.Dot(p - origin, dir))) return false;
        float len = Vector3.Distance(a, p);
        if (len < MinTipSegment)
        {
            // The crossing sits on particle k−1: that particle becomes the tip, if it is free.
            if (k - 1 < 1 || w.InvMass[i - 1] == 0f) return false;
            cut = new StrandCut(s, k, a, w.GetVelocity(i - 1), w.GetRest(i - 1), w.RestLength[i - 1]);
            return true;
        }
        var restA = w.GetRest(i - 1); var restB = w.GetRest(i);
        float restSeg = Vector3.Distance(restA, restB);
        var tipRest = restSeg > 0f ? restA + (restB - restA) * (len / restSeg) : restA;
        var tipVelocity = Vector3.Lerp(w.GetVelocity(i - 1), w.GetVelocity(i), u);
        if (len < MinTipShare * w.RestLength[i] && k >= 2 && w.InvMass[i - 1] != 0f)
        {
            // Particle k−1 becomes the tip, on the stroke: no sliver of a segment after it.
            cut = new StrandCut(s, k, p, tipVelocity, tipRest, Vector3.Distance(w.GetPosition(i - 2), p));
            return true;
        }
        cut = new StrandCut(s, k + 1, p, tipVelocity, tipRest, len);
        return true;
    }

    /// <summary>Parameter on segment a → b of the point nearest the ray (the point that projects to the crossing).</summary>
    internal static float ClosestOnSegmentToRay(Vector3 a, Vector3 b, Vector3 o, Vector3 d, float fallback)
    {
        var e = b - a; var w0 = a - o;
        double ee = Vector3.Dot(e, e), ed = Vector3.Dot(e, d), dd = Vector3.Dot(d, d);
        double ew = Vector3.Dot(e, w0), dw = Vector3.Dot(d, w0);
        double denom = ee * dd - ed * ed;
        if (denom < 1e-12 * ee * dd) return Math.Clamp(fallback, 0f, 1f); // segment seen end-on
        return (float)Math.Clamp((ed * dw - dd * ew) / denom, 0.0, 1.0);
    }

    // ---------------- selection ----------------

    /// <summary>The strands inside a screen-space area (see <see cref="SelectionOptions"/> for what "inside" means).</summary>
    public static StrandSelection Select(HairScene scene, StrokeCamera camera, SelectionArea area, SelectionOptions? options = null)
    {
        ArgumentNullException.ThrowIfNull(scene);
        ArgumentNullException.ThrowIfNull(camera);
        ArgumentNullException.ThrowIfNull(area);
        options ??= new SelectionOptions();
        var w = scene.World;
        var colliders = new Collider[options.VisibleOnly ? scene.Colliders.Count : 0];
        for (int c = 0; c < colliders.Length; c++) colliders[c] = scene.Colliders[c].ToWorld(w.Head);
        var meshes = options.VisibleOnly ? scene.MeshColliderArray : [];
        var chosen = new List<int>();
        for (int s = 0; s < w.StrandCount; s++)
        {
            int first = w.StrandFirst[s], n = options.RootsOnly ? 1 : w.StrandParticleCount[s];
            for (int k = 0; k < n; k++)
            {
                var p = w.GetPosition(first + k);
                if (!camera.Project(p, out var sp, out _) || !area.Contains(sp)) continue;
                if (colliders.Length > 0 && Hidden(camera, colliders, p, sp)) continue;
                if (meshes.Length > 0)
                {
                    var (o, d) = camera.ScreenRay(sp);
                    bool hidden = false;
                    foreach (var mesh in meshes) hidden = hidden || MeshHides(mesh, w.Head, o, d, Vector3.Dot(p - o, d));
                    if (hidden) continue;
                }
                chosen.Add(s);
                break;
            }
        }
        return new StrandSelection(w, chosen.ToArray());
    }

    /// <summary>
    /// Does the mesh cover a point at ray distance tp? The trace stops a little short of the point (two cells, at least
    /// 2 mm), so hair lying on the surface is not hidden by the surface under it.
    /// </summary>
    internal static bool MeshHides(Meshes.MeshCollider mesh, in RigidTransform head, Vector3 origin, Vector3 dir, float tp) =>
        ColliderRay.Intersect(mesh, mesh.PoseFor(head), origin, dir, tp - MathF.Max(0.002f, 2f * mesh.Field.CellSize), out _);

    private static bool Hidden(StrokeCamera cam, Collider[] colliders, Vector3 p, Vector2 screen)
    {
        var (o, d) = cam.ScreenRay(screen);
        float tp = Vector3.Dot(p - o, d);
        foreach (var c in colliders)
            if (ColliderRay.Intersect(c, o, d, out float th) && th < tp - 1e-4f) return true;
        return false;
    }

    // ---------------- fit ----------------

    /// <summary>Plans a fit of the selected strands to a stroke (SPEC A.5, Algorithm 3); see <see cref="FitCommand"/>.</summary>
    public static FitCommand Fit(HairScene scene, StrandSelection selection, Stroke stroke, FitOptions? options = null)
    {
        ArgumentNullException.ThrowIfNull(scene);
        ArgumentNullException.ThrowIfNull(selection);
        ArgumentNullException.ThrowIfNull(stroke);
        options ??= new FitOptions();
        if (!ReferenceEquals(selection.World, scene.World)) throw new ArgumentException("The selection belongs to another world.", nameof(selection));
        if (selection.Count == 0) throw new ArgumentException("Nothing is selected: select strands before fitting.", nameof(selection));
        return FitCommand.Plan(scene, selection, stroke, options);
    }

    // ---------------- reset / regrow ----------------

    /// <summary>Puts the selected strands (all if null) back at their rest pose under the current head, at rest.</summary>
    public static EditCommand ResetToRest(HairScene scene, StrandSelection? selection = null)
    {
        ArgumentNullException.ThrowIfNull(scene);
        return new ResetCommand(scene.World, StrandsOf(scene.World, selection), null);
    }

    /// <summary>
    /// Regrows the selected strands (all if null) from a groom of the same layout (for example the freshly built
    /// groom): full length, the groom's rest pose and rest shape, placed at rest under the current head.
    /// </summary>
    public static EditCommand Regrow(HairScene scene, HairWorld groom, StrandSelection? selection = null)
    {
        ArgumentNullException.ThrowIfNull(scene);
        ArgumentNullException.ThrowIfNull(groom);
        if (!scene.World.SameLayout(groom)) throw new ArgumentException("The groom's layout differs from the scene's world.", nameof(groom));
        return new ResetCommand(scene.World, StrandsOf(scene.World, selection), groom);
    }

    /// <summary>
    /// Makes the current shape of the selected strands (all if null) their rest pose and rest shape — for example
    /// after the groom has settled under gravity, so a global shape stiffness holds the hanging hair rather than
    /// pulling it back to the groom's initial pose. Nothing moves.
    /// </summary>
    public static EditCommand BakeRestPose(HairScene scene, StrandSelection? selection = null)
    {
        ArgumentNullException.ThrowIfNull(scene);
        return new BakeCommand(scene.World, StrandsOf(scene.World, selection));
    }

    private static int[] StrandsOf(HairWorld w, StrandSelection? selection)
    {
        if (selection == null) { var all = new int[w.StrandCount]; for (int s = 0; s < all.Length; s++) all[s] = s; return all; }
        if (!ReferenceEquals(selection.World, w)) throw new ArgumentException("The selection belongs to another world.", nameof(selection));
        return selection.Strands.ToArray();
    }
}
