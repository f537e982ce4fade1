using System.Reflection;
using HairSim.Measurement;

namespace HairSim.Tests.Measurement;

public class StabilityGuardsTests
{
    /// <summary>The reference groom's size: 25 cm strands of 16 particles, 0.35 m reach.</summary>
    private static readonly GroomScale ReferenceScale = GroomScale.Of(0.25f, 16, 0.35f);

    private static SimulationSettings Guarded(SimulationSettings requested, float dt, float move = 0f, float angle = 0f, bool teleported = false)
    {
        var effective = new SimulationSettings();
        StabilityGuards.Apply(requested, effective, dt, move, angle, teleported, ReferenceScale);
        return effective;
    }

    [Fact]
    public void MullerAlphaAboveOneIsClampedOnlyWithGuards()
    {
        const BendModel source = BendModel.SourceTriples;
        Assert.Equal(1f, Guarded(new SimulationSettings { Bend = source, Alpha = 3f }, 1 / 60f).Alpha);
        Assert.Equal(3f, Guarded(new SimulationSettings { Bend = source, Alpha = 3f, Guards = false }, 1 / 60f).Alpha);
        Assert.Equal(0.5f, Guarded(new SimulationSettings { Bend = source, Alpha = 0.5f }, 1 / 60f).Alpha);
        // The literal force's α is a spring rate (1/s²), not a per-step share: not clamped.
        Assert.Equal(500f, Guarded(new SimulationSettings { Bend = source, Alpha = 500f, Mode = ShapeMatchMode.LiteralForce }, 1 / 60f).Alpha);
        // α belongs to the source's triples: under any other bend model no triple goal pulls, guards or not.
        Assert.Equal(0f, Guarded(new SimulationSettings { Alpha = 0.5f }, 1 / 60f).Alpha);
        Assert.Equal(0f, Guarded(new SimulationSettings { Bend = BendModel.Limp, Alpha = 0.5f, Guards = false }, 1 / 60f).Alpha);
    }

    [Fact]
    public void SmallHairGetsSubstepsShortEnoughForItsSegments()
    {
        // Gravity may move a particle at most 5 % of the mean segment (h²·g ≤ 0.05·ℓ): a doll's 1 cm strand of 16
        // particles (ℓ = 0.67 mm) needs h ≤ 1.84 ms, 10 substeps at 60 Hz; a person's 25 cm strand (ℓ = 16.7 mm) h ≤ 9.2 ms,
        // which the default 4 substeps already meet; a 10 m creature needs none more.
        var effective = new SimulationSettings();
        float Segment(float length) => length / 15f;
        int Substeps(float length, float dt)
        {
            StabilityGuards.Apply(new SimulationSettings(), effective, dt, 0f, 0f, false, GroomScale.Of(length, 16, length));
            return effective.Substeps;
        }
        double g = new SimulationSettings().Gravity.Length();
        Assert.Equal((int)Math.Ceiling((1 / 60.0) / Math.Sqrt(0.05 * Segment(0.01f) / g)), Substeps(0.01f, 1 / 60f));
        Assert.Equal(10, Substeps(0.01f, 1 / 60f));
        Assert.Equal(4, Substeps(0.25f, 1 / 60f));
        Assert.Equal(4, Substeps(10f, 1 / 60f));
        StabilityGuards.Apply(new SimulationSettings { Guards = false }, effective, 1 / 60f, 0f, 0f, false, GroomScale.Of(0.01f, 16, 0.01f));
        Assert.Equal(4, effective.Substeps);
        StabilityGuards.Apply(new SimulationSettings { MaxFallPerSubstep = 0f }, effective, 1 / 60f, 0f, 0f, false, GroomScale.Of(0.01f, 16, 0.01f));
        Assert.Equal(4, effective.Substeps);
    }

    [Fact]
    public void LongFramesGetMoreSubstepsSoTheSubstepStaysShort()
    {
        // An absolute limit of 1/60 s (the fall limit off here, see SmallHairGetsSubstepsShortEnoughForItsSegments): 4 substeps are
        // enough down to 15 Hz, one substep only at 60 Hz and above.
        Assert.Equal(4, Guarded(new SimulationSettings { MaxFallPerSubstep = 0f, MaxSubstep = 1 / 60f }, 1 / 15f).Substeps);
        Assert.Equal(1, Guarded(new SimulationSettings { MaxFallPerSubstep = 0f, MaxSubstep = 1 / 60f, Substeps = 1 }, 1 / 60f).Substeps);
        Assert.Equal(4, Guarded(new SimulationSettings { MaxFallPerSubstep = 0f, MaxSubstep = 1 / 60f, Substeps = 1 }, 1 / 15f).Substeps);
        Assert.Equal(16, Guarded(new SimulationSettings { MaxFallPerSubstep = 0f, MaxSubstep = 1 / 240f }, 1 / 15f).Substeps);
        Assert.Equal(8, Guarded(new SimulationSettings { MaxFallPerSubstep = 0f, MaxSubstep = 1 / 60f, Substeps = 8 }, 1 / 15f).Substeps);
        Assert.Equal(1, Guarded(new SimulationSettings { MaxFallPerSubstep = 0f, MaxSubstep = 1 / 60f, Substeps = 1, Guards = false }, 1 / 15f).Substeps);
        Assert.Equal(60, Guarded(new SimulationSettings { MaxFallPerSubstep = 0f, MaxSubstep = 1 / 60f }, 1f).Substeps);
        // With the default fall limit a 25 cm groom needs h ≤ 9.2 ms: 8 substeps at 15 Hz, 2 at 60 Hz.
        Assert.Equal(8, Guarded(new SimulationSettings(), 1 / 15f).Substeps);
        Assert.Equal(2, Guarded(new SimulationSettings { Substeps = 1 }, 1 / 60f).Substeps);
        Assert.Equal(StabilityGuards.MaxSubsteps, Guarded(new SimulationSettings { MaxFallPerSubstep = 0f, MaxSubstep = 1 / 60f }, 1 / 60f, 100f).Substeps);
    }

    [Fact]
    public void FastHeadMovesGetMoreSubstepsButTeleportsDoNot()
    {
        // 0.3 m + 0.5 rad × 0.35 m reach = 0.475 m of travel at 1.2 × 1.67 cm = 2 cm per substep.
        Assert.Equal(24, Guarded(new SimulationSettings(), 1 / 60f, 0.3f, 0.5f).Substeps);
        Assert.Equal(4, Guarded(new SimulationSettings(), 1 / 60f, 0.3f, 0.5f, teleported: true).Substeps);
    }

    [Fact]
    public void ScaleFreeSettingsBecomeTheSameLookAtEverySize()
    {
        // Damping and the speed limit are stated per natural time √(L/1 g) and natural speed √(1 g·L): the SI values the
        // systems see scale as 1/√L and √L, so the defaults are 2/s and 40 m/s on 25 cm hair.
        var effective = new SimulationSettings();
        foreach (float length in new[] { 0.01f, 0.25f, 10f })
        {
            StabilityGuards.Apply(new SimulationSettings(), effective, 1 / 60f, 0f, 0f, false, GroomScale.Of(length, 16, length));
            double t0 = Math.Sqrt(length / BendProfile.StandardGravity);
            Assert.Equal(0.32 / t0, effective.Damping, 3);
            Assert.Equal(25 * Math.Sqrt(BendProfile.StandardGravity * length), effective.MaxSpeed, 3);
        }
        StabilityGuards.Apply(new SimulationSettings(), effective, 1 / 60f, 0f, 0f, false, ReferenceScale);
        Assert.InRange(effective.Damping, 1.95f, 2.05f);
        Assert.InRange(effective.MaxSpeed, 38f, 40f);
        // Head travel per substep is a share of the mean segment: 1.2 × 1.67 cm = 2 cm on the reference groom, 40 times that on a 40 times larger one.
        var giant = GroomScale.Of(10f, 16, 14f);
        StabilityGuards.Apply(new SimulationSettings(), effective, 1 / 60f, 0.3f * 40f, 0.5f, false, giant);
        Assert.Equal(Guarded(new SimulationSettings(), 1 / 60f, 0.3f, 0.5f).Substeps, effective.Substeps);
    }

    [Fact]
    public void TeleportsAreJumpsLongerThanAShareOfTheHairsReach()
    {
        foreach (float k in new[] { 0.04f, 1f, 40f })
        {
            var scene = GroomBuilder.BuildScene(new GroomSettings
            {
                SheetCount = 4, StrandsPerSheet = 2, ParticlesPerStrand = 8, StrandLength = 0.25f * k, HeadRadii = new System.Numerics.Vector3(0.078f, 0.1f, 0.095f) * k,
            });
            var sim = new HairSimulation(scene);
            float reach = sim.Pipeline.Scale.Reach;
            sim.Step(1 / 60f, new RigidTransform(new System.Numerics.Vector3(1.9f * reach, 0, 0), System.Numerics.Quaternion.Identity));
            Assert.False(sim.Pipeline.LastFrame.Teleported, $"×{k}: a jump of 1.9 reaches is not a teleport");
            sim.Step(1 / 60f, new RigidTransform(new System.Numerics.Vector3(3.95f * reach, 0, 0), System.Numerics.Quaternion.Identity));
            Assert.True(sim.Pipeline.LastFrame.Teleported, $"×{k}: a second jump of 2.05 reaches is a teleport");
        }
    }

    [Fact]
    public void PipelineRunsTheGuardedSubsteps()
    {
        var scene = GroomBuilder.BuildScene(CanonicalCases.SmallGroom(8, 2, 1), new SimulationSettings { MaxSubstep = 1 / 240f });
        var sim = new HairSimulation(scene);
        sim.Step(1 / 15f);
        Assert.Equal(16, sim.Pipeline.LastFrame.Substeps);
        Assert.Equal(1 / 240f, sim.Pipeline.LastFrame.H, 6);
        Assert.Equal(4, scene.Settings.Substeps); // the user's settings are left alone
        Assert.Equal(16, sim.Pipeline.LastFrameSubsteps);
        sim.Step(1 / 240f);
        Assert.Equal(4, sim.Pipeline.LastFrameSubsteps); // counted per frame, not summed over frames
    }

    [Fact]
    public void LastFrameSubstepsCountsEveryPartOfASplitFrame()
    {
        // Hair volume on 1 cm hair at 30 Hz steps each frame in several parts, each with its share of the substeps:
        // the count is what the pipeline stepped over all of them (what a profiler or the bench divides by).
        var scene = CrossingSheets.Scene(new VolumeSettings(), SolverPath.Fast, scale: 0.04f);
        var sim = new HairSimulation(scene);
        sim.Step(1f / 30);
        int parts = sim.Pipeline.LastFrameParts;
        Assert.True(parts > 1, $"{parts} parts");
        Assert.InRange(sim.Pipeline.LastFrameSubsteps, parts, 4 * parts);
        Assert.True(sim.Pipeline.LastFrameSubsteps >= scene.Settings.Substeps);
    }

    [Fact]
    public void CopyToCopiesEverySetting()
    {
        var source = new SimulationSettings();
        var target = new SimulationSettings();
        var props = typeof(SimulationSettings).GetProperties(BindingFlags.Public | BindingFlags.Instance);
        foreach (var p in props)
        {
            object value = p.PropertyType == typeof(float) ? 0.123f
                : p.PropertyType == typeof(int) ? 7
                : p.PropertyType == typeof(bool) ? !(bool)p.GetValue(source)!
                : p.PropertyType == typeof(System.Numerics.Vector3) ? new System.Numerics.Vector3(1, 2, 3)
                : p.PropertyType.IsEnum ? Enum.GetValues(p.PropertyType).GetValue(1)!
                : throw new InvalidOperationException($"CopyToCopiesEverySetting does not know how to vary {p.PropertyType} {p.Name}.");
            p.SetValue(source, value);
        }
        source.CopyTo(target);
        foreach (var p in props) Assert.True(Equals(p.GetValue(source), p.GetValue(target)), $"{p.Name} was not copied");
    }

    [Fact]
    public void AlphaClampStopsTheSourcesSchemeFromOscillating()
    {
        // Müller α = 4 with one substep overshoots every goal: without the guard the hair never calms down.
        var s = new SimulationSettings { Bend = BendModel.SourceTriples, Alpha = 4f, Substeps = 1, Length = LengthMode.None, MaxSubstep = 0f, Guards = false };
        var unguarded = StabilityMap.Run(s, 1 / 60f, 16, StabilityScenario.Shake, sheets: 3);
        s.Guards = true;
        var guarded = StabilityMap.Run(s, 1 / 60f, 16, StabilityScenario.Shake, sheets: 3);
        Assert.False(unguarded.EnergyDecays);
        Assert.True(guarded.Finite && guarded.EnergyDecays && guarded.MaxInside == 0);
    }

    [Fact]
    public void HeadTravelGuardKeepsANearTeleportFromTearingTheHair()
    {
        // At 15 Hz, with the substep-length guards off so only the head-travel guard differs; the source's scheme,
        // whose length pass runs before collision (the default bend sweep is inextensible by itself).
        var unguarded = StabilityMap.Run(new SimulationSettings { Bend = BendModel.SourceTriples, Guards = false, MaxSubstep = 0f, MaxFallPerSubstep = 0f }, 1 / 15f, 16, StabilityScenario.NearTeleport);
        var guarded = StabilityMap.Run(new SimulationSettings { Bend = BendModel.SourceTriples, MaxSubstep = 0f, MaxFallPerSubstep = 0f }, 1 / 15f, 16, StabilityScenario.NearTeleport);
        Assert.True(unguarded.WorstElongation >= StabilityResult.StretchLimit, $"unguarded {unguarded.WorstElongation:P1}");
        Assert.True(guarded.Stable, $"guarded {guarded.WorstElongation:P1}, inside {guarded.MaxInside}");
    }
}
