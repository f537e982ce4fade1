using System.Numerics;
using HairSim.Measurement;
using Xunit;

namespace HairSim.Tests.Core;

/// <summary>The hair volume system (<see cref="VolumeSettings"/>, <see cref="VolumeSystem"/> and its fast twin).</summary>
public class VolumeTests
{
    private static HairScene Groom(SolverPath path, VolumeSettings? volume = null, BendModel bend = BendModel.Limp)
    {
        var scene = GroomBuilder.BuildScene(new GroomSettings { SheetCount = 24, StrandsPerSheet = 9, ParticlesPerStrand = 12, StrandLength = 0.2f },
            new SimulationSettings { Path = path, Bend = bend });
        if (volume != null) scene.SetComponent(volume);
        return scene;
    }

    /// <summary>A pipeline of the volume system alone (nothing else moves), on the scene's path.</summary>
    private static HairSimulation VolumeOnly(HairScene scene)
    {
        var factory = PipelineBuilder.CreateDefault().Factories.Single(f => f.Name == VolumeSystem.SystemName);
        return new HairSimulation(scene, new PipelineBuilder().Add(factory with { IsNeeded = _ => true }));
    }

    [Fact]
    public void The_pipeline_holds_the_volume_system_only_when_the_scene_asks_for_it()
    {
        var scene = Groom(SolverPath.Fast);
        var sim = new HairSimulation(scene);
        sim.Step(1f / 60);
        Assert.DoesNotContain(VolumeSystem.SystemName, sim.Pipeline.SystemNames);
        scene.SetComponent(new VolumeSettings());
        sim.Step(1f / 60);
        Assert.Equal(VolumeSystem.SystemName, sim.Pipeline.SystemNames[0]); // first: once per frame, before the substeps
        Assert.Equal(SystemPhase.FrameStart, sim.Pipeline.Systems[0].Phase);
        scene.RemoveComponent<VolumeSettings>();
        sim.Step(1f / 60);
        Assert.DoesNotContain(VolumeSystem.SystemName, sim.Pipeline.SystemNames);
    }

    [Fact]
    public void Friction_relaxes_opposite_motions_of_coinciding_strands_by_the_analytic_share()
    {
        foreach (var path in new[] { SolverPath.Reference, SolverPath.Fast })
        {
            // Two strands in the same place moving in opposite directions: the hair's mean velocity there is zero, so
            // each keeps e^(−Friction·dt/T₀) of its velocity.
            var w = new HairWorld(1, 2, 8);
            var pts = new Vector3[8];
            for (int k = 0; k < 8; k++) pts[k] = new Vector3(0.03f * k, 0f, 0f);
            w.SetStrand(0, pts, pinned: 1); w.SetStrand(1, pts, pinned: 1);
            for (int k = 1; k < 8; k++) { w.VelZ[k] = 0.5f; w.VelZ[8 + k] = -0.5f; }
            var volume = new VolumeSettings { Stiffness = 0f, Friction = 3f, SampleEvery = 1 };
            var scene = new HairScene(w, new SimulationSettings { Path = path });
            scene.SetComponent(volume);
            var sim = VolumeOnly(scene);
            float dt = 1f / 60;
            sim.Step(dt);
            double natural = GroomScale.Of(w).NaturalTime;
            double keep = Math.Exp(-3.0 * dt / natural);
            for (int k = 1; k < 8; k++)
            {
                Assert.Equal(0.5 * keep, w.VelZ[k], 4);
                Assert.Equal(-0.5 * keep, w.VelZ[8 + k], 4);
                Assert.Equal(0f, w.VelX[k]); Assert.Equal(0f, w.VelY[k]);
            }
            Assert.Equal(0f, w.VelZ[0]); // pinned roots are left alone
        }
    }

    [Fact]
    public void Packed_hair_is_pushed_outward_harder_than_hair_as_grown()
    {
        foreach (var path in new[] { SolverPath.Reference, SolverPath.Fast })
        {
            var scene = Groom(path, new VolumeSettings { Friction = 0f });
            var w = scene.World;
            var sim = VolumeOnly(scene);
            sim.Step(1f / 60);
            // As grown, the hair is at its rest density on average (half of it above the median, so it is pushed too).
            double restPush = 0;
            for (int i = 0; i < w.ParticleCount; i++) restPush += w.GetVelocity(i).Length();
            for (int i = 0; i < w.ParticleCount; i++) w.SetVelocity(i, Vector3.Zero);
            // Pack every strand's free particles to 40 % of their distance from the hair's centre.
            var centre = Vector3.Zero; int free = 0;
            for (int i = 0; i < w.ParticleCount; i++) if (w.InvMass[i] > 0f) { centre += w.GetPosition(i); free++; }
            centre /= free;
            for (int i = 0; i < w.ParticleCount; i++)
                if (w.InvMass[i] > 0f) w.SetPosition(i, centre + 0.4f * (w.GetPosition(i) - centre));
            sim.Step(1f / 60);
            double packedPush = 0; int outward = 0, moved = 0;
            for (int i = 0; i < w.ParticleCount; i++)
            {
                if (w.InvMass[i] == 0f) continue;
                var v = w.GetVelocity(i);
                packedPush += v.Length();
                if (v.Length() > 1e-6f) { moved++; if (Vector3.Dot(v, w.GetPosition(i) - centre) > 0f) outward++; }
            }
            Assert.True(packedPush > 1.3 * restPush, $"{path}: packed push {packedPush} vs rest {restPush}");
            Assert.True(outward > 0.8 * moved, $"{path}: {outward} of {moved} pushed outward");
        }
    }

    [Fact]
    public void The_fast_path_gives_the_reference_path_s_velocity_changes()
    {
        // The same state (a limp groom that has fallen and is swinging) through both implementations, one frame.
        var source = Groom(SolverPath.Reference);
        var run = new HairSimulation(source);
        for (int f = 1; f <= 40; f++) run.Step(1f / 60, HeadMotion.Shake(f / 60f));
        var volume = new VolumeSettings();
        var results = new List<float[]>();
        foreach (var path in new[] { SolverPath.Reference, SolverPath.Fast })
        {
            var scene = Groom(path, volume);
            foreach (var (to, from) in scene.World.Buffers().Zip(source.World.Buffers())) from.CopyTo(to, 0);
            var before = (float[])scene.World.VelX.Clone();
            VolumeOnly(scene).Step(1f / 60);
            var w = scene.World;
            var dv = new float[3 * w.ParticleCount];
            for (int i = 0; i < w.ParticleCount; i++)
            {
                dv[3 * i] = w.VelX[i] - source.World.VelX[i]; dv[3 * i + 1] = w.VelY[i] - source.World.VelY[i]; dv[3 * i + 2] = w.VelZ[i] - source.World.VelZ[i];
            }
            results.Add(dv);
        }
        float largest = results[0].Max(MathF.Abs);
        Assert.True(largest > 1e-3f, $"the frame changes velocities ({largest})");
        float worst = 0f;
        for (int i = 0; i < results[0].Length; i++) worst = MathF.Max(worst, MathF.Abs(results[0][i] - results[1][i]));
        Assert.True(worst <= 1e-3f * largest + 1e-6f, $"fast differs from reference by {worst} (largest change {largest})");
    }

    [Fact]
    public void The_fast_path_does_not_depend_on_the_thread_count()
    {
        float[]? first = null;
        foreach (int threads in new[] { 1, 2, 3 })
        {
            using var d = new ParallelDispatcher(threads);
            var scene = Groom(SolverPath.Fast, new VolumeSettings());
            var sim = new HairSimulation(scene, dispatcher: d);
            for (int f = 1; f <= 30; f++) sim.Step(1f / 60, HeadMotion.Shake(f / 60f));
            var bits = scene.World.Buffers().SelectMany(b => b).ToArray();
            if (first == null) first = bits; else Assert.Equal(first, bits);
        }
    }

    [Theory]
    [InlineData(19, 4)]  // two blocks of eight and three one by one; samples every 4th strand and the last
    [InlineData(16, 1)]  // the reference groom's strands, every strand a sample
    [InlineData(5, 3)]   // strands shorter than a block: one by one only
    public void The_fast_path_s_eight_lane_splat_and_sample_give_the_one_by_one_bits(int particles, int every)
    {
        if (!System.Runtime.Intrinsics.X86.Avx2.IsSupported) return; // one by one is all there is
        var results = new List<float[]>();
        foreach (bool lanes in new[] { true, false })
        {
            var scene = GroomBuilder.BuildScene(new GroomSettings { SheetCount = 24, StrandsPerSheet = 11, ParticlesPerStrand = particles, StrandLength = 0.2f },
                new SimulationSettings { Path = SolverPath.Fast, Bend = BendModel.Limp });
            scene.SetComponent(new VolumeSettings { SampleEvery = every });
            var sim = new HairSimulation(scene);
            sim.Step(1f / 60);
            var volume = sim.Pipeline.Systems.OfType<HairSim.Fast.FastVolumeSystem>().Single();
            Assert.True(volume.Lanes);
            volume.Lanes = lanes;
            for (int f = 2; f <= 40; f++) sim.Step(1f / 60, HeadMotion.Shake(f / 60f));
            results.Add(scene.World.Buffers().SelectMany(b => b).ToArray());
        }
        Assert.Equal(results[0], results[1]);
        // And the volume did something in those frames: without it the hair ends elsewhere.
        var plain = GroomBuilder.BuildScene(new GroomSettings { SheetCount = 24, StrandsPerSheet = 11, ParticlesPerStrand = particles, StrandLength = 0.2f },
            new SimulationSettings { Path = SolverPath.Fast, Bend = BendModel.Limp });
        var run = new HairSimulation(plain);
        run.Step(1f / 60);
        for (int f = 2; f <= 40; f++) run.Step(1f / 60, HeadMotion.Shake(f / 60f));
        Assert.NotEqual(results[0], plain.World.Buffers().SelectMany(b => b).ToArray());
    }

    [Fact]
    public void Limp_hair_sinks_on_the_crown_and_half_the_rest_density_keeps_it_within_a_fifth()
    {
        static double Kept(VolumeSettings? volume)
        {
            var g = new GroomSettings { SheetCount = 120, StrandsPerSheet = 8 };
            var scene = GroomBuilder.BuildScene(g, new SimulationSettings { Bend = BendModel.Limp });
            if (volume != null) scene.SetComponent(volume);
            double grown = HairVolume.OuterLayerThickness(scene.World, g.HeadCenter, g.HeadRadii, 0.5f);
            var sim = new HairSimulation(scene);
            for (int f = 0; f < 60; f++) sim.Step(1f / 60);
            return HairVolume.OuterLayerThickness(scene.World, g.HeadCenter, g.HeadRadii, 0.5f) / grown;
        }
        // Nothing holds limp hair up but other hair: without volume, and with the default target (the median rest
        // density, which the sparser outer layer reaches by sinking), the crown's outer layer sinks to about half.
        Assert.InRange(Kept(null), 0.0, 0.7);
        Assert.InRange(Kept(new VolumeSettings()), 0.0, 0.7);
        Assert.InRange(Kept(new VolumeSettings { Density = 0.5f }), 0.8, 1.2);
    }

    [Fact]
    public void Bad_volume_settings_are_refused_before_anything_moves()
    {
        foreach (var path in new[] { SolverPath.Reference, SolverPath.Fast })
        foreach (var bad in new Action<VolumeSettings>[]
        {
            v => v.Stiffness = float.NaN, v => v.Friction = -1f, v => v.Density = 0f, v => v.CellSize = float.PositiveInfinity, v => v.SampleEvery = 0,
        })
        {
            var volume = new VolumeSettings();
            var scene = Groom(path, volume);
            var sim = new HairSimulation(scene);
            sim.Step(1f / 60);
            bad(volume);
            var before = scene.World.Buffers().Select(b => (float[])b.Clone()).ToArray();
            var error = Assert.Throws<ArgumentOutOfRangeException>(() => sim.Step(1f / 60));
            Assert.StartsWith("Volume ", error.Message);
            Assert.Equal(before, scene.World.Buffers());
        }
    }

    [Fact]
    public void Extreme_settings_stay_finite_at_every_scale_and_frame_rate()
    {
        foreach (float scale in new[] { 0.04f, 1f, 40f })
        foreach (int hz in new[] { 30, 240 })
        foreach (var volume in new[]
        {
            new VolumeSettings { Stiffness = 1000f, Friction = 1000f, Density = 0.05f },
            new VolumeSettings { Stiffness = 1000f, Friction = 0f, Density = 0.05f, CellSize = 0.1f, SampleEvery = 1 },
        })
        {
            var r = CrossingSheets.Run(volume, SolverPath.Fast, hz, scale: scale);
            Assert.Equal(0, r.NonFinite);
        }
    }

    [Theory]
    [InlineData(0.0005f, 400, 400)]   // B in A's plane: at or below, and in the layer
    [InlineData(0.0055f, 0, 400)]     // half a per cent above: not below, but in A's layer
    [InlineData(0.12f, 0, 0)]         // as dropped: well above
    public void The_crossing_measure_tells_B_below_A_from_B_in_A_layer(float drop, int sunk, int inLayer)
    {
        // The measure on the sheets as placed (A at 0.05 % of the length above the floor's top, B at `drop`), so the
        // answer is known: every one of the 20 × 20 crossings has the same gap.
        var scene = CrossingSheets.Scene(null, SolverPath.Fast, drop);
        var r = CrossingSheets.Measure(scene.World, 0.25f);
        Assert.Equal(400, r.Crossings);
        Assert.Equal(sunk, r.Sunk);
        Assert.Equal(inLayer, r.InLayer);
        Assert.Equal(drop - 0.0005f, r.MeanGap, 1e-5);
    }

    [Fact]
    public void A_sheet_dropped_on_a_crossing_sheet_sinks_into_it_without_volume()
    {
        // The control for the figures in docs/volume.md: without hair–hair interaction the upper sheet ends at the lower
        // sheet's height, below it at a large share of the crossings; with the volume, the sheets are pushed apart (most
        // crossings disappear) and fewer of the remaining ones have the upper sheet below.
        var off = CrossingSheets.Run(null, SolverPath.Fast, 60);
        Assert.Equal(400, off.Crossings);
        Assert.InRange(off.SunkShare, 0.3, 0.7);
        Assert.InRange(Math.Abs(off.MeanGap), 0, 1e-3);
        var on = CrossingSheets.Run(new VolumeSettings(), SolverPath.Fast, 60);
        Assert.True(on.Sunk < 0.1 * off.Sunk, $"with volume {on.Sunk} of {on.Crossings} crossings sank, without {off.Sunk} of {off.Crossings}");
        Assert.Equal(0, on.NonFinite);
    }

    [Theory]
    [MemberData(nameof(CrossingSheetCases.EveryScaleAndRate), MemberType = typeof(CrossingSheetCases))]
    public void With_the_default_volume_a_dropped_sheet_rests_on_the_crossing_sheet(SolverPath path, int hz, float scale)
    {
        // Default settings, 1 cm, 25 cm and 10 m strands: the falling sheet is stopped by friction and held about a
        // cell above the lower one instead of passing into it (without volume about half the crossings sink: the
        // control test above), and the sheets stay crossed (a churning push scatters them: before the passes were cut
        // finer while the push is stiff, 0–14 crossings were left at 30–60 Hz for 1 cm and 25 cm hair).
        var r = CrossingSheets.Run(new VolumeSettings(), path, hz, scale: scale);
        Assert.True(r.Crossings >= 100, $"the sheets still cross ({r.Crossings})");
        Assert.True(r.Sunk <= 0.02 * r.Crossings, $"{r.Sunk} of {r.Crossings} crossings sank");
        // A few B strands still end in A's layer (on the floor beside A's strands: 0–5 % of the crossings in
        // docs/volume-report.md); without volume nearly all do.
        Assert.True(r.InLayer <= 0.08 * r.Crossings, $"B in A's layer at {r.InLayer} of {r.Crossings} crossings");
        Assert.True(r.MeanGap > 0.05, $"B rests above A (mean gap {r.MeanGap:P1} of the length)");
        Assert.Equal(0, r.NonFinite);
    }

    [Fact]
    public void A_stiff_push_cuts_the_frame_finer_and_quiet_hair_keeps_one_pass()
    {
        // 25 cm hair at 60 Hz: one pass per frame by MaxStep (1/8 natural time = 20 ms); once sheet B lands on A the
        // push is stiff and the frames are cut into 2 … 4 parts (never more than MaxRefine × what MaxStep asks).
        var scene = CrossingSheets.Scene(new VolumeSettings(), SolverPath.Fast);
        var sim = new HairSimulation(scene);
        int most = 0;
        for (int f = 0; f < 60; f++) { sim.Step(1f / 60); most = Math.Max(most, sim.Pipeline.LastFrameParts); }
        Assert.Equal(1, new VolumeSettings().PartsOf(1f / 60, sim.Pipeline.Scale));
        Assert.InRange(most, 2, VolumeSettings.MaxRefine);

        // The reference groom shaken (the scene leave-out times): one pass per 60 Hz frame throughout.
        var groom = GroomBuilder.BuildScene(GroomSettings.Reference(), new SimulationSettings());
        groom.SetComponent(new VolumeSettings());
        var run = new HairSimulation(groom);
        for (int f = 1; f <= 90; f++)
        {
            run.Step(1f / 60, HeadMotion.Shake(f / 60f));
            Assert.Equal(1, run.Pipeline.LastFrameParts);
        }
    }

    [Fact]
    public void The_longest_part_follows_the_stiffness_and_is_bounded()
    {
        var volume = new VolumeSettings();
        var scale = new GroomScale(0.3f, 0.25f / 15, 0.25f);
        double cell = scale.Segment;
        Assert.Equal(double.PositiveInfinity, volume.LongestPart(0, cell, scale));
        Assert.Equal(double.PositiveInfinity, new VolumeSettings { Stiffness = 0f }.LongestPart(9, cell, scale));
        // A sheet as sampled (curvature about 3.3 per cell²) takes a 60 Hz frame in one pass; a churning one (9) does not.
        Assert.True(volume.LongestPart(3.3, cell, scale) > 1.0 / 60);
        Assert.True(volume.LongestPart(9, cell, scale) < 1.0 / 60);
        // Never shorter than MaxStep / MaxRefine natural times; the same share of the natural time at every size.
        Assert.Equal(volume.MaxStep * scale.NaturalTime / VolumeSettings.MaxRefine, volume.LongestPart(1e6, cell, scale), 9);
        var giant = new GroomScale(12f, 10f / 15, 10f);
        Assert.Equal(volume.LongestPart(9, cell, scale) / scale.NaturalTime, volume.LongestPart(9, giant.Segment, giant) / giant.NaturalTime, 6);
    }

    [Fact]
    public void A_long_frame_is_stepped_in_parts_when_the_volume_asks_for_it()
    {
        var volume = new VolumeSettings { MaxStep = 1f / 32 };
        var scale = new GroomScale(0.3f, 0.25f / 15, 0.25f);
        Assert.Equal(4, volume.PartsOf(1f / 60, scale));   // 16.7 ms / (0.16 s / 32 = 5 ms)
        Assert.Equal(1, volume.PartsOf(1f / 240, scale));
        Assert.Equal(VolumeSettings.MaxParts, volume.PartsOf(1f, scale));
        Assert.Equal(1, new VolumeSettings().PartsOf(1f / 60, scale)); // the default: one pass per 60 Hz frame for 25 cm hair
        Assert.Equal(2, new VolumeSettings().PartsOf(1f / 30, scale));
    }
}
