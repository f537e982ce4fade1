using System.Numerics;
using HairSim;
using Xunit.Abstractions;

namespace HairSim.Tests.Fast;

/// <summary>
/// The fallbacks of the reference, hit on purpose, must match on the fast path: coincident neighbours in
/// follow-the-leader and PBD, a triple whose ends coincide in shape matching, and particles exactly at a
/// sphere's or ellipsoid's centre or on a capsule's axis.
/// </summary>
public class FastDegenerateCaseTests(ITestOutputHelper output)
{
    private static HairScene Build(SolverPath path, LengthMode length, float globalShape, BendModel bend)
    {
        var w = new HairWorld(2, 8, 16);
        for (int s = 0; s < w.StrandCount; s++)
        {
            var pts = new Vector3[16];
            for (int k = 0; k < 16; k++) pts[k] = new Vector3(0.05f * s, 0.3f - 0.015f * k, 0.01f * (s % 3));
            w.SetStrand(s, pts, pinned: 1, straightRestShape: s % 2 == 0);
        }
        // Strand 0: particle 5 on top of particle 4 (zero-length edge), particle 9 on top of particle 7 (triple 8's ends coincide).
        w.SetPosition(5, w.GetPosition(4));
        w.SetPosition(9, w.GetPosition(7));
        // Strand 2 (straight, not the first in the world): triple 5's ends coincide (the 16-lane path's register-only case hands it on).
        int f2 = w.StrandFirst[2];
        w.SetPosition(f2 + 6, w.GetPosition(f2 + 4));
        // Strand 3 (bent rest shape): the same, in a bent strand.
        int f3 = w.StrandFirst[3];
        w.SetPosition(f3 + 11, w.GetPosition(f3 + 9));
        var st = new SimulationSettings { Path = path, Substeps = 1, Length = length, GlobalShapeStiffness = globalShape, Bend = bend };
        var scene = new HairScene(w, st);
        // Particle 8 of strands 4, 5 and 6 sits exactly at a sphere centre, on a capsule axis, at an ellipsoid centre.
        var p4 = w.GetPosition(w.StrandFirst[4] + 8);
        var p5 = w.GetPosition(w.StrandFirst[5] + 8);
        var p6 = w.GetPosition(w.StrandFirst[6] + 8);
        scene.AddCollider(Collider.Sphere(p4, 0.004f));
        scene.AddCollider(Collider.Capsule(p5 - new Vector3(0.01f, 0, 0), p5 + new Vector3(0.01f, 0, 0), 0.004f));
        scene.AddCollider(Collider.Ellipsoid(p6, new Vector3(0.004f, 0.005f, 0.006f), Quaternion.CreateFromYawPitchRoll(0.4f, 0.1f, 0.2f)));
        return scene;
    }

    [Theory]
    [InlineData(ShapeMatchSystem.SystemName, LengthMode.FollowTheLeader, 0.02f)]
    [InlineData(ShapeMatchSystem.SystemName, LengthMode.FollowTheLeader, 0f)] // no global pull: the 16-lane path where available
    [InlineData(LengthSystem.SystemName, LengthMode.FollowTheLeader, 0.02f)]
    [InlineData(LengthSystem.SystemName, LengthMode.Pbd, 0.02f)]
    [InlineData(CollideSystem.SystemName, LengthMode.FollowTheLeader, 0.02f)]
    [InlineData("frame", LengthMode.FollowTheLeader, 0.02f)]
    [InlineData("frame", LengthMode.FollowTheLeader, 0f)]
    [InlineData("frame", LengthMode.Pbd, 0.02f)]
    // The default bend model: the sweep's own fallbacks (zero-length segment, target along the rest direction).
    [InlineData(BendSystem.SystemName, LengthMode.FollowTheLeader, 0f)]
    [InlineData("frame-rest", LengthMode.FollowTheLeader, 0.02f)]
    [InlineData("frame-rest", LengthMode.FollowTheLeader, 0f)]
    public void FallbacksMatchReference(string system, LengthMode length, float globalShape)
    {
        var bend = system is BendSystem.SystemName or "frame-rest" ? BendModel.RestShape : BendModel.SourceTriples;
        var reference = Build(SolverPath.Reference, length, globalShape, bend);
        var fast = Build(SolverPath.Fast, length, globalShape, bend);
        var before = reference.World.Clone();
        var builder = PipelineBuilder.CreateDefault();
        if (system is not ("frame" or "frame-rest"))
        {
            builder = new PipelineBuilder();
            foreach (var f in PipelineBuilder.CreateDefault().Factories) if (f.Name == system) builder.Add(f);
        }
        var pr = builder.Build(reference);
        var pf = builder.Build(fast, new ParallelDispatcher(2));
        pr.Step(1f / 60f, RigidTransform.Identity);
        pf.Step(1f / 60f, RigidTransform.Identity);
        float dx = FastPathScenes.MaxPositionDifference(reference.World, fast.World);
        float dv = FastPathScenes.MaxVelocityDifference(reference.World, fast.World);
        float moved = FastPathScenes.MaxPositionDifference(before, reference.World);
        float vmax = 0f;
        for (int i = 0; i < reference.World.ParticleCount; i++) vmax = MathF.Max(vmax, reference.World.GetVelocity(i).Length());
        output.WriteLine($"{system}/{length}: |Δx| {dx:E2} m (moved {moved:E2}), |Δv| {dv:E2} m/s (max |v| {vmax:E2})");
        Assert.Equal(0, fast.World.CountNonFinite());
        // A fallback that was skipped or taken differently changes a particle by millimetres / metres per second.
        Assert.True(dx <= 1e-6f, $"positions differ by {dx:E3} m");
        Assert.True(dv <= 1e-5f * MathF.Max(1f, vmax) + 5e-4f, $"velocities differ by {dv:E3} m/s");
        if (system is CollideSystem.SystemName or LengthSystem.SystemName or BendSystem.SystemName) Assert.True(moved > 1e-3f, "the degenerate particles were moved");
    }
}
