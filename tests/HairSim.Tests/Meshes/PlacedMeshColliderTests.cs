using System.Numerics;
using HairSim.Fast;
using HairSim.Measurement;
using HairSim.Meshes;
using Xunit;

namespace HairSim.Tests.Meshes;

/// <summary>
/// Mesh colliders placed on the head or in the world (<see cref="MeshCollider.Placement"/>, <see cref="ColliderSpace"/>):
/// the pose they collide at, a world-space body the hair meets while the head moves (both paths' bits), refusals.
/// </summary>
public sealed class PlacedMeshColliderTests
{
    private static readonly SignedDistanceField Ball = SignedDistanceField.Bake(TriangleMesh.Ellipsoid(Vector3.Zero, new Vector3(0.02f), 24, 48), 0.002f);

    [Fact]
    public void PoseForComposesAHeadPlacementAndIgnoresTheHeadInWorldSpace()
    {
        var head = new RigidTransform(new Vector3(1, 2, 3), Quaternion.CreateFromYawPitchRoll(1.2f, 0.3f, -0.4f));
        var placement = new RigidTransform(new Vector3(0.1f, -0.05f, 0.02f), Quaternion.CreateFromYawPitchRoll(-0.5f, 0.2f, 0.1f));
        var onHead = new MeshCollider(Ball) { Placement = placement };
        var inWorld = new MeshCollider(Ball, space: ColliderSpace.World) { Placement = placement };
        Assert.Equal(head, new MeshCollider(Ball).PoseFor(head));   // the default: the field is in head space
        var v = new Vector3(0.03f, -0.01f, 0.02f);
        var expected = head.TransformPoint(placement.TransformPoint(v));
        Assert.True(Vector3.Distance(expected, onHead.PoseFor(head).TransformPoint(v)) < 1e-5f);
        Assert.Equal(placement.Position, inWorld.PoseFor(head).Position);
        Assert.True(Vector3.Distance(placement.TransformPoint(v), inWorld.PoseFor(head).TransformPoint(v)) < 1e-6f);
        Assert.Throws<ArgumentException>(() => inWorld.Placement = new RigidTransform(new Vector3(float.NaN, 0, 0), Quaternion.Identity));
        Assert.Throws<ArgumentException>(() => inWorld.Placement = new RigidTransform(Vector3.Zero, default));
        Assert.Throws<ArgumentOutOfRangeException>(() => new MeshCollider(Ball, space: (ColliderSpace)7));
    }

    [Fact]
    public void AWorldSpaceBodyStaysWhereItIsWhileTheHeadMovesAndHairRestsOnIt()
    {
        // A 2 cm ball fixed in the world where a settled strand's tip hangs; the head then moves 6 cm sideways and
        // shakes. The hair must stay out of the ball where it is in the world (not where the head took it), on the
        // chunk path and system by system alike.
        var groom = new GroomSettings { SheetCount = 40, StrandsPerSheet = 8 };
        HairScene Build() => GroomBuilder.BuildScene(groom, new SimulationSettings { Path = SolverPath.Fast });
        var settle = Build();
        var settling = new HairSimulation(settle);
        for (int f = 0; f < 60; f++) settling.Step(1f / 60f);
        var w0 = settle.World;
        var centre = w0.GetPosition(w0.TipIndex(w0.SkeletonStrand(10)));
        var scenes = new[] { Build(), Build() };
        var sims = new HairSimulation[2];
        for (int k = 0; k < 2; k++)
        {
            var collider = new MeshCollider(Ball, space: ColliderSpace.World) { Placement = new RigidTransform(centre, Quaternion.Identity) };
            scenes[k].SetComponent(collider);
            sims[k] = new HairSimulation(scenes[k]);
        }
        sims[1].Pipeline.UseStrandChunks = false;
        Assert.Equal(FastPathInfo.Avx512, sims[0].Pipeline.UsesStrandChunks);
        float deepest = 0f, nearest = float.MaxValue;
        for (int f = 1; f <= 150; f++)
        {
            var shake = HeadMotion.Shake(f / 60f);
            var head = new RigidTransform(new Vector3(0.06f * MathF.Min(1f, f / 60f), 0, 0), shake.Rotation);
            foreach (var sim in sims) sim.Step(1f / 60f, head);
            Assert.True(scenes[0].World.BitEquals(scenes[1].World), $"chunks and the system-by-system pass differ after frame {f}");
            var w = scenes[0].World;
            for (int i = 0; i < w.ParticleCount; i++)
            {
                if (w.InvMass[i] == 0f) continue;
                float r = Vector3.Distance(w.GetPosition(i), centre);
                deepest = MathF.Max(deepest, 0.02f - r);
                nearest = MathF.Min(nearest, r);
            }
        }
        Assert.Equal(0, scenes[0].World.CountNonFinite());
        Assert.True(nearest < 0.023f, $"no hair came within 3 mm of the ball (nearest {nearest * 1000:F1} mm from its centre): the test sees nothing");
        Assert.True(deepest < 0.001f, $"a particle is {deepest * 1000:F2} mm inside the world-space ball");
        Assert.True(WorldMetrics.Measure(scenes[0]).MaxPenetration < 0.001);
    }
}
