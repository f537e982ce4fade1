using System.Numerics;

namespace HairSim.Meshes;

/// <summary>
/// A scene component: collide the hair with a mesh through its baked <see cref="SignedDistanceField"/> (head space,
/// moving with the head like the other colliders). Add it with <c>scene.SetComponent(new MeshCollider(sdf))</c>; the
/// pipeline then holds <see cref="MeshCollideSystem"/>, and leaves it out when no scene asks for it.
/// </summary>
public sealed class MeshCollider
{
    public MeshCollider(SignedDistanceField field, float margin = 0f, TriangleMesh? mesh = null)
    {
        Mesh = mesh;
        ArgumentNullException.ThrowIfNull(field);
        if (!float.IsFinite(margin) || margin < 0f || margin >= field.Band)
            throw new ArgumentOutOfRangeException(nameof(margin), margin, $"Margin must be in [0, {field.Band}) metres (the field's band).");
        Field = field; Margin = margin;
    }

    public SignedDistanceField Field { get; }
    /// <summary>The mesh the field was baked from, when known (for drawing it; the collision reads only the field).</summary>
    public TriangleMesh? Mesh { get; }
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
        // Head space once per call: local = Rᵀ(p − t).
        var toLocal = Matrix4x4.CreateFromQuaternion(Quaternion.Conjugate(head.Rotation));
        var toWorld = Matrix4x4.CreateFromQuaternion(head.Rotation);
        var t = head.Position;
        var field = mc.Field;
        float margin = mc.Margin, slide = ctx.Settings.ContactSlide, slack = 0.1f * field.CellSize + 1e-5f;
        for (int s = begin; s < end; s++)
        {
            int first = w.StrandFirst[s], last = first + w.StrandParticleCount[s];
            float previous = float.MaxValue;
            for (int i = first; i < last; i++)
            {
                float d = PushOut(w, field, i, t, toLocal, toWorld, margin, slide);
                // The segment's midpoint can only be inside if an end is within half a segment of the surface (the
                // field is 1-Lipschitz up to trilinear slack): most segments skip the second sample.
                if (i > first && MathF.Max(previous, d) - 0.5f * w.RestLength[i] < margin + slack)
                {
                    var mid = Vector3.TransformNormal(0.5f * (w.GetPosition(i - 1) + w.GetPosition(i)) - t, toLocal);
                    float dm = field.Sample(mid, out var gm);
                    if (dm < margin && gm.LengthSquared() > 1e-12f)
                    {
                        var push = Vector3.TransformNormal(Vector3.Normalize(gm), toWorld);
                        for (int j = i - 1; j <= i; j++)
                        {
                            if (w.InvMass[j] == 0f) continue;
                            w.PutPosition(j, w.GetPosition(j) + push * (margin - dm));
                            RemoveInward(w, j, push, slide);
                        }
                        // Lifting a segment over a thin part (an ear) can push an end into it from the other side.
                        PushOut(w, field, i - 1, t, toLocal, toWorld, margin, slide);
                        d = PushOut(w, field, i, t, toLocal, toWorld, margin, slide);
                    }
                }
                previous = d;
            }
        }
    }

    /// <summary>Pushes particle i out to the margin (up to three steps: in a crease one push can land in the other part); returns its distance.</summary>
    private static float PushOut(HairWorld w, SignedDistanceField field, int i, Vector3 t, in Matrix4x4 toLocal, in Matrix4x4 toWorld, float margin, float slide)
    {
        var local = Vector3.TransformNormal(w.GetPosition(i) - t, toLocal);
        float d = field.Distance(local);
        if (d >= margin || w.InvMass[i] == 0f) return d;
        for (int it = 0; it < 3 && d < margin; it++)
        {
            field.Sample(local, out var g);
            if (g.LengthSquared() <= 1e-12f) break;
            var n = Vector3.Normalize(g);
            local += n * (margin - d);
            RemoveInward(w, i, Vector3.TransformNormal(n, toWorld), slide);
            d = field.Distance(local);
        }
        w.PutPosition(i, t + Vector3.TransformNormal(local, toWorld));
        return d;
    }

    private static void RemoveInward(HairWorld w, int i, Vector3 normal, float slide)
    {
        var v = w.GetVelocity(i);
        float vn = Vector3.Dot(v, normal);
        if (vn < 0f) w.PutVelocity(i, (v - vn * normal) * slide);
    }
}
