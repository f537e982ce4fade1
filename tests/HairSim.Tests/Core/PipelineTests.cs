using System.Numerics;

namespace HairSim.Tests.Core;

public class PipelineTests
{
    private static HairScene Scene(Action<SimulationSettings>? change = null) =>
        new(GroomBuilder.Build(TestWorlds.SmallGroom()), TestWorlds.Settings(change));

    [Fact]
    public void SceneWithoutColliderRunsNoCollisionSystem()
    {
        var scene = Scene();
        var sim = new HairSimulation(scene);
        Assert.DoesNotContain(CollideSystem.SystemName, sim.Pipeline.SystemNames);
        scene.AddCollider(Collider.Ellipsoid(Vector3.Zero, new Vector3(0.078f, 0.1f, 0.095f)));
        Assert.Contains(CollideSystem.SystemName, sim.Pipeline.SystemNames);
        scene.ClearColliders();
        Assert.DoesNotContain(CollideSystem.SystemName, sim.Pipeline.SystemNames);
    }

    [Fact]
    public void NothingToDrawMeansNoInterpolation()
    {
        var scene = Scene();
        var sim = new HairSimulation(scene);
        Assert.DoesNotContain(InterpolateSystem.SystemName, sim.Pipeline.SystemNames);
        Assert.Null(scene.RenderOutput);
        scene.Render = new RenderSettings { StrandsPerGap = 2 };
        Assert.Contains(InterpolateSystem.SystemName, sim.Pipeline.SystemNames);
        sim.Step(1f / 60f);
        Assert.NotNull(scene.RenderOutput);
        Assert.Equal(12 * (5 + 4 * 2), scene.RenderOutput!.StrandCount);
        scene.Render = null;
        Assert.DoesNotContain(InterpolateSystem.SystemName, sim.Pipeline.SystemNames);
    }

    [Fact]
    public void SettingsDecideShapeMatchAndLengthSystems()
    {
        var names = new HairSimulation(Scene(s => { s.Alpha = 0; s.Length = LengthMode.None; })).Pipeline.SystemNames;
        Assert.Equal(new[] { HeadFollowSystem.SystemName, IntegrateSystem.SystemName }, names);
        var full = GroomBuilder.BuildScene(TestWorlds.SmallGroom(), TestWorlds.Settings());
        full.Render = new RenderSettings();
        Assert.Equal(new[]
        {
            HeadFollowSystem.SystemName, ShapeMatchSystem.SystemName, IntegrateSystem.SystemName,
            LengthSystem.SystemName, CollideSystem.SystemName, InterpolateSystem.SystemName,
        }, new HairSimulation(full).Pipeline.SystemNames);
    }

    private sealed class WindField { public Vector3 Velocity; }

    private sealed class CountingWindSystem : IHairSystem
    {
        public int Runs;
        public string Name => "Wind";
        public SystemPhase Phase => SystemPhase.Substep;
        public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
        {
            Runs++;
            var wind = scene.GetComponent<WindField>()!;
            var w = scene.World;
            for (int s = begin; s < end; s++)
                for (int i = w.StrandFirst[s]; i < w.StrandFirst[s] + w.StrandParticleCount[s]; i++)
                    if (w.InvMass[i] > 0) w.VelX[i] += wind.Velocity.X * ctx.H;
        }
    }

    [Fact]
    public void SystemAddedLaterJoinsOnlyWhenItsDataExists()
    {
        var wind = new CountingWindSystem();
        var builder = PipelineBuilder.CreateDefault().Add(new SystemFactory("Wind", SystemPhase.Substep, 250,
            s => s.HasComponent<WindField>(), _ => wind));
        var scene = Scene();
        var sim = new HairSimulation(scene, builder);
        Assert.DoesNotContain("Wind", sim.Pipeline.SystemNames);
        sim.Step(1f / 60f);
        Assert.Equal(0, wind.Runs);

        scene.SetComponent(new WindField { Velocity = new Vector3(3, 0, 0) });
        Assert.Contains("Wind", sim.Pipeline.SystemNames);
        // Runs between shape matching (200) and integration (300).
        var names = sim.Pipeline.SystemNames;
        Assert.True(IndexOf(names, "Wind") > IndexOf(names, ShapeMatchSystem.SystemName) && IndexOf(names, "Wind") < IndexOf(names, IntegrateSystem.SystemName));
        sim.Step(1f / 60f);
        Assert.Equal(scene.Settings.Substeps, wind.Runs);

        scene.RemoveComponent<WindField>();
        Assert.DoesNotContain("Wind", sim.Pipeline.SystemNames);
    }

    private static int IndexOf(IReadOnlyList<string> list, string name)
    {
        for (int i = 0; i < list.Count; i++) if (list[i] == name) return i;
        return -1;
    }

    [Fact]
    public void DuplicateSystemNamesAreRefused()
    {
        var b = PipelineBuilder.CreateDefault();
        Assert.Throws<ArgumentException>(() => b.Add(new SystemFactory(IntegrateSystem.SystemName, SystemPhase.Substep, 1, _ => true, _ => new IntegrateSystem())));
    }

    [Fact]
    public void CopyingIntoAWorldAlwaysGivesItANewEditStamp()
    {
        // Caches keyed on a world's stamp (the pipeline's reach for the stability guards) must see every copy, even
        // from a world whose own stamp is lower than the target's.
        var source = new HairWorld(1, 2, 4);
        var target = source.Clone();
        for (int k = 0; k < 5; k++) target.MarkEdited();
        int seen = target.EditStamp;
        source.CopyTo(target);
        Assert.True(target.EditStamp > seen, $"stamp {target.EditStamp} after a copy, {seen} before");
        int again = target.EditStamp;
        source.CopyTo(target);
        Assert.NotEqual(again, target.EditStamp);
    }

    [Fact]
    public void CopyingMotionKeepsTheStampAndCopiesOnlyTheSimulatedState()
    {
        var scene = GroomBuilder.BuildScene(TestWorlds.SmallGroom(), new SimulationSettings());
        var sim = new HairSimulation(scene);
        var saved = scene.World.Clone();
        for (int f = 1; f <= 5; f++) sim.Step(1f / 60f, new RigidTransform(System.Numerics.Vector3.Zero, System.Numerics.Quaternion.CreateFromYawPitchRoll(0.1f * f, 0, 0)));
        int stamp = scene.World.EditStamp;
        float mass = scene.World.InvMass[5];
        scene.World.InvMass[5] = 0.5f; // not motion: must survive the copy
        saved.CopyMotionTo(scene.World);
        Assert.Equal(stamp, scene.World.EditStamp);
        Assert.Equal(saved.Head, scene.World.Head);
        Assert.Equal(saved.PosX, scene.World.PosX);
        Assert.Equal(saved.VelZ, scene.World.VelZ);
        Assert.Equal(0.5f, scene.World.InvMass[5]);
        scene.World.InvMass[5] = mass;
        Assert.Throws<ArgumentException>(() => saved.CopyMotionTo(new HairWorld(1, 1, 4)));
    }
}
