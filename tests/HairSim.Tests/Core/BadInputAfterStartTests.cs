using System.Numerics;

namespace HairSim.Tests.Core;

/// <summary>
/// Bad values that reach a running scene (a setter after the first step, a buffer written by hand, a head pose)
/// are refused with an exception before anything changes, on both paths, and the scene steps on once they are
/// put right: never NaN spreading through the hair, never a frozen scene.
/// </summary>
public class BadInputAfterStartTests
{
    private static (HairScene Scene, HairSimulation Sim) Running(SolverPath path)
    {
        var scene = GroomBuilder.BuildScene(new GroomSettings { SheetCount = 6, StrandsPerSheet = 4, ParticlesPerStrand = 10 }, new SimulationSettings { Path = path });
        var sim = new HairSimulation(scene);
        for (int f = 0; f < 5; f++) sim.Step(1f / 60f);
        return (scene, sim);
    }

    public static TheoryData<string, SolverPath> Cases()
    {
        var d = new TheoryData<string, SolverPath>();
        foreach (var path in new[] { SolverPath.Reference, SolverPath.Fast })
            foreach (var c in new[] { "gravity-nan", "alpha-nan", "substeps-0", "damping-inf", "rest-nan", "restlength-nan", "invmass-negative", "head-nan" })
                d.Add(c, path);
        return d;
    }

    [Theory]
    [MemberData(nameof(Cases))]
    public void RefusedBeforeAnythingChangesAndTheSceneStepsOnOnceRepaired(string bad, SolverPath path)
    {
        var (scene, sim) = Running(path);
        var w = scene.World;
        var st = scene.Settings;
        var head = RigidTransform.Identity;
        Action repair = () => { };
        switch (bad)
        {
            case "gravity-nan": { var g = st.Gravity; st.Gravity = new Vector3(0, float.NaN, 0); repair = () => st.Gravity = g; break; }
            case "alpha-nan": { var a = st.Alpha; st.Alpha = float.NaN; repair = () => st.Alpha = a; break; }
            case "substeps-0": { st.Guards = false; st.Substeps = 0; repair = () => st.Substeps = 4; break; }
            case "damping-inf": { var d = st.Damping; st.Damping = float.PositiveInfinity; repair = () => st.Damping = d; break; }
            case "rest-nan": { float x = w.RestX[0]; w.RestX[0] = float.NaN; w.MarkEdited(); repair = () => { w.RestX[0] = x; w.MarkEdited(); }; break; }
            case "restlength-nan": { float l = w.RestLength[3]; w.RestLength[3] = float.NaN; w.MarkEdited(); repair = () => { w.RestLength[3] = l; w.MarkEdited(); }; break; }
            case "invmass-negative": { float m = w.InvMass[4]; w.InvMass[4] = -1f; w.MarkEdited(); repair = () => { w.InvMass[4] = m; w.MarkEdited(); }; break; }
            case "head-nan": head = default; break; // a zero rotation: the constructor refuses NaN, a default value bypasses it
        }
        var before = w.Clone();
        Assert.ThrowsAny<ArgumentException>(() => sim.Step(1f / 60f, head));
        Assert.True(w.BitEquals(before), $"{bad}: the refused frame changed the world");
        repair();
        var moving = w.Clone();
        sim.Step(1f / 60f, RigidTransform.Identity);
        sim.Step(1f / 60f, new RigidTransform(new Vector3(0.01f, 0, 0), Quaternion.Identity));
        Assert.Equal(0, w.CountNonFinite());
        Assert.False(w.BitEquals(moving), $"{bad}: the scene did not step on after the repair");
    }

    [Fact]
    public void NonFinitePositionsAndVelocitiesAreRefusedByTheSetters()
    {
        var (scene, _) = Running(SolverPath.Fast);
        var w = scene.World;
        var before = w.Clone();
        Assert.Throws<ArgumentException>(() => w.SetPosition(5, new Vector3(float.NaN, 0, 0)));
        Assert.Throws<ArgumentException>(() => w.SetPosition(5, new Vector3(0, float.PositiveInfinity, 0)));
        Assert.Throws<ArgumentException>(() => w.SetVelocity(5, new Vector3(0, 0, float.NegativeInfinity)));
        Assert.True(w.BitEquals(before));
        w.SetPosition(5, new Vector3(0.01f, 0.02f, 0.03f));
        Assert.Equal(new Vector3(0.01f, 0.02f, 0.03f), w.GetPosition(5));
    }
}
