using System.Numerics;

namespace HairSim.Tests.Core;

public class HeadFollowTests
{
    [Fact]
    public void RootsMatchTheHeadTransformExactlyAfterItMovesAndRotates()
    {
        var scene = GroomBuilder.BuildScene(TestWorlds.SmallGroom(), TestWorlds.Settings());
        var w = scene.World;
        var sim = new HairSimulation(scene);
        for (int f = 1; f <= 40; f++)
        {
            var head = new RigidTransform(new Vector3(0.01f * f, 0.005f * f, -0.002f * f),
                Quaternion.CreateFromYawPitchRoll(0.02f * f, 0.01f * f, -0.015f * f));
            sim.Step(1f / 60f, head);
            Assert.Equal(head, w.Head);
            for (int i = 0; i < w.ParticleCount; i++)
            {
                if (w.InvMass[i] != 0f) continue;
                Assert.Equal(head.TransformPoint(w.GetRest(i)), w.GetPosition(i));
            }
        }
    }

    [Fact]
    public void TeleportCarriesTheHairRigidlyAndLeavesEveryValueFinite()
    {
        foreach (var mode in new[] { ShapeMatchMode.Muller, ShapeMatchMode.LiteralForce })
        foreach (var length in new[] { LengthMode.FollowTheLeader, LengthMode.None })
        {
            HairScene Make() => GroomBuilder.BuildScene(TestWorlds.SmallGroom(), TestWorlds.Settings(s => { s.Mode = mode; s.Length = length; }));
            var stay = Make(); var jump = Make();
            var simStay = new HairSimulation(stay); var simJump = new HairSimulation(jump);
            for (int f = 0; f < 30; f++) { simStay.Step(1f / 60f); simJump.Step(1f / 60f); }
            // 100 m away and turned around (about the vertical, so gravity acts the same) in one frame.
            var far = new RigidTransform(new Vector3(100, -40, 60), Quaternion.CreateFromAxisAngle(Vector3.UnitY, MathF.PI));
            for (int f = 0; f < 20; f++) { simStay.Step(1f / 60f); simJump.Step(1f / 60f, far); }
            Assert.True(simJump.Pipeline.LastFrame.Teleported == false);
            Assert.Equal(0, jump.World.CountNonFinite());
            // The teleported hair moves exactly as the hair that stayed, carried by the jump.
            for (int i = 0; i < jump.World.ParticleCount; i++)
            {
                var expected = far.TransformPoint(stay.World.GetPosition(i));
                Assert.True(Vector3.Distance(expected, jump.World.GetPosition(i)) < 1e-3f, $"{mode}/{length}: particle {i}");
            }
            Assert.Equal(WorldMetrics.Measure(stay).MaxEdgeStretch, WorldMetrics.Measure(jump).MaxEdgeStretch, 2);
            Assert.Equal(0, WorldMetrics.Measure(jump).ParticlesInside);
        }
    }

    [Fact]
    public void TeleportFrameIsDetected()
    {
        var scene = GroomBuilder.BuildScene(TestWorlds.SmallGroom(), TestWorlds.Settings());
        var sim = new HairSimulation(scene);
        sim.Step(1f / 60f, new RigidTransform(new Vector3(0, 10, 0), Quaternion.Identity));
        Assert.True(sim.Pipeline.LastFrame.Teleported);
        Assert.Equal(0, scene.World.CountNonFinite());
    }

    [Fact]
    public void SmallHeadMotionIsNotATeleport()
    {
        var scene = GroomBuilder.BuildScene(TestWorlds.SmallGroom(), TestWorlds.Settings());
        var sim = new HairSimulation(scene);
        sim.Step(1f / 60f, new RigidTransform(new Vector3(0.05f, 0, 0), Quaternion.CreateFromAxisAngle(Vector3.UnitY, 0.2f)));
        Assert.False(sim.Pipeline.LastFrame.Teleported);
    }
}
