using System.Buffers.Binary;
using System.Numerics;
using HairSim.Editing;
using HairSim.IO;

namespace HairSim.Tests.Core;

/// <summary>
/// The plane collider (<see cref="ColliderKind.Plane"/>): a point and a normal, the half-space below solid; on the head
/// or fixed in the world; both collision paths; kept by hairstyle files; bad values refused.
/// </summary>
public class PlaneColliderTests
{
    [Fact]
    public void A_point_below_the_plane_goes_straight_up_to_it()
    {
        var plane = Collider.Plane(new Vector3(0f, -0.1f, 0f), new Vector3(0f, 2f, 0f));
        Assert.Equal(Vector3.UnitY, plane.Normal);
        Assert.True(plane.Resolve(new Vector3(0.3f, -0.13f, 0.2f), out var surface, out var normal, out float depth));
        Assert.Equal(new Vector3(0.3f, -0.1f, 0.2f), surface);
        Assert.Equal(Vector3.UnitY, normal);
        Assert.Equal(0.03f, depth, 6);
        Assert.False(plane.Resolve(new Vector3(5f, -0.099f, -7f), out _, out _, out _));
        // Tilted: the surface point is the orthogonal projection (on the plane, the move along the normal).
        var n = Vector3.Normalize(new Vector3(1f, 2f, -0.5f));
        var tilted = Collider.Plane(new Vector3(0.1f, 0f, 0f), n);
        var p = new Vector3(0.05f, -0.2f, 0.1f);
        Assert.True(tilted.Resolve(p, out surface, out _, out depth));
        Assert.Equal(0f, Vector3.Dot(surface - tilted.Center, n), 6);
        Assert.Equal(0f, Vector3.Cross(surface - p, n).Length(), 6);
        Assert.Equal(-Vector3.Dot(p - tilted.Center, n), depth, 6);
    }

    [Fact]
    public void A_plane_on_the_head_turns_and_moves_with_it_and_one_in_the_world_stays()
    {
        var head = new RigidTransform(new Vector3(0.1f, 0.5f, 0f), Quaternion.CreateFromAxisAngle(Vector3.UnitZ, MathF.PI / 2));
        var plane = Collider.Plane(new Vector3(0f, -0.1f, 0f), Vector3.UnitY);
        var placed = plane.ToWorld(head);
        Assert.Equal(head.TransformPoint(plane.Center), placed.Center);
        Assert.True(Vector3.Distance(new Vector3(-1f, 0f, 0f), placed.Normal) < 1e-6f, $"{placed.Normal}");
        var world = plane.InWorldSpace();
        Assert.Equal(world.Center, world.ToWorld(head).Center);
        Assert.Equal(world.Normal, world.ToWorld(head).Normal);
        // The editor's ray test sees it (a ray from above hits at the height over the plane).
        Assert.True(ColliderRay.Intersect(world, new Vector3(0f, 0.4f, 0f), -Vector3.UnitY, out float t));
        Assert.Equal(0.5f, t, 5);
        Assert.False(ColliderRay.Intersect(world, new Vector3(0f, 0.4f, 0f), Vector3.UnitY, out _));
    }

    /// <summary>Limp strands start horizontal at their roots and fall onto a floor fixed in the world 10 cm below.</summary>
    private static HairSimulation Floor(SolverPath path, out HairScene scene, bool headPlane = false)
    {
        const int strands = 6, n = 16;
        const float segment = 0.015f;
        var w = new HairWorld(1, strands, n);
        var rest = new Vector3[n];
        var start = new Vector3[n];
        var tilt = Vector3.Normalize(new Vector3(0.15f, -1f, 0.05f));
        for (int s = 0; s < strands; s++)
        {
            var root = new Vector3(0f, 0f, 0.02f * s);
            for (int k = 0; k < n; k++) { rest[k] = root + tilt * (segment * k); start[k] = root + new Vector3(segment * k, 0f, 0f); }
            w.SetStrand(s, rest, start, pinned: 1);
        }
        scene = new HairScene(w, new SimulationSettings { Path = path, Bend = BendModel.Limp, Damping = 1f });
        var floor = Collider.Plane(new Vector3(0f, -0.1f, 0f), Vector3.UnitY);
        scene.AddCollider(headPlane ? floor : floor.InWorldSpace());
        return new HairSimulation(scene);
    }

    [Theory]
    [InlineData(SolverPath.Reference)]
    [InlineData(SolverPath.Fast)]
    public void Hair_falls_onto_a_floor_plane_and_rests_on_it(SolverPath path)
    {
        var sim = Floor(path, out var scene);
        var w = scene.World;
        for (int f = 0; f < 180; f++) sim.Step(1f / 60f);
        var settled = w.Clone();
        for (int f = 0; f < 60; f++) sim.Step(1f / 60f);
        Assert.Equal(0, w.CountNonFinite());
        int onFloor = 0;
        float lowest = float.MaxValue, moved = 0f, worstLength = 0f;
        for (int s = 0; s < w.StrandCount; s++)
            for (int k = 0; k < w.StrandParticleCount[s]; k++)
            {
                int i = w.StrandFirst[s] + k;
                var p = w.GetPosition(i);
                lowest = MathF.Min(lowest, p.Y);
                if (p.Y < -0.098f) onFloor++;
                moved = MathF.Max(moved, Vector3.Distance(p, settled.GetPosition(i)));
                if (k > 0) worstLength = MathF.Max(worstLength, MathF.Abs(Vector3.Distance(p, w.GetPosition(i - 1)) / w.RestLength[i] - 1f));
            }
        // 22.5 cm strands from 10 cm above the floor: the lower ~8 particles of each lie on it, none below it.
        Assert.True(lowest > -0.1f - 1e-5f, $"a particle is {(-0.1f - lowest) * 1000:F3} mm below the floor");
        Assert.InRange(onFloor, 6 * 6, 6 * 10);
        // At rest: nothing moved by a tenth of a millimetre in the last second. (Velocities are not the measure: follow-the-
        // leader's damping term leaves a constant velocity on the particle below the root of a resting strand.)
        Assert.True(moved < 1e-4f, $"a particle moved {moved * 1000:F3} mm in the last second");
        // Collision runs after the length pass, so where a strand bends onto the floor a segment is pushed off its length
        // by a fraction of a substep's fall (0.75 % here); never more than 1 %.
        Assert.True(worstLength < 1e-2f, $"a segment is {worstLength:P3} off its rest length");
        Assert.True(WorldMetrics.Measure(scene).MaxPenetration < 1e-5, "penetration");
    }

    [Fact]
    public void Both_paths_lay_the_hair_on_the_floor_the_same_way()
    {
        var reference = Floor(SolverPath.Reference, out var a);
        var fast = Floor(SolverPath.Fast, out var b);
        float worst = 0f;
        for (int f = 0; f < 240; f++)
        {
            reference.Step(1f / 60f);
            fast.Step(1f / 60f);
            for (int i = 0; i < a.World.ParticleCount; i++) worst = MathF.Max(worst, Vector3.Distance(a.World.GetPosition(i), b.World.GetPosition(i)));
        }
        // Float against double through a fall, a landing and a slide: within a millimetre (a tenth of a segment) all the way.
        Assert.True(worst < 1e-3f, $"the paths differ by {worst * 1000:F3} mm");
    }

    [Theory]
    [InlineData(SolverPath.Reference)]
    [InlineData(SolverPath.Fast)]
    public void A_floor_on_the_head_sinks_with_it_and_one_in_the_world_holds_the_hair_up(SolverPath path)
    {
        // The head drops 5 cm: hair on a world floor piles up on it; with the floor on the head it drops along.
        var down = new RigidTransform(new Vector3(0f, -0.05f, 0f), Quaternion.Identity);
        var world = Floor(path, out var ws);
        var onHead = Floor(path, out var hs, headPlane: true);
        for (int f = 0; f < 180; f++) { world.Step(1f / 60f, down); onHead.Step(1f / 60f, down); }
        float lowestWorld = float.MaxValue, lowestHead = float.MaxValue;
        for (int i = 0; i < ws.World.ParticleCount; i++) { lowestWorld = MathF.Min(lowestWorld, ws.World.PosY[i]); lowestHead = MathF.Min(lowestHead, hs.World.PosY[i]); }
        Assert.True(MathF.Abs(lowestWorld + 0.1f) < 1e-3f, $"world floor: lowest particle at {lowestWorld}");
        Assert.True(MathF.Abs(lowestHead + 0.15f) < 1e-3f, $"head floor: lowest particle at {lowestHead}");
    }

    [Fact]
    public void A_hairstyle_file_keeps_planes_on_the_head_and_in_the_world()
    {
        var scene = GroomBuilder.BuildScene(new GroomSettings { SheetCount = 4, StrandsPerSheet = 3, ParticlesPerStrand = 8 });
        scene.AddCollider(Collider.Plane(new Vector3(0f, -0.3f, 0f), new Vector3(0.1f, 1f, 0f)));
        scene.AddCollider(Collider.Plane(new Vector3(0.2f, -0.5f, 0.1f), Vector3.UnitY).InWorldSpace());
        using var ms = new MemoryStream();
        HairstyleFile.Save(scene, ms);
        var data = ms.ToArray();
        Assert.Equal(HairstyleFile.Version, BinaryPrimitives.ReadInt32LittleEndian(data.AsSpan(8)));
        var loaded = HairstyleFile.Load(data);
        Assert.Equal(scene.Colliders.Count, loaded.Colliders.Count);
        for (int c = 0; c < scene.Colliders.Count; c++)
        {
            Assert.Equal(scene.Colliders[c].Kind, loaded.Colliders[c].Kind);
            Assert.Equal(scene.Colliders[c].Center, loaded.Colliders[c].Center);
            Assert.Equal(scene.Colliders[c].Normal, loaded.Colliders[c].Normal);
            Assert.Equal(scene.Colliders[c].InWorld, loaded.Colliders[c].InWorld);
        }
        Assert.Equal(2, loaded.Colliders.Count(c => c.Kind == ColliderKind.Plane));
        // A file that says version 2 cannot hold a plane: refused with a clear message, as a corrupt file is.
        BinaryPrimitives.WriteInt32LittleEndian(data.AsSpan(8), 2);
        BinaryPrimitives.WriteUInt32LittleEndian(data.AsSpan(data.Length - 4), Crc32.Compute(data.AsSpan(0, data.Length - 4)));
        Assert.Contains("unknown kind", Assert.Throws<InvalidDataException>(() => HairstyleFile.Load(data)).Message);
    }

    public static TheoryData<string> BadPlanes() => new() { "point-nan", "point-inf", "normal-zero", "normal-tiny", "normal-nan", "normal-inf" };

    [Theory]
    [MemberData(nameof(BadPlanes))]
    public void Bad_planes_are_refused_and_the_scene_is_unchanged(string bad)
    {
        var scene = GroomBuilder.BuildScene(new GroomSettings { SheetCount = 4, StrandsPerSheet = 3, ParticlesPerStrand = 8 });
        var sim = new HairSimulation(scene);
        sim.Step(1f / 60f);
        var before = scene.World.Clone();
        int colliders = scene.Colliders.Count, revision = scene.Revision;
        Vector3 point = new(0f, -0.2f, 0f), normal = Vector3.UnitY;
        switch (bad)
        {
            case "point-nan": point.Y = float.NaN; break;
            case "point-inf": point.X = float.NegativeInfinity; break;
            case "normal-zero": normal = Vector3.Zero; break;
            case "normal-tiny": normal = new Vector3(0f, 1e-9f, 0f); break;
            case "normal-nan": normal = new Vector3(0f, float.NaN, 0f); break;
            case "normal-inf": normal = new Vector3(float.PositiveInfinity, 1f, 0f); break;
        }
        var e = Assert.ThrowsAny<ArgumentException>(() => scene.AddCollider(Collider.Plane(point, normal)));
        Assert.Contains(bad.StartsWith("point") ? "point" : "normal", e.Message);
        Assert.Equal(colliders, scene.Colliders.Count);
        Assert.Equal(revision, scene.Revision);
        Assert.True(scene.World.BitEquals(before));
        sim.Step(1f / 60f);
        Assert.Equal(0, scene.World.CountNonFinite());
    }
}
