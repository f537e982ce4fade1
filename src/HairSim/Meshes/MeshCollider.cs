using System.Numerics;

namespace HairSim.Meshes;

/// <summary>
/// A scene component: collide the hair with a mesh through its baked <see cref="SignedDistanceField"/> (head space,
/// moving with the head like the other colliders). Add it with <c>scene.SetComponent(new MeshCollider(sdf))</c>; the
/// pipeline then holds <see cref="MeshCollideSystem"/>, and leaves it out when no scene asks for it.
/// </summary>
public sealed class MeshCollider
{
    public MeshCollider(SignedDistanceField field, float margin = 0f)
    {
        ArgumentNullException.ThrowIfNull(field);
        if (!float.IsFinite(margin) || margin < 0f || margin >= field.Band)
            throw new ArgumentOutOfRangeException(nameof(margin), margin, $"Margin must be in [0, {field.Band}) metres (the field's band).");
        Field = field; Margin = margin;
    }

    public SignedDistanceField Field { get; }
    /// <summary>Hair keeps at least this far from the surface (metres), like the root lift of an ellipsoid groom.</summary>
    public float Margin { get; }
}

/// <summary>
/// Collision with a <see cref="MeshCollider"/>: a particle whose signed distance (in head space, at the substep's head
/// pose) is below the margin goes back out along the field's gradient, its inward velocity is removed and the rest
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
        var mc = scene.GetComponent<MeshCollider>();
        if (mc == null) return;
        var w = scene.World;
        var head = ctx.HeadAt(substep);
        var field = mc.Field;
        float margin = mc.Margin, slide = ctx.Settings.ContactSlide;
        for (int s = begin; s < end; s++)
        {
            int first = w.StrandFirst[s], last = first + w.StrandParticleCount[s];
            for (int i = first; i < last; i++)
            {
                if (w.InvMass[i] != 0f) Push(w, head, field, margin, slide, i, head.InverseTransformPoint(w.GetPosition(i)));
                if (i == first) continue;
                // The segment's midpoint: both ends move out by the midpoint's depth.
                var mid = head.InverseTransformPoint(0.5f * (w.GetPosition(i - 1) + w.GetPosition(i)));
                float dm = field.Sample(mid, out var gm);
                if (dm >= margin || gm.LengthSquared() < 1e-12f) continue;
                var push = head.TransformDirection(Vector3.Normalize(gm)) * (margin - dm);
                for (int j = i - 1; j <= i; j++)
                {
                    if (w.InvMass[j] == 0f) continue;
                    w.PutPosition(j, w.GetPosition(j) + push);
                    RemoveInward(w, j, Vector3.Normalize(push), slide);
                }
            }
        }
    }

    private static void Push(HairWorld w, in RigidTransform head, SignedDistanceField field, float margin, float slide, int i, Vector3 local)
    {
        float d = field.Sample(local, out var g);
        if (d >= margin || g.LengthSquared() < 1e-12f) return;
        var n = Vector3.Normalize(g);
        w.PutPosition(i, head.TransformPoint(local + n * (margin - d)));
        RemoveInward(w, i, head.TransformDirection(n), slide);
    }

    private static void RemoveInward(HairWorld w, int i, Vector3 normal, float slide)
    {
        var v = w.GetVelocity(i);
        float vn = Vector3.Dot(v, normal);
        if (vn < 0f) w.PutVelocity(i, (v - vn * normal) * slide);
    }
}
