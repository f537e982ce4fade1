using System.Numerics;

namespace HairSim.Tests.Core;

public class CollideTests
{
    [Fact]
    public void EllipsoidPushesRadiallyToTheSurfaceAsTheSourceDoes()
    {
        var c = Collider.Ellipsoid(Vector3.Zero, new Vector3(1, 2, 1));
        Assert.True(c.Resolve(new Vector3(0, 0.5f, 0), out var s, out var n, out var depth));
        Assert.Equal(new Vector3(0, 2, 0), s);
        Assert.Equal(Vector3.UnitY, n);
        Assert.Equal(1.5f, depth, 5);
        // Off-axis: the surface point lies on the ray from the centre through p.
        var p = new Vector3(0.3f, 0.4f, 0.1f);
        Assert.True(c.Resolve(p, out s, out _, out _));
        Assert.Equal(1f, s.X * s.X + s.Y * s.Y / 4 + s.Z * s.Z, 4);
        Assert.True(Vector3.Cross(Vector3.Normalize(s), Vector3.Normalize(p)).Length() < 1e-5f);
        Assert.False(c.Resolve(new Vector3(0, 2.1f, 0), out _, out _, out _));
    }

    [Fact]
    public void ParticleExactlyAtTheCentreIsHandledWithoutNaN()
    {
        foreach (var c in new[]
                 {
                     Collider.Ellipsoid(Vector3.One, new Vector3(1, 2, 3)), Collider.Sphere(Vector3.One, 0.5f),
                     Collider.Capsule(Vector3.One, Vector3.One, 0.5f), Collider.Capsule(Vector3.One, new Vector3(1, 2, 1), 0.5f),
                 })
        {
            Assert.True(c.Resolve(Vector3.One, out var s, out var n, out var d));
            Assert.True(float.IsFinite(s.X) && float.IsFinite(s.Y) && float.IsFinite(s.Z));
            Assert.Equal(1f, n.Length(), 5);
            Assert.True(d > 0);
            Assert.Equal(0f, c.Penetration(s), 4);
        }
    }

    [Fact]
    public void DegenerateCollidersAreRefusedWithClearErrors()
    {
        Assert.Throws<ArgumentOutOfRangeException>(() => Collider.Ellipsoid(Vector3.Zero, new Vector3(1, 0, 1)));
        Assert.Throws<ArgumentException>(() => Collider.Ellipsoid(new Vector3(float.NaN, 0, 0), Vector3.One));
        Assert.Throws<ArgumentOutOfRangeException>(() => Collider.Sphere(Vector3.Zero, float.NaN));
        Assert.Throws<ArgumentOutOfRangeException>(() => Collider.Capsule(Vector3.Zero, Vector3.One, -1f));
        Assert.Throws<ArgumentException>(() => Collider.Ellipsoid(Vector3.Zero, Vector3.One, new Quaternion(0, 0, 0, 0)));
    }

    /// <summary>Hair laid out horizontally above the head falls onto it; no particle is inside after any frame.</summary>
    [Theory]
    [InlineData(LengthMode.FollowTheLeader)]
    [InlineData(LengthMode.None)]
    public void HeadDropLeavesNoParticleInsideTheEllipsoid(LengthMode length)
    {
        var radii = new Vector3(0.078f, 0.1f, 0.095f);
        int strands = 24, n = 12;
        var w = new HairWorld(1, strands, n);
        var pts = new Vector3[n];
        for (int s = 0; s < strands; s++)
        {
            float a = 2 * MathF.PI * s / strands;
            var dir = new Vector3(MathF.Cos(a), 0, MathF.Sin(a));
            var root = new Vector3(0, 0.13f, 0) + dir * 0.02f;
            for (int k = 0; k < n; k++) pts[k] = root + dir * (0.02f * k);
            w.SetStrand(s, pts, pinned: 1, straightRestShape: true);
        }
        var scene = new HairScene(w, TestWorlds.Settings(s => s.Length = length));
        scene.AddCollider(Collider.Ellipsoid(Vector3.Zero, radii));
        var sim = new HairSimulation(scene);
        bool touched = false;
        for (int f = 0; f < 180; f++)
        {
            sim.Step(1f / 60f);
            var m = WorldMetrics.Measure(scene);
            Assert.Equal(0, m.ParticlesInside);
            Assert.Equal(0, m.NonFinite);
            for (int i = 0; i < w.ParticleCount && !touched; i++)
            {
                var p = w.GetPosition(i);
                touched = p.X * p.X / (radii.X * radii.X) + p.Y * p.Y / (radii.Y * radii.Y) + p.Z * p.Z / (radii.Z * radii.Z) < 1.0001f && w.InvMass[i] > 0;
            }
        }
        Assert.True(touched, "the hair reached the head");
    }

    [Fact]
    public void HeadMovingUpIntoHangingHairLeavesNothingInside()
    {
        var g = TestWorlds.SmallGroom();
        var scene = GroomBuilder.BuildScene(g, TestWorlds.Settings());
        var sim = new HairSimulation(scene);
        for (int f = 0; f < 60; f++)
        {
            // Fast bob and turn of the head, within teleport limits.
            float t = f / 60f;
            var head = new RigidTransform(new Vector3(0, 0.05f * MathF.Sin(12 * t), 0), Quaternion.CreateFromAxisAngle(Vector3.UnitY, 0.8f * MathF.Sin(9 * t)));
            sim.Step(1f / 60f, head);
            var m = WorldMetrics.Measure(scene);
            Assert.Equal(0, m.ParticlesInside);
            Assert.Equal(0, m.NonFinite);
        }
    }

    [Fact]
    public void ParticlePushedTangentiallyKeepsSliding()
    {
        // A free tip (no shape matching, no length pass) resting on top of a sphere, pushed sideways.
        var w = new HairWorld(1, 1, 2);
        w.SetStrand(0, new[] { new Vector3(0, 5, 0), new Vector3(0, 1f, 0) }, pinned: 1, straightRestShape: true);
        w.SetVelocity(1, new Vector3(0.5f, 0, 0));
        var scene = new HairScene(w, TestWorlds.Settings(s => { s.Alpha = 0; s.Length = LengthMode.None; s.Damping = 0; s.Substeps = 4; }));
        scene.AddCollider(Collider.Sphere(Vector3.Zero, 1f));
        var sim = new HairSimulation(scene);
        float lastAngle = 0;
        for (int f = 0; f < 30; f++)
        {
            sim.Step(1f / 60f);
            var p = w.GetPosition(1);
            Assert.InRange(p.Length(), 0.9999f, 1.01f);        // on the surface, not inside, not flying off
            float angle = MathF.Atan2(p.X, p.Y);
            Assert.True(angle > lastAngle, $"frame {f}: still sliding forward ({angle} > {lastAngle})");
            lastAngle = angle;
        }
        Assert.True(w.GetVelocity(1).Length() >= 0.5f, "gravity along the slope speeds it up; sliding does not stop it");
    }
}
