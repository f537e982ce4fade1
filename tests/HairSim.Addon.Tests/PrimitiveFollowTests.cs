using System.Numerics;
using HairSheet.Logic;
using HairSim;
using static HairSheet.Addon.Tests.TestScenes;

namespace HairSheet.Addon.Tests;

/// <summary>
/// Sphere, capsule and ellipsoid nodes following a bone or node (<see cref="ColliderFollowMath.OffsetIn"/>,
/// <see cref="ColliderFollowMath.Place"/>): the offset taken in the editor carried by the frame, sized by the node's scale,
/// and a shoulder capsule on a moving bone placed every frame through <see cref="HairScene.SetCollider"/> without a rebuild.
/// </summary>
public class PrimitiveFollowTests
{
    /// <summary>A Godot Transform3D (rotation, per-axis scale, origin) as GodotConvert.ToNumericsMatrix writes it.</summary>
    private static Matrix4x4 Godot(Quaternion rotation, Vector3 scale, Vector3 origin)
    {
        Vector3 x = Vector3.Transform(Vector3.UnitX, rotation) * scale.X, y = Vector3.Transform(Vector3.UnitY, rotation) * scale.Y,
            z = Vector3.Transform(Vector3.UnitZ, rotation) * scale.Z;
        return new(x.X, x.Y, x.Z, 0, y.X, y.Y, y.Z, 0, z.X, z.Y, z.Z, 0, origin.X, origin.Y, origin.Z, 1);
    }

    private static readonly Quaternion NodeTurn = Quaternion.CreateFromYawPitchRoll(0.3f, 0.4f, -0.2f);
    // The collider node as placed in the editor (scaled 1.5×), and the bone it follows then and later.
    private static readonly Matrix4x4 NodeGlobal = Godot(NodeTurn, new Vector3(1.5f), new Vector3(0.12f, 1.45f, 0.03f));
    private static readonly RigidTransform BoneThen = new(new Vector3(0.05f, 1.4f, 0f), Quaternion.CreateFromYawPitchRoll(0.1f, 0f, 0.2f));
    private static readonly RigidTransform BoneNow = new(new Vector3(0.3f, 1.2f, -0.4f), Quaternion.CreateFromYawPitchRoll(1.1f, -0.5f, 0.3f));

    /// <summary>A point of the node, in the node's own coordinates, where the bone now carries it: BoneNow ∘ BoneThen⁻¹ of its global place.</summary>
    private static Vector3 Carried(Vector3 local) => BoneNow.TransformPoint(BoneThen.InverseTransformPoint(Vector3.Transform(local, NodeGlobal)));

    [Fact]
    public void A_capsule_keeps_its_place_on_the_bone_and_its_scaled_size()
    {
        var shape = new PrimitiveShape(ColliderKind.Capsule, new Vector3(0.04f, 0.1f, 0f));
        var offset = ColliderFollowMath.OffsetIn(NodeGlobal, BoneThen);
        // Placed at the frame it was taken in: where the node is.
        var there = ColliderFollowMath.Place(shape, offset, BoneThen);
        AssertClose(Vector3.Transform(new Vector3(0f, -0.1f, 0f), NodeGlobal), there.Center);
        AssertClose(Vector3.Transform(new Vector3(0f, 0.1f, 0f), NodeGlobal), there.End);
        var now = ColliderFollowMath.Place(shape, offset, BoneNow);
        Assert.True(now.InWorld);
        Assert.Equal(ColliderKind.Capsule, now.Kind);
        AssertClose(Carried(new Vector3(0f, -0.1f, 0f)), now.Center);
        AssertClose(Carried(new Vector3(0f, 0.1f, 0f)), now.End);
        Assert.Equal(0.06f, now.Radius, 5); // 4 cm × the node's 1.5 scale
        Assert.Equal(0.3f, Vector3.Distance(now.Center, now.End), 4);
    }

    [Fact]
    public void Spheres_and_ellipsoids_follow_too_and_the_ellipsoid_turns_with_the_bone()
    {
        var offset = ColliderFollowMath.OffsetIn(NodeGlobal, BoneThen);
        var sphere = ColliderFollowMath.Place(new PrimitiveShape(ColliderKind.Sphere, new Vector3(0.05f, 0f, 0f)), offset, BoneNow);
        AssertClose(Carried(Vector3.Zero), sphere.Center);
        Assert.Equal(0.075f, sphere.Radius, 5);
        var radii = new Vector3(0.08f, 0.1f, 0.09f);
        var ellipsoid = ColliderFollowMath.Place(new PrimitiveShape(ColliderKind.Ellipsoid, radii), offset, BoneNow);
        AssertClose(Carried(Vector3.Zero), ellipsoid.Center);
        AssertClose(radii * 1.5f, ellipsoid.Radii);
        // The tip of each semi-axis lands where the bone carries the node's scaled axis.
        foreach (var axis in new[] { Vector3.UnitX, Vector3.UnitY, Vector3.UnitZ })
        {
            var r = Vector3.Dot(axis, radii);
            AssertClose(Carried(axis * r), ellipsoid.Center + Vector3.Transform(axis * r * 1.5f, ellipsoid.Rotation), 1e-5f);
        }
        Assert.Throws<ArgumentException>(() => ColliderFollowMath.Place(new PrimitiveShape(ColliderKind.Plane, Vector3.One), offset, BoneNow));
    }

    [Fact]
    public void A_shoulder_capsule_on_a_moving_bone_pushes_the_hair_without_a_rebuild_and_the_update_allocates_nothing()
    {
        // A settled groom; a shoulder capsule (along the bone's Y, turned to lie along X) follows a bone that swings in
        // from 20 cm beside the hair to a strand's tip and holds there, placed before every step as HairSystem3D does.
        var groom = new GroomSettings { SheetCount = 40, StrandsPerSheet = 8, ParticlesPerStrand = 12, StrandLength = 0.25f };
        var scene = GroomBuilder.BuildScene(groom, new SimulationSettings { Path = SolverPath.Fast });
        var sim = new HairSimulation(scene);
        for (int f = 0; f < 60; f++) sim.Step(1f / 60f);
        var w = scene.World;
        var target = w.GetPosition(w.TipIndex(w.SkeletonStrand(10)));
        var lying = Quaternion.CreateFromAxisAngle(Vector3.UnitZ, MathF.PI / 2);
        RigidTransform BoneAt(int f)
        {
            float s = MathF.Min(1f, f / 40f);
            return new RigidTransform(target + new Vector3(0f, 0f, 0.2f * (1f - s)), Quaternion.CreateFromYawPitchRoll(0.5f * s, 0f, 0f));
        }
        var shape = new PrimitiveShape(ColliderKind.Capsule, new Vector3(0.025f, 0.05f, 0f));
        var offset = ColliderFollowMath.OffsetIn(Godot(lying, Vector3.One, BoneAt(0).Position), BoneAt(0)); // the node on the bone's origin
        scene.AddCollider(ColliderFollowMath.Place(shape, offset, BoneAt(0)));
        int index = scene.Colliders.Count - 1, revision = scene.Revision;
        var pipeline = sim.Pipeline;
        float deepest = 0f, nearest = float.MaxValue;
        var allocations = new UpdateAllocations();
        for (int f = 0; f <= 100; f++)
        {
            allocations.Begin();
            var capsule = ColliderFollowMath.Place(shape, offset, BoneAt(f));
            scene.SetCollider(index, capsule);
            allocations.End();
            sim.Step(1f / 60f);
            if (f < 40) continue;
            for (int i = 0; i < w.ParticleCount; i++)
            {
                if (w.InvMass[i] == 0f) continue;
                var p = w.GetPosition(i);
                deepest = MathF.Max(deepest, capsule.Penetration(p));
                var axis = capsule.End - capsule.Center;
                float t = Math.Clamp(Vector3.Dot(p - capsule.Center, axis) / axis.LengthSquared(), 0f, 1f);
                nearest = MathF.Min(nearest, Vector3.Distance(p, capsule.Center + t * axis) - capsule.Radius);
            }
        }
        allocations.AssertNonePerUpdate();
        Assert.Same(pipeline, sim.Pipeline);
        Assert.Equal(revision, scene.Revision);
        Assert.Equal(0, w.CountNonFinite());
        Assert.True(nearest < 0.003f, $"no hair came within 3 mm of the capsule (nearest {nearest * 1000:F1} mm): the test sees nothing");
        Assert.True(deepest < 0.001f, $"a particle is {deepest * 1000:F2} mm inside the capsule the bone carried in");
    }
}
