using System.Numerics;
using HairSim.Measurement;
using Xunit;

namespace HairSim.Tests.Core;

/// <summary>Strand contacts between sheets (<see cref="StrandContactSettings"/>, <see cref="StrandContactSystem"/>).</summary>
public class StrandContactTests
{
    /// <summary>
    /// A grate and a strand: sheet A, five strands of <paramref name="particles"/> particles, 20 cm long along x, 2 cm
    /// apart in z, pinned everywhere (fixed rods, no collider); sheet B's first strand, 10 cm along z across them,
    /// <paramref name="height"/> above, free, so under gravity it falls onto the grate and rests across it. (Sheet B's
    /// other strands fall freely far away.)
    /// </summary>
    private static HairScene Grate(SolverPath path, float height, int particles = 5, StrandContactSettings? contacts = null)
    {
        var w = new HairWorld(2, Rods, particles);
        var pts = new Vector3[particles];
        for (int r = 0; r < Rods; r++)
        {
            for (int k = 0; k < particles; k++) pts[k] = new Vector3(0.2f * (k / (particles - 1f) - 0.5f), 0f, 0.02f * (r - Rods / 2));
            w.SetStrand(r, pts, pinned: particles);
            for (int k = 0; k < particles; k++) pts[k] = new Vector3(r == 0 ? 0.013f : 1f + r, height, 0.1f * (k / (particles - 1f) - 0.5f));
            w.SetStrand(Rods + r, pts, pinned: 0);
        }
        var scene = new HairScene(w, new SimulationSettings { Path = path, Bend = BendModel.Limp });
        if (contacts != null) scene.SetComponent(contacts);
        return scene;
    }

    private const int Rods = 5;

    // B's height above the middle rod, where it passes over it (z = 0); NaN if it no longer does.
    private static float Gap(HairWorld w)
    {
        var b = w.GetStrandPositions(Rods);
        for (int k = 1; k < b.Length; k++)
            if ((b[k - 1].Z < 0f) != (b[k].Z < 0f))
                return b[k - 1].Y + (b[k].Y - b[k - 1].Y) * (0f - b[k - 1].Z) / (b[k].Z - b[k - 1].Z);
        return float.NaN;
    }

    // The least distance between a segment of a rod and a segment of B.
    private static double Closest(HairWorld w)
    {
        var b = w.GetStrandPositions(Rods);
        double best = double.MaxValue;
        for (int r = 0; r < Rods; r++)
        {
            var a = w.GetStrandPositions(r);
            for (int p = 1; p < a.Length; p++)
                for (int q = 1; q < b.Length; q++)
                {
                    StrandContactSystem.ClosestPoints((a[p - 1].X, a[p - 1].Y, a[p - 1].Z), (a[p].X, a[p].Y, a[p].Z),
                        (b[q - 1].X, b[q - 1].Y, b[q - 1].Z), (b[q].X, b[q].Y, b[q].Z), out double s, out double t);
                    best = Math.Min(best, Vector3.Distance(Vector3.Lerp(a[p - 1], a[p], (float)s), Vector3.Lerp(b[q - 1], b[q], (float)t)));
                }
        }
        return best;
    }

    [Fact]
    public void The_pipeline_holds_strand_contacts_only_when_the_scene_asks_for_them()
    {
        var scene = CrossingSheets.Scene(null, SolverPath.Fast);
        var sim = new HairSimulation(scene);
        sim.Step(1f / 60);
        Assert.DoesNotContain(StrandContactSystem.SystemName, sim.Pipeline.SystemNames);
        scene.SetComponent(new StrandContactSettings());
        sim.Step(1f / 60);
        var system = Assert.Single(sim.Pipeline.Systems, s => s.Name == StrandContactSystem.SystemName);
        Assert.Equal(SystemPhase.PassEnd, system.Phase);
        scene.RemoveComponent<StrandContactSettings>();
        sim.Step(1f / 60);
        Assert.DoesNotContain(StrandContactSystem.SystemName, sim.Pipeline.SystemNames);
    }

    [Theory]
    [InlineData(SolverPath.Reference)]
    [InlineData(SolverPath.Fast)]
    public void A_strand_that_falls_on_a_grate_rests_on_it_the_contact_distance_away(SolverPath path)
    {
        // B falls 2 cm onto the fixed grate under 1 g. Without contacts it falls through; with them it comes to rest on
        // the rods with the closest points D = Thickness × the groom's mean segment apart, above them.
        var contacts = new StrandContactSettings { Thickness = 0.2f };
        var scene = Grate(path, 0.02f, contacts: contacts);
        var sim = new HairSimulation(scene);
        for (int f = 0; f < 120; f++) sim.Step(1f / 60);
        double d = contacts.Thickness * sim.Pipeline.Scale.Segment;
        Assert.InRange(Closest(scene.World), 0.98 * d, 1.02 * d);
        Assert.InRange(Gap(scene.World), 0.98 * d, 1.5 * d);
        // At rest on the grate: B moves at a few per cent of its natural speed √(g·L) at most (the pushes of each pass
        // against the fall of each pass).
        var w = scene.World;
        double natural = Math.Sqrt(9.81 * 0.1);
        for (int i = w.StrandFirst[Rods], e = i + w.StrandParticleCount[Rods]; i < e; i++)
            Assert.True(w.GetVelocity(i).Length() < 0.1 * natural, $"particle {i - w.StrandFirst[Rods]} of B still moves at {w.GetVelocity(i).Length()} m/s");

        var free = Grate(path, 0.02f);
        var control = new HairSimulation(free);
        for (int f = 0; f < 30; f++) control.Step(1f / 60);
        Assert.True(Gap(free.World) < 0f, $"without contacts B falls through the grate (gap {Gap(free.World)})");
    }

    [Theory]
    [InlineData(SolverPath.Reference, 30)]
    [InlineData(SolverPath.Fast, 30)]
    [InlineData(SolverPath.Fast, 240)]
    public void A_strand_thrown_through_a_grate_within_one_frame_is_put_back_on_its_side(SolverPath path, int hz)
    {
        // B starts 1 cm above the grate moving down at 3 m/s, so a 30 Hz frame carries it 10 cm, ten times the gap, past
        // the rods (its middle particle meets the middle rod's particle exactly): the closest points alone would push it
        // further down; the continuous test puts it back above.
        var scene = Grate(path, 0.01f, contacts: new StrandContactSettings());
        var w = scene.World;
        for (int i = w.StrandFirst[Rods], e = i + w.StrandParticleCount[Rods]; i < e; i++) w.VelY[i] = -3f;
        var sim = new HairSimulation(scene);
        sim.Step(1f / hz);
        Assert.True(Gap(w) > 0f, $"B passed through A (gap {Gap(w)} m)");
        var system = (StrandContactSystem)sim.Pipeline.Systems.Single(s => s.Name == StrandContactSystem.SystemName);
        if (hz == 30) Assert.True(system.LastPass.Crossed > 0, "the pass saw the crossing");
        // Clear of the rods (the pass's last sweeps only undo crossings, so B may still be nearer than D after such a blow).
        Assert.True(Closest(w) >= 0.25 * new StrandContactSettings().Thickness * sim.Pipeline.Scale.Segment, $"B {Closest(w)} m from the rods");
        // Bent by the blow, B then slides off the grate or slips through a gap between two rods (no crossing either);
        // while it still lies across the middle rod, it lies on top of it.
        for (int f = 0; f < hz / 10; f++)
        {
            sim.Step(1f / hz);
            Assert.False(Gap(w) <= 0f, $"frame {f}: B below the middle rod ({Gap(w)} m)");
        }

        var control = Grate(path, 0.01f);
        for (int i = control.World.StrandFirst[Rods], e = i + control.World.StrandParticleCount[Rods]; i < e; i++) control.World.VelY[i] = -3f;
        new HairSimulation(control).Step(1f / hz);
        if (hz == 30) Assert.True(Gap(control.World) < 0f, "without contacts B passes through A in one frame");
    }

    [Theory]
    [MemberData(nameof(CrossingSheetCases.EveryScaleAndRate), MemberType = typeof(CrossingSheetCases))]
    [InlineData(SolverPath.Reference, 30, 0.04f)]
    public void With_contacts_no_crossing_ends_with_the_upper_sheet_at_or_below_the_lower(SolverPath path, int hz, float scale)
    {
        // The test: sheet B dropped on the crossing sheet A, 1 cm, 25 cm and 10 m hair at 30 … 240 Hz, with the
        // default contacts alone and with the default volume too. B is never at or below A (without anything about half
        // the crossings sink: VolumeTests' control), nor in A's layer (less than 1 % of the length above it: the default
        // thickness keeps B 1/60 of the length above); the sheets still cross (the volume spreads them: 88 … 399 are left
        // with both), and the segments' lengths are about as exact as without contacts: the floor's friction, after the
        // length pass, leaves up to 8 % on a doll's scale at 30 … 60 Hz either way, and the snapshot of a churning
        // stack varies from run to run.
        foreach (var volume in new[] { null, new VolumeSettings() })
        {
            var r = CrossingSheets.Run(volume, path, hz, scale: scale, contacts: new StrandContactSettings());
            var without = CrossingSheets.Run(volume, path, hz, scale: scale);
            string label = volume == null ? "contacts" : "contacts and volume";
            Assert.True(r.Crossings >= 50, $"{label}: the sheets still cross ({r.Crossings})");
            Assert.True(r.Sunk == 0, $"{label}: {r.Sunk} of {r.Crossings} crossings sank");
            Assert.True(r.InLayer == 0, $"{label}: B in A's layer at {r.InLayer} of {r.Crossings}");
            Assert.True(r.LengthError <= 2 * without.LengthError + 0.01, $"{label}: segment length error {r.LengthError:P2}, {without.LengthError:P2} without contacts");
            Assert.Equal(0, r.NonFinite);
        }
    }

    [Fact]
    public void Contacts_give_the_same_bits_on_one_two_and_three_threads()
    {
        float[]? first = null;
        foreach (int threads in new[] { 1, 2, 3 })
        {
            var scene = CrossingSheets.Scene(new VolumeSettings(), SolverPath.Fast, contacts: new StrandContactSettings());
            using var d = new ParallelDispatcher(threads);
            var sim = new HairSimulation(scene, dispatcher: d);
            for (int f = 0; f < 90; f++) sim.Step(1f / 60);
            var bits = scene.World.Buffers().SelectMany(b => b).ToArray();
            if (first == null) first = bits;
            else Assert.Equal(first, bits);
        }
    }

    [Fact]
    public void Bad_contact_settings_are_refused_before_anything_moves()
    {
        foreach (var bad in new[]
        {
            new StrandContactSettings { Thickness = float.NaN }, new StrandContactSettings { Thickness = 0f },
            new StrandContactSettings { Thickness = 11f }, new StrandContactSettings { Iterations = 0 },
            new StrandContactSettings { Iterations = 65 }, new StrandContactSettings { Restitution = -0.1f },
            new StrandContactSettings { Restitution = float.PositiveInfinity },
        })
        {
            var scene = CrossingSheets.Scene(null, SolverPath.Fast, contacts: bad);
            var sim = new HairSimulation(scene);
            var before = scene.World.Buffers().Select(b => (float[])b.Clone()).ToArray();
            Assert.Throws<ArgumentOutOfRangeException>(() => sim.Step(1f / 60));
            Assert.Equal(before, scene.World.Buffers());
        }
    }

    [Fact]
    public void A_full_head_of_hair_is_refused_with_a_message_and_left_as_it_was()
    {
        // The reference groom: 435 sheets over one another hold hundreds of candidate pairs per segment, more than any
        // per-pair method affords each frame; volume is the tool there. Refused at the first frame, nothing moved.
        var scene = GroomBuilder.BuildScene(GroomSettings.Reference(), new SimulationSettings());
        scene.SetComponent(new StrandContactSettings());
        var sim = new HairSimulation(scene);
        var before = scene.World.Buffers().Select(b => (float[])b.Clone()).ToArray();
        var e = Assert.Throws<InvalidOperationException>(() => sim.Step(1f / 60));
        Assert.Contains("VolumeSettings", e.Message);
        Assert.Equal(before, scene.World.Buffers());
        // Without contacts the same groom steps.
        scene.RemoveComponent<StrandContactSettings>();
        sim.Step(1f / 60);
        Assert.Equal(0, scene.World.CountNonFinite());
    }

    [Fact]
    public void Extreme_contact_settings_stay_finite_at_every_scale_and_frame_rate()
    {
        foreach (float scale in new[] { 0.04f, 40f })
        foreach (int hz in new[] { 30, 240 })
        foreach (var contacts in new[]
        {
            new StrandContactSettings { Thickness = 1f, Iterations = 64, Restitution = 1f },
            new StrandContactSettings { Thickness = 0.01f, Iterations = 1 },
        })
        {
            var r = CrossingSheets.Run(new VolumeSettings { Stiffness = 1000f, Friction = 1000f }, SolverPath.Fast, hz, scale: scale, contacts: contacts);
            Assert.Equal(0, r.NonFinite);
        }
    }

    [Fact]
    public void A_teleport_frame_carries_the_hair_without_contacts()
    {
        // On a teleport the hair is carried rigidly with the head: contacts must not judge that jump as a crossing.
        var scene = CrossingSheets.Scene(null, SolverPath.Fast, contacts: new StrandContactSettings());
        var sim = new HairSimulation(scene);
        for (int f = 0; f < 30; f++) sim.Step(1f / 60);
        sim.Step(1f / 60, new RigidTransform(new Vector3(5f, 0f, 0f), Quaternion.CreateFromAxisAngle(Vector3.UnitY, 2f)));
        Assert.True(sim.Pipeline.LastFrame.Teleported);
        var system = (StrandContactSystem)sim.Pipeline.Systems.Single(s => s.Name == StrandContactSystem.SystemName);
        Assert.Equal(default, system.LastPass);
    }
}
