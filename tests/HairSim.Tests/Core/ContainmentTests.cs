using System.Numerics;
using HairSim.Tests.Fast;

namespace HairSim.Tests.Core;

/// <summary>
/// A non-finite value met during a step (a custom system, a bug, a buffer written by hand) is contained at the end of
/// the frame: the strand holding it is put back at its rest pose on the head, at rest, the frame's report names it,
/// and every other strand steps on exactly as in a run without it.
/// </summary>
[Collection(nameof(AllocationCollection))] // allocation is measured here too
public class ContainmentTests
{
    /// <summary>A user's system with a bug: while armed, it writes NaN (or ∞) into one particle of one strand in the last substep.</summary>
    private sealed class Saboteur(int strand, int particle, float value, bool velocity) : IHairSystem
    {
        public bool Armed;
        public string Name => "Saboteur";
        public SystemPhase Phase => SystemPhase.Substep;

        public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
        {
            if (!Armed || substep != ctx.Substeps - 1 || strand < begin || strand >= end) return;
            int i = scene.World.StrandFirst[strand] + particle;
            if (velocity) scene.World.VelY[i] = value; else scene.World.PosX[i] = value;
        }
    }

    private static (HairSimulation Sim, Saboteur Saboteur) Build(SolverPath path, IThreadDispatcher? dispatcher, int strand, float value = float.NaN, bool velocity = false)
    {
        var scene = GroomBuilder.BuildScene(new GroomSettings { SheetCount = 8, StrandsPerSheet = 6, ParticlesPerStrand = 12 }, new SimulationSettings { Path = path });
        var saboteur = new Saboteur(strand, 5, value, velocity);
        var builder = PipelineBuilder.CreateDefault().Add(new SystemFactory(saboteur.Name, SystemPhase.Substep, 320, _ => true, _ => saboteur));
        return (new HairSimulation(scene, builder, dispatcher), saboteur);
    }

    private static RigidTransform HeadAt(int f) => new(new Vector3(0.02f * MathF.Sin(f / 9f), 0f, 0f), Quaternion.CreateFromYawPitchRoll(0.5f * MathF.Sin(f / 13f), 0f, 0f));

    public static TheoryData<SolverPath, int, string> Cases()
    {
        var d = new TheoryData<SolverPath, int, string>();
        foreach (var path in new[] { SolverPath.Reference, SolverPath.Fast })
            foreach (int threads in new[] { 1, 2 })
                foreach (var value in new[] { "nan-position", "inf-position", "nan-velocity" })
                    d.Add(path, threads, value);
        return d;
    }

    [Theory]
    [MemberData(nameof(Cases))]
    public void A_strand_a_custom_system_makes_non_finite_is_reset_to_rest_and_the_rest_of_the_scene_steps_on_bit_for_bit(SolverPath path, int threads, string bad)
    {
        const int strand = 17, injectAt = 20, frames = 40;
        float value = bad == "inf-position" ? float.PositiveInfinity : float.NaN;
        bool velocity = bad == "nan-velocity";
        using var d1 = new ParallelDispatcher(threads);
        using var d2 = new ParallelDispatcher(threads);
        var (sim, saboteur) = Build(path, d1, strand, value, velocity);
        var (control, _) = Build(path, d2, strand); // the same pipeline, never armed
        var w = sim.World;
        for (int f = 1; f <= frames; f++)
        {
            saboteur.Armed = f == injectAt;
            sim.Step(1f / 60f, HeadAt(f));
            control.Step(1f / 60f, HeadAt(f));
            Assert.Equal(0, w.CountNonFinite());
            var report = sim.LastFrameReport;
            if (f != injectAt) { Assert.Equal(0, report.StrandsReset); continue; }
            // Named once, with the reason.
            Assert.Equal(1, report.StrandsReset);
            Assert.Equal([strand], report.ResetStrands.ToArray());
            // The reason is what the frame's end found: a NaN position the bend sweep has since placed again from its
            // parent leaves a NaN velocity (the sweep's Δx/h) behind, so the reason may name the velocity only.
            Assert.NotEqual(StrandResetReason.None, report.ResetReasons[0]);
            Assert.Equal(report.ResetReasons[0], report.Reasons);
            Assert.False(report.Truncated);
            // Back at its rest pose under the frame's head, at rest.
            var head = HeadAt(f);
            Assert.Equal(head, w.Head);
            for (int k = 0; k < w.StrandCapacity[strand]; k++)
            {
                int i = w.StrandFirst[strand] + k;
                Assert.Equal(head.TransformPoint(w.GetRest(i)), w.GetPosition(i));
                Assert.Equal(Vector3.Zero, w.GetVelocity(i));
            }
            // Every other strand is bit for bit where the control run has it.
            AssertOtherStrandsBitEqual(w, control.World, strand);
        }
        Assert.Equal(1, sim.StrandsResetTotal);
        AssertOtherStrandsBitEqual(w, control.World, strand);
        // The reset strand steps on: it moved with the head after the reset, and differs from its rest pose.
        float moved = 0f;
        for (int k = 1; k < w.StrandParticleCount[strand]; k++)
        {
            int i = w.StrandFirst[strand] + k;
            moved = MathF.Max(moved, Vector3.Distance(w.GetPosition(i), w.Head.TransformPoint(w.GetRest(i))));
        }
        Assert.True(moved > 1e-4f, $"the reset strand did not step on (moved {moved} m from its rest pose)");
    }

    private static void AssertOtherStrandsBitEqual(HairWorld a, HairWorld b, int except)
    {
        float[][] x = a.Buffers(), y = b.Buffers();
        for (int s = 0; s < a.StrandCount; s++)
        {
            if (s == except) continue;
            for (int i = a.StrandFirst[s]; i < a.StrandFirst[s] + a.StrandCapacity[s]; i++)
                for (int k = 0; k < 6; k++)
                    if (BitConverter.SingleToInt32Bits(x[k][i]) != BitConverter.SingleToInt32Bits(y[k][i]))
                        Assert.Fail($"strand {s}, particle {i - a.StrandFirst[s]}, buffer {k}: {x[k][i]} vs {y[k][i]} without the injection");
        }
    }

    [Theory]
    [InlineData(SolverPath.Reference)]
    [InlineData(SolverPath.Fast)]
    public void A_buffer_written_by_hand_between_frames_is_contained_on_the_strand_chunk_path_too(SolverPath path)
    {
        // No custom system: on the fast path with AVX-512 the frame runs on strand chunks (the injected NaN rides in a chunk lane).
        var scene = FastPathScenes.Build("rest", path);
        var control = FastPathScenes.Build("rest", path);
        var sim = new HairSimulation(scene);
        var sim2 = new HairSimulation(control);
        var w = scene.World;
        if (path == SolverPath.Fast && HairSim.Fast.FastPathInfo.Avx512) Assert.True(sim.Pipeline.UsesStrandChunks);
        for (int f = 1; f <= 12; f++) { sim.Step(1f / 60f, FastPathScenes.HeadAt(f)); sim2.Step(1f / 60f, FastPathScenes.HeadAt(f)); }
        int[] victims = [3, 64, 65, w.StrandCount - 1];
        foreach (int s in victims) w.PosY[w.StrandFirst[s] + 7] = float.NaN; // bypassing the setters, as a bug would
        w.VelZ[w.StrandFirst[100] + 2] = float.NegativeInfinity;
        sim.Step(1f / 60f, FastPathScenes.HeadAt(13));
        sim2.Step(1f / 60f, FastPathScenes.HeadAt(13));
        Assert.Equal(0, w.CountNonFinite());
        Assert.Equal(5, sim.LastFrameReport.StrandsReset);
        Assert.Equal([3, 64, 65, 100, w.StrandCount - 1], sim.LastFrameReport.ResetStrands.ToArray());
        Assert.True(sim.LastFrameReport.Reasons.HasFlag(StrandResetReason.NonFiniteVelocity));
        for (int s = 0; s < w.StrandCount; s++)
        {
            if (s is 3 or 64 or 65 or 100 || s == w.StrandCount - 1) continue;
            for (int i = w.StrandFirst[s]; i < w.StrandFirst[s] + w.StrandCapacity[s]; i++)
                Assert.True(w.GetPosition(i) == control.World.GetPosition(i) && w.GetVelocity(i) == control.World.GetVelocity(i), $"strand {s} changed");
        }
        for (int f = 14; f <= 30; f++) { sim.Step(1f / 60f, FastPathScenes.HeadAt(f)); Assert.Equal(0, sim.LastFrameReport.StrandsReset); }
        Assert.Equal(0, w.CountNonFinite());
    }

    [Fact]
    public void More_reset_strands_than_the_report_lists_are_still_counted()
    {
        var scene = GroomBuilder.BuildScene(new GroomSettings { SheetCount = 20, StrandsPerSheet = 10, ParticlesPerStrand = 6 });
        var sim = new HairSimulation(scene);
        sim.Step(1f / 60f);
        var w = scene.World;
        for (int s = 0; s < 150; s++) w.VelX[w.StrandFirst[s] + 4] = float.NaN; // a free particle
        sim.Step(1f / 60f);
        var r = sim.LastFrameReport;
        Assert.Equal(150, r.StrandsReset);
        Assert.True(r.Truncated);
        Assert.Equal(Enumerable.Range(0, FrameReport.MaxListed).ToArray(), r.ResetStrands.ToArray());
        Assert.Contains("150 strand(s) reset", r.ToString());
        Assert.Equal(0, w.CountNonFinite());
    }

    [Theory]
    [InlineData(1)]
    [InlineData(2)]
    public void Containment_allocates_nothing_even_on_frames_that_reset_strands(int threads)
    {
        using var dispatcher = new ParallelDispatcher(threads);
        var (sim, saboteur) = Build(SolverPath.Fast, dispatcher, 9);
        saboteur.Armed = true; // every frame
        for (int f = 1; f <= 30; f++) sim.Step(1f / 60f, HeadAt(f));
        Assert.Equal(1, sim.LastFrameReport.StrandsReset);
        // The stepping thread (the workers' allocations are covered by FastAllocationTests' per-thread probe).
        long before = GC.GetAllocatedBytesForCurrentThread();
        for (int f = 31; f <= 50; f++) sim.Step(1f / 60f, HeadAt(f));
        Assert.Equal(0, GC.GetAllocatedBytesForCurrentThread() - before);
        Assert.Equal(50, sim.StrandsResetTotal);
    }
}
