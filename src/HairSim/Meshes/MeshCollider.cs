using System.Numerics;

namespace HairSim.Meshes;

/// <summary>Where a <see cref="MeshCollider"/>'s <see cref="MeshCollider.Placement"/> is given.</summary>
public enum ColliderSpace
{
    /// <summary>Relative to the head: the mesh moves with the head (a head mesh, or a part placed on it).</summary>
    Head,
    /// <summary>In world space: the caller moves it (a body, a shoulder on a bone, a prop), setting the placement every frame.</summary>
    World,
}

/// <summary>
/// Collide the hair with a mesh through its baked <see cref="SignedDistanceField"/>. Add it with
/// <c>scene.SetComponent(new MeshCollider(sdf))</c> (the scene's main mesh, e.g. the head a groom grows on) or, for
/// more meshes (a body beside the head), <c>scene.AddMeshCollider(…)</c>: <see cref="HairScene.MeshColliders"/> lists them
/// all. The pipeline then holds <see cref="MeshCollideSystem"/>, and leaves it out when no scene asks for it. By default the field is in head space and moves with the head; a
/// <see cref="Placement"/> puts it elsewhere on the head, or, with <see cref="ColliderSpace.World"/>, anywhere in the
/// world (set it before each step, e.g. from a bone's global pose). A placement changed between two steps is carried
/// from the last frame's across the substeps, as the head is, so a fast bone sweeps the hair instead of jumping into it;
/// a jump beyond the teleport limits places it at once. A collider moving this way belongs to one scene.
/// </summary>
public sealed class MeshCollider
{
    private RigidTransform _placement = RigidTransform.Identity;
    private float _reach = -1f;

    public MeshCollider(SignedDistanceField field, float margin = 0f, TriangleMesh? mesh = null, ColliderSpace space = ColliderSpace.Head)
    {
        Mesh = mesh;
        ArgumentNullException.ThrowIfNull(field);
        if (!float.IsFinite(margin) || margin < 0f || margin >= field.Band)
            throw new ArgumentOutOfRangeException(nameof(margin), margin, $"Margin must be in [0, {field.Band}) metres (the field's band).");
        if (!Enum.IsDefined(space)) throw new ArgumentOutOfRangeException(nameof(space), space, "Unknown collider space.");
        Field = field; Margin = margin; Space = space;
    }

    public SignedDistanceField Field { get; }
    /// <summary>The mesh the field was baked from, when known (for drawing it; the collision reads only the field).</summary>
    public TriangleMesh? Mesh { get; }
    /// <summary>Hair keeps at least this far from the surface (metres), like the root lift of an ellipsoid groom.</summary>
    public float Margin { get; }
    /// <summary>Whether <see cref="Placement"/> is relative to the head or in world space.</summary>
    public ColliderSpace Space { get; }

    /// <summary>
    /// The field's pose: relative to the head (<see cref="ColliderSpace.Head"/>, identity: the field is in head space) or
    /// in the world (<see cref="ColliderSpace.World"/>). Rigid; refused unless finite with a non-zero rotation (kept normalised).
    /// </summary>
    public RigidTransform Placement
    {
        get => _placement;
        set
        {
            var p = value.Position; var q = value.Rotation;
            if (!float.IsFinite(p.X) || !float.IsFinite(p.Y) || !float.IsFinite(p.Z) || !float.IsFinite(q.X) || !float.IsFinite(q.Y)
                || !float.IsFinite(q.Z) || !float.IsFinite(q.W) || !(q.LengthSquared() > 1e-12f))
                throw new ArgumentException($"A placement must be finite with a non-zero rotation, got {p}, {q}.", nameof(value));
            _placement = new RigidTransform(p, Quaternion.Normalize(q));
        }
    }

    /// <summary>The field's world pose while the head is at <paramref name="head"/>: what the collision, the metrics and visibility tests use.</summary>
    public RigidTransform PoseFor(in RigidTransform head) => PoseFor(head, _placement);

    /// <summary>The world pose of the field placed at <paramref name="placement"/> (in this collider's space).</summary>
    internal RigidTransform PoseFor(in RigidTransform head, in RigidTransform placement) => Space == ColliderSpace.World ? placement
        : new RigidTransform(head.TransformPoint(placement.Position), Quaternion.Normalize(Quaternion.Concatenate(placement.Rotation, head.Rotation)));

    /// <summary>The placement at the end of the last stepped frame: where the next frame carries it from.</summary>
    internal RigidTransform PlacementBefore { get; private set; } = RigidTransform.Identity;

    /// <summary>A frame has been stepped (or the collider joined a scene): its placement is the next frame's start.</summary>
    internal void Stepped() => PlacementBefore = _placement;

    /// <summary>How far the field's farthest corner lies from its origin: a turn by an angle moves its surface at most this × the angle.</summary>
    internal float Reach
    {
        get
        {
            if (_reach < 0f)
            {
                var f = Field;
                var lo = f.Origin; var hi = lo + f.CellSize * new Vector3(f.Nx - 1, f.Ny - 1, f.Nz - 1);
                _reach = Vector3.Max(Vector3.Abs(lo), Vector3.Abs(hi)).Length();
            }
            return _reach;
        }
    }
}

/// <summary>
/// Collision with a <see cref="MeshCollider"/>: a particle whose signed distance (in the field's space, at the substep's
/// head pose, or at its world placement) is below the margin goes back out along the field's gradient, its inward velocity is removed and the rest
/// kept (scaled by ContactSlide), as <see cref="CollideSystem"/> does for ellipsoids. Segments are tested at their
/// midpoints too, so a part thinner than a segment (an ear's rim) cannot slip between two particles: a midpoint
/// inside pushes both ends out. One implementation for both paths: it touches only its own strands, so threads
/// step strand ranges in parallel.
/// </summary>
public sealed class MeshCollideSystem : IHairSystem
{
    public const string SystemName = "MeshCollide";
    public string Name => SystemName;
    public SystemPhase Phase => SystemPhase.Substep;

    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        // One mesh after the other over the same strands: strands are independent, so chunks (one mesh after the other per chunk) agree.
        var colliders = scene.MeshColliderArray;
        for (int m = 0; m < colliders.Length; m++)
            Collide(scene.World, colliders[m], new Pose(ctx.MeshPoseAt(substep, m, colliders)), ctx.Settings.ContactSlide, begin, end);
    }

    /// <summary>
    /// The head pose as a rotation matrix both ways (built once per call): local = Rᵀ(p − t), world = R·local + t. The
    /// vectorised kernel (FastMeshCollideSystem) builds the same matrices and does every operation below in the same
    /// order, so the two give the same bits.
    /// </summary>
    internal readonly struct Pose(RigidTransform head)
    {
        public readonly Fast.PoseLanes ToLocal = Fast.PoseLanes.InverseRotation(head.Rotation), ToWorld = new(head.Rotation, head.Position);
        public readonly Vector3 T = head.Position;
    }

    /// <summary>The threshold below which a segment's midpoint can be inside: margin + 1-Lipschitz slack of the trilinear field.</summary>
    internal static float MidpointThreshold(MeshCollider mc) => mc.Margin + (0.1f * mc.Field.CellSize + 1e-5f);

    internal static void Collide(HairWorld w, MeshCollider mc, in Pose pose, float slide, int begin, int end)
    {
        var field = mc.Field;
        float margin = mc.Margin, threshold = MidpointThreshold(mc);
        for (int s = begin; s < end; s++)
        {
            int first = w.StrandFirst[s], last = first + w.StrandParticleCount[s];
            float previous = float.MaxValue;
            for (int i = first; i < last; i++)
            {
                float d = PushOut(w, field, i, pose, margin, slide);
                // The segment's midpoint can only be inside if an end is within half a segment of the surface (the
                // field is 1-Lipschitz up to trilinear slack): most segments skip the second sample.
                if (i > first && MathF.Max(previous, d) - 0.5f * w.RestLength[i] < threshold)
                {
                    float mx = 0.5f * (w.PosX[i - 1] + w.PosX[i]) - pose.T.X, my = 0.5f * (w.PosY[i - 1] + w.PosY[i]) - pose.T.Y,
                        mz = 0.5f * (w.PosZ[i - 1] + w.PosZ[i]) - pose.T.Z;
                    var mid = pose.ToLocal.Direction(new Vector3(mx, my, mz));
                    float dm = field.SampleAt(mid.X, mid.Y, mid.Z, out float gx, out float gy, out float gz);
                    float g2 = gx * gx + gy * gy + gz * gz;
                    if (dm < margin && g2 > 1e-12f)
                    {
                        float len = MathF.Sqrt(g2);
                        var push = pose.ToWorld.Direction(new Vector3(gx / len, gy / len, gz / len));
                        float amount = margin - dm;
                        for (int j = i - 1; j <= i; j++)
                        {
                            if (w.InvMass[j] == 0f) continue;
                            w.PosX[j] += push.X * amount; w.PosY[j] += push.Y * amount; w.PosZ[j] += push.Z * amount;
                            RemoveInward(w, j, push, slide);
                        }
                        // Lifting a segment over a thin part (an ear) can push an end into it from the other side.
                        PushOut(w, field, i - 1, pose, margin, slide);
                        d = PushOut(w, field, i, pose, margin, slide);
                    }
                }
                previous = d;
            }
        }
    }

    /// <summary>Pushes particle i out to the margin (up to three steps: in a crease one push can land in the other part); returns its distance.</summary>
    private static float PushOut(HairWorld w, SignedDistanceField field, int i, in Pose pose, float margin, float slide)
    {
        var local = pose.ToLocal.Direction(new Vector3(w.PosX[i] - pose.T.X, w.PosY[i] - pose.T.Y, w.PosZ[i] - pose.T.Z));
        float d = field.DistanceAt(local.X, local.Y, local.Z);
        if (d >= margin || w.InvMass[i] == 0f) return d;
        for (int it = 0; it < 3 && d < margin; it++)
        {
            field.SampleAt(local.X, local.Y, local.Z, out float gx, out float gy, out float gz);
            float g2 = gx * gx + gy * gy + gz * gz;
            if (!(g2 > 1e-12f)) break;
            float len = MathF.Sqrt(g2), amount = margin - d;
            float nx = gx / len, ny = gy / len, nz = gz / len;
            local = new Vector3(local.X + nx * amount, local.Y + ny * amount, local.Z + nz * amount);
            RemoveInward(w, i, pose.ToWorld.Direction(new Vector3(nx, ny, nz)), slide);
            d = field.DistanceAt(local.X, local.Y, local.Z);
        }
        var p = pose.ToWorld.Point(local);
        w.PosX[i] = p.X; w.PosY[i] = p.Y; w.PosZ[i] = p.Z;
        return d;
    }

    private static void RemoveInward(HairWorld w, int i, Vector3 normal, float slide)
    {
        float vx = w.VelX[i], vy = w.VelY[i], vz = w.VelZ[i];
        float vn = vx * normal.X + vy * normal.Y + vz * normal.Z;
        if (vn < 0f) { w.VelX[i] = (vx - vn * normal.X) * slide; w.VelY[i] = (vy - vn * normal.Y) * slide; w.VelZ[i] = (vz - vn * normal.Z) * slide; }
    }
}
