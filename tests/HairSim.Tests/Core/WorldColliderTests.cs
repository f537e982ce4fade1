using System.Numerics;
using HairSim.IO;
using Xunit;

namespace HairSim.Tests.Core;

/// <summary>Colliders fixed in the world (<see cref="Collider.InWorldSpace"/>): the head's motion does not move them.</summary>
public class WorldColliderTests
{
    [Fact]
    public void A_world_collider_stays_where_it_is_and_a_head_collider_moves_with_the_head()
    {
        var head = new RigidTransform(new Vector3(0.1f, 0.2f, -0.3f), Quaternion.CreateFromYawPitchRoll(0.4f, 0.1f, 0f));
        var sphere = Collider.Sphere(new Vector3(0f, -0.3f, 0f), 0.05f);
        var fixedSphere = sphere.InWorldSpace();
        Assert.True(fixedSphere.InWorld);
        Assert.False(sphere.InWorld);
        Assert.Equal(sphere.Center, fixedSphere.ToWorld(head).Center);
        Assert.Equal(head.TransformPoint(sphere.Center), sphere.ToWorld(head).Center);
        var capsule = Collider.Capsule(new Vector3(-0.2f, -0.25f, 0f), new Vector3(0.2f, -0.25f, 0f), 0.04f).InWorldSpace();
        Assert.Equal(capsule.End, capsule.ToWorld(head).End);
    }

    [Theory]
    [InlineData(SolverPath.Reference)]
    [InlineData(SolverPath.Fast)]
    public void Hair_rests_on_a_bar_fixed_in_the_world_while_the_head_moves_away_from_it(SolverPath path)
    {
        // Limp strands hang from the head onto a horizontal bar fixed in the world 12 cm below the roots. The head then
        // slides 6 cm along the bar: the bar stays, the hair keeps out of it. The same bar attached to the head would have
        // moved with it (the control: its world position after the slide is 6 cm away).
        int strands = 8, n = 12;
        var w = new HairWorld(1, strands, n);
        var pts = new Vector3[n];
        for (int s = 0; s < strands; s++)
        {
            for (int k = 0; k < n; k++) pts[k] = new Vector3(-0.035f + 0.01f * s, -0.02f * k, 0.005f);
            w.SetStrand(s, pts, pinned: 1);
        }
        var bar = Collider.Capsule(new Vector3(-0.3f, -0.12f, 0f), new Vector3(0.3f, -0.12f, 0f), 0.01f).InWorldSpace();
        var scene = new HairScene(w, new SimulationSettings { Path = path, Bend = BendModel.Limp });
        scene.AddCollider(bar);
        var sim = new HairSimulation(scene);
        for (int f = 1; f <= 120; f++)
        {
            float x = 0.06f * Math.Min(1f, f / 60f);
            sim.Step(1f / 60, new RigidTransform(new Vector3(x, 0f, 0f), Quaternion.Identity));
        }
        Assert.Equal(0, w.CountNonFinite());
        float deepest = 0f;
        for (int i = 0; i < w.ParticleCount; i++)
        {
            var p = w.GetPosition(i);
            float dy = p.Y + 0.12f, dz = p.Z, d = MathF.Sqrt(dy * dy + dz * dz); // distance from the bar's axis
            if (MathF.Abs(p.X) < 0.3f) deepest = MathF.Max(deepest, 0.01f - d);
        }
        Assert.True(deepest < 1e-3f, $"a particle is {deepest * 1000:F2} mm inside the fixed bar");
        var metrics = WorldMetrics.Measure(scene);
        Assert.True(metrics.MaxPenetration < 1e-3, $"penetration {metrics.MaxPenetration}");
        // Hair hangs over the bar: some particle lies below the bar's axis (it draped over, not through).
        bool draped = false;
        for (int i = 0; i < w.ParticleCount; i++) draped |= w.GetPosition(i).Y < -0.14f;
        Assert.True(draped, "the strands reach past the bar");
        var attached = Collider.Capsule(new Vector3(-0.3f, -0.12f, 0f), new Vector3(0.3f, -0.12f, 0f), 0.01f);
        Assert.Equal(0.06f, attached.ToWorld(w.Head).Center.X - bar.ToWorld(w.Head).Center.X, 4);
    }

    [Fact]
    public void A_hairstyle_file_keeps_which_colliders_are_fixed_in_the_world()
    {
        var scene = GroomBuilder.BuildScene(new GroomSettings { SheetCount = 6, StrandsPerSheet = 3, ParticlesPerStrand = 8 });
        scene.AddCollider(Collider.Sphere(new Vector3(0f, -0.5f, 0f), 0.2f).InWorldSpace());
        string path = Path.Combine(Path.GetTempPath(), $"world-collider-{Guid.NewGuid():N}.hairstyle");
        try
        {
            HairstyleFile.Save(scene, path);
            var loaded = HairstyleFile.Load(path);
            Assert.Equal(scene.Colliders.Count, loaded.Colliders.Count);
            for (int c = 0; c < scene.Colliders.Count; c++)
            {
                Assert.Equal(scene.Colliders[c].InWorld, loaded.Colliders[c].InWorld);
                Assert.Equal(scene.Colliders[c].Center, loaded.Colliders[c].Center);
            }
            Assert.Contains(loaded.Colliders, c => c.InWorld);
            Assert.Contains(loaded.Colliders, c => !c.InWorld); // the head ellipsoid stays on the head
        }
        finally { File.Delete(path); }
    }
}
