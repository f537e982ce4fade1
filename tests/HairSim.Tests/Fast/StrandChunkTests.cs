using System.Numerics;
using HairSim;
using HairSim.Fast;
using Xunit.Abstractions;

namespace HairSim.Tests.Fast;

/// <summary>
/// With AVX-512 the fast pipeline steps uncut 16-particle strands in 32-strand chunks (<see cref="StrandChunk"/>),
/// transposed into rows once per frame. Each chunk kernel does the arithmetic of its system's 16-lane path in the
/// same order, so a run with chunks must give exactly the bits of the same run system by system, in every scene:
/// those that chunks take whole, those they take in part (cuts, bends, short strands), and those they leave alone
/// (PBD, global stiffness).
/// </summary>
public class StrandChunkTests(ITestOutputHelper output)
{
    private static bool ChunksExpected => FastPathInfo.Avx512;

    [Theory]
    [MemberData(nameof(FastVsReferenceTests.Scenes), MemberType = typeof(FastVsReferenceTests))]
    public void ChunksGiveTheBitsOfTheSystemBySystemPath(string scene)
    {
        foreach (int threads in new[] { 1, 2 })
        {
            using var dispatcher = new ParallelDispatcher(threads);
            var (chunked, plain, simC, simP) = Twins(scene, dispatcher, p => p.UseStrandChunks = false);
            Assert.Equal(ChunksExpected, simC.Pipeline.UsesStrandChunks);
            Assert.False(simP.Pipeline.UsesStrandChunks);
            int stepped = 0;
            for (int f = 1; f <= 12; f++)
            {
                simC.Step(1f / 60f, FastPathScenes.HeadAt(f));
                simP.Step(1f / 60f, FastPathScenes.HeadAt(f));
                stepped += simC.Pipeline.LastFrameChunks.Stepped;
                Assert.True(chunked.World.BitEquals(plain.World), $"{scene}, {threads} thread(s): the paths differ after frame {f}");
            }
            Assert.Equal(0, simP.Pipeline.LastFrameChunks.Stepped);
            Assert.False(FastPathScenes.Build(scene, SolverPath.Fast).World.BitEquals(chunked.World));
            // Scenes whose settings every chunk kernel handles, with whole 16-particle strands: chunks must be used.
            bool chunkable = scene is "straight" or "sphere" or "capsule" or "rotated-ellipsoid" or "all-colliders" or "literal"
                or "length-none" or "speed-limit" or "one-pin" or "no-colliders"
                // The default bend model takes bent rest shapes in chunks too (only the source's triples refuse them).
                or "rest" or "rest-bent" or "rest-soft" or "rest-speed-limit" or "rest-all-colliders" or "limp"
                // and cut strands (particles past a cut ride along as pins and are put back as they were).
                or "rest-cut" or "rest-cut-mixed"
                // and strands of any capacity up to 64 (the rows past it masked like a cut).
                or "rest-short8" or "rest-p12" or "rest-p3" or "rest-p17" or "rest-p40" or "rest-p64";
            if (ChunksExpected && chunkable) Assert.True(stepped > 0, $"{scene}: no chunk was stepped");
            // No run of 32 whole 16-particle strands (cut, cut-mixed, short8), or settings the chunk kernels leave to the plain path.
            // The source's triples and length sweep keep cut strands on their own path.
            if (scene is "pbd" or "global-shape" or "short8" or "cut" or "cut-mixed") Assert.Equal(0, stepped);
            output.WriteLine($"{scene}, {threads} thread(s): {stepped} chunks over 12 frames");
        }
    }

    /// <summary>
    /// The "rest" scene stepped with chunks and system by system side by side for <paramref name="frames"/> frames,
    /// <paramref name="before"/> changing both (chunked scene, plain scene, chunked simulation, frame) ahead of each
    /// frame; asserts the same bits after every frame and returns the chunks stepped in each.
    /// </summary>
    private static int[] SideBySide(int frames, Action<HairScene, HairScene, HairSimulation, int> before)
    {
        var chunked = FastPathScenes.Build("rest", SolverPath.Fast);
        var plain = FastPathScenes.Build("rest", SolverPath.Fast);
        var simC = new HairSimulation(chunked);
        var simP = new HairSimulation(plain);
        simP.Pipeline.UseStrandChunks = false;
        var stepped = new int[frames + 1];
        for (int f = 1; f <= frames; f++)
        {
            before(chunked, plain, simC, f);
            simC.Step(1f / 60f, FastPathScenes.HeadAt(f));
            simP.Step(1f / 60f, FastPathScenes.HeadAt(f));
            stepped[f] = simC.Pipeline.LastFrameChunks.Stepped;
            Assert.True(chunked.World.BitEquals(plain.World), $"the paths differ after frame {f}");
        }
        return stepped;
    }

    [Fact]
    public void ChunksFollowSettingChangesAndBackAsTheSystemBySystemPathDoes()
    {
        // The bend sweep's chunks skip their per-strand cache checks while the settings, the edit stamp and every
        // strand's cache are as they were when the chunk was last checked. A change and a change back (substeps, so h;
        // Sag; damping), also one made while the chunks were off, must still reach every strand.
        var stepped = SideBySide(36, (chunked, plain, simC, f) =>
        {
            // Frame 30: the chunked simulation steps system by system (as a frame handed back does) with other substeps,
            // so the strands' caches change behind the chunks' backs; frame 31 goes back to chunks and to 4 substeps.
            simC.Pipeline.UseStrandChunks = f != 30;
            foreach (var st in new[] { chunked.Settings, plain.Settings })
            {
                st.Substeps = f is >= 6 and < 12 ? 5 : f == 30 ? 6 : 4;
                st.Sag = f is >= 16 and < 20 ? 0.05f : 0.01f;
                st.BendDamping = f is >= 24 and < 28 ? 2f * new SimulationSettings().BendDamping + 0.1f : new SimulationSettings().BendDamping;
            }
        });
        if (ChunksExpected) Assert.True(stepped.Sum() > 0);
    }

    [Fact]
    public void MassesAndRestLengthsEditedBetweenFramesReachTheChunksThatKeepThemInRows()
    {
        // Chunks keep their masses and rest lengths in row layout until the next edit (ChunkConstantRows): a pin added
        // in the middle of strands that stay in chunks, and rest lengths stretched, must reach them at the next frame.
        var stepped = SideBySide(16, (chunked, plain, _, f) =>
        {
            if (f != 6 && f != 11) return;
            foreach (var w in new[] { chunked.World, plain.World })
            {
                for (int s = 0; s < 64; s++)
                {
                    int first = w.StrandFirst[s], n = w.StrandParticleCount[s];
                    if (f == 6) w.InvMass[first + n / 2] = 0f; // a second pin, half way down
                    else for (int i = first + 1; i < first + n; i++) w.RestLength[i] *= 1.25f;
                }
                w.MarkEdited();
            }
        });
        if (ChunksExpected) Assert.All(stepped.Skip(1), n => Assert.True(n > 0, "every frame steps chunks"));
    }

    [Fact]
    public void AnEditBetweenFramesReachesTheChunksItTurnsAway()
    {
        // Which runs of strands make chunks is remembered per chunk until the next edit: strands an edit sets free (no
        // pin left: they leave the chunk path) must leave it at once, as on the system-by-system path.
        var stepped = SideBySide(16, (chunked, plain, _, f) =>
        {
            if (f != 8) return;
            foreach (var w in new[] { chunked.World, plain.World })
            {
                // Strands 40 and 100 lose their pins: the 144 strands then hold 3 runs of 32 without them, not 4.
                foreach (int s in new[] { 40, 100 })
                    for (int i = w.StrandFirst[s]; i < w.StrandFirst[s] + w.StrandParticleCount[s]; i++) w.InvMass[i] = 1f;
                w.MarkEdited();
            }
        });
        if (ChunksExpected) Assert.True(stepped[8] < stepped[7], $"{stepped[7]} chunks before the edit, {stepped[8]} after");
    }

    [Fact]
    public void ChunkWithCoincidingParticlesGoesBackToThePerStrandPathWithTheSameBits()
    {
        var chunked = FastPathScenes.Build("straight", SolverPath.Fast);
        var plain = FastPathScenes.Build("straight", SolverPath.Fast);
        foreach (var w in new[] { chunked.World, plain.World })
        {
            // Strand 40 (second chunk): particles 5 and 7 coincide, so triple 6 has no axis (the reference's fallback).
            int f = w.StrandFirst[40];
            w.SetPosition(f + 7, w.GetPosition(f + 5));
        }
        var (simC, simP) = Pair(chunked, plain);
        StepBoth(simC, simP, 1);
        Assert.Equal(0, chunked.World.CountNonFinite());
        if (!ChunksExpected) return;
        var (stepped, handedBack) = simC.Pipeline.LastFrameChunks;
        Assert.Equal(4, stepped); // 144 strands: chunks at 0, 32, 64, 96
        Assert.Equal(1, handedBack);
        for (int f = 2; f <= 6; f++) StepBoth(simC, simP, f);
    }

    [Fact]
    public void CutStrandInsideARunLeavesItsNeighboursInChunks()
    {
        var scene = FastPathScenes.Build("straight", SolverPath.Fast);
        var plain = FastPathScenes.Build("straight", SolverPath.Fast);
        foreach (var w in new[] { scene.World, plain.World })
        {
            w.StrandParticleCount[10] = 9;
            w.MarkEdited();
        }
        var (sim, simP) = Pair(scene, plain);
        StepBoth(sim, simP, 1);
        // 144 strands, strand 10 cut: chunks start at 11, 43, 75, 107 (strands 0 … 10 and 139 … 143 go system by system).
        if (ChunksExpected) Assert.Equal(4, sim.Pipeline.LastFrameChunks.Stepped);
    }

    [Fact]
    public void CutStrandsRideInChunksAndWhatIsPastTheCutStaysAsItWas()
    {
        var scene = FastPathScenes.Build("rest-cut", SolverPath.Fast);
        var w = scene.World;
        var before = w.Clone();
        var sim = new HairSimulation(scene);
        // Frames without a teleport (which carries everything, past cuts too, with the head: FastPathScenes.HeadAt(6)).
        for (int f = 1; f <= 5; f++)
        {
            sim.Step(1f / 60f, FastPathScenes.HeadAt(f));
            Assert.False(sim.Pipeline.LastFrame.Teleported);
        }
        // 144 strands, every one cut: four chunks of 32, each frame (the last 16 go system by system).
        if (ChunksExpected) Assert.Equal(4, sim.Pipeline.LastFrameChunks.Stepped);
        int live = 0, past = 0;
        for (int s = 0; s < w.StrandCount; s++)
        {
            int first = w.StrandFirst[s], n = w.StrandParticleCount[s];
            for (int i = first + 1; i < first + n; i++) if (w.GetPosition(i) != before.GetPosition(i)) live++;
            for (int i = first + n; i < first + w.StrandCapacity[s]; i++)
            {
                Assert.Equal(before.GetPosition(i), w.GetPosition(i));
                Assert.Equal(before.GetVelocity(i), w.GetVelocity(i));
                past++;
            }
        }
        Assert.True(past > 0 && live > 0, $"{past} particles past cuts, {live} live particles moved");
    }

    [Theory]
    [InlineData("rest-p12")]
    [InlineData("rest-p40")]
    public void ShorterAndLongerStrandsCutInChunksGiveTheBitsOfTheSystemBySystemPath(string scene)
    {
        var chunked = FastPathScenes.Build(scene, SolverPath.Fast);
        var plain = FastPathScenes.Build(scene, SolverPath.Fast);
        foreach (var w in new[] { chunked.World, plain.World })
        {
            // Live counts 2 … capacity: the rows past each cut and past the capacity masked alike.
            for (int s = 0; s < w.StrandCount; s++) w.StrandParticleCount[s] = 2 + (s * 5) % (w.StrandCapacity[s] - 1);
            w.MarkEdited();
        }
        var (simC, simP) = Pair(chunked, plain);
        for (int f = 1; f <= 5; f++) StepBoth(simC, simP, f);
        if (ChunksExpected) Assert.Equal(4, simC.Pipeline.LastFrameChunks.Stepped);
    }

    [Fact]
    public void ChunksNeedEverySubstepSystemToRunOnThem()
    {
        var scene = FastPathScenes.Build("straight", SolverPath.Fast);
        var builder = PipelineBuilder.CreateDefault();
        // A system from outside the core (a wind, say) that only knows the world: the pipeline must not chunk.
        builder.Add(new SystemFactory("wind", SystemPhase.Substep, 250, _ => true, _ => new Wind()));
        var sim = new HairSimulation(scene, builder);
        Assert.False(sim.Pipeline.UsesStrandChunks);
        sim.Step(1f / 60f, FastPathScenes.HeadAt(1));
        Assert.Equal(0, sim.Pipeline.LastFrameChunks.Stepped);
        Assert.False(new HairSimulation(FastPathScenes.Build("straight", SolverPath.Fast), PipelineBuilder.CreateDefault(allowAvx512: false)).Pipeline.UsesStrandChunks);
        Assert.False(new HairSimulation(FastPathScenes.Build("straight", SolverPath.Reference)).Pipeline.UsesStrandChunks);
    }

    /// <summary>Simulations of two copies of a scene, chunks on and off.</summary>
    [Theory]
    [InlineData("rest", 1)]
    [InlineData("rest", 2)]
    [InlineData("rest-speed-limit", 1)]
    [InlineData("rest-soft", 2)]
    [InlineData("rest-cut-mixed", 1)]
    [InlineData("rest-p3", 2)]
    [InlineData("rest-p40", 1)]
    [InlineData("limp", 1)]
    public void TheSweepThatIntegratesEachRowGivesTheBitsOfIntegrationsOwnPass(string scene, int threads)
    {
        if (!ChunksExpected) return; // chunks (and so the fused sweep) need AVX-512
        // Limp hair has no bend sweep to take the integration in.
        FusedAgainstApart(scene, threads, p => p.FuseChunkIntegration = false, p => p.FuseChunkIntegration,
            p => p.LastFrameIntegratedInSweep, taken: scene != "limp", "fused and apart");
    }

    [Theory]
    [InlineData("rest", 1)]
    [InlineData("rest", 2)]
    [InlineData("rest-bent", 2)]
    [InlineData("rest-rotated-ellipsoid", 1)]
    [InlineData("rest-cut-mixed", 1)]
    [InlineData("rest-p3", 2)]
    [InlineData("rest-p40", 1)]
    [InlineData("rest-all-colliders", 1)]
    public void TheCollisionOnTheSweepsNearRowsGivesTheBitsOfItsOwnPassOverEveryRow(string scene, int threads)
    {
        if (!ChunksExpected) return; // chunks (and so the sweep's row test) need AVX-512
        // Only one ellipsoid is taken (several colliders keep the collision's pass over every row).
        var (fused, simF) = FusedAgainstApart(scene, threads, p => p.FuseChunkFarRows = false, p => p.FuseChunkFarRows,
            p => p.LastFrameTestedFarRowsInSweep, taken: scene != "rest-all-colliders", "the sweep's near rows and the collision's own pass");
        // Not vacuous: the hair is both near the head (rows the collision takes) and far from it (rows it skips).
        var last = simF.Pipeline.LastFrame;
        var head = last.CollidersAt(last.Substeps - 1)[0]; // where the moving head was at the end of the last substep
        FastCollideSystem.FarSphere(head, out var centre, out float outer2);
        var w = fused.World;
        int near = 0;
        for (int i = 0; i < w.ParticleCount; i++)
        {
            var d = new System.Numerics.Vector3(w.PosX[i], w.PosY[i], w.PosZ[i]) - centre;
            if (d.LengthSquared() <= outer2) near++;
        }
        Assert.InRange(near, 1, w.ParticleCount - 1);
    }

    [Theory]
    [InlineData(1)]
    [InlineData(2)]
    public void ChunksCutShortInEveryStrandSweepOnlyTheirLiveRowsWithTheBitsOfTheSystemBySystemPath(int threads)
    {
        // Every strand keeps 2 … 6 of its 16 particles: rows 6 … 15 are past every lane's cut, and the chunk's sweeps
        // and per-particle passes stop before them (StrandChunk.LiveRows).
        using var dispatcher = new ParallelDispatcher(threads);
        var (chunked, _, simC, simP) = Twins("rest", dispatcher, p => p.UseStrandChunks = false, w =>
        {
            for (int s = 0; s < w.StrandCount; s++) w.StrandParticleCount[s] = 2 + s % 5;
            w.MarkEdited();
        });
        int stepped = 0;
        for (int f = 1; f <= 12; f++)
        {
            StepBoth(simC, simP, f);
            stepped += simC.Pipeline.LastFrameChunks.Stepped;
        }
        if (ChunksExpected) Assert.True(stepped > 0, "no chunk was stepped");
        Assert.False(FastPathScenes.Build("rest", SolverPath.Fast).World.BitEquals(chunked.World));
    }

    [Fact]
    public void ANonFiniteValuePastACutInAChunkIsContainedAsOnTheSystemBySystemPath()
    {
        // The runner scans a chunk's stored rows itself (past the cuts too), not the world's buffers after the job.
        var chunked = FastPathScenes.Build("rest-cut", SolverPath.Fast);
        var plain = FastPathScenes.Build("rest-cut", SolverPath.Fast);
        var (simC, simP) = Pair(chunked, plain);
        for (int f = 1; f <= 6; f++) StepBoth(simC, simP, f);
        var w = chunked.World;
        int victim = -1;
        for (int s = 0; s < w.StrandCount && victim < 0; s++) if (w.StrandParticleCount[s] < w.StrandCapacity[s]) victim = s;
        Assert.True(victim >= 0, "the scene has a cut strand");
        int past = w.StrandFirst[victim] + w.StrandCapacity[victim] - 1;
        chunked.World.VelX[past] = float.NaN;
        plain.World.VelX[past] = float.NaN;
        StepBoth(simC, simP, 7);
        if (ChunksExpected) Assert.True(simC.Pipeline.LastFrameChunks.Stepped > 0);
        Assert.Equal([victim], simC.LastFrameReport.ResetStrands.ToArray());
        Assert.Equal([victim], simP.LastFrameReport.ResetStrands.ToArray());
        Assert.Equal(0, w.CountNonFinite());
    }

    /// <summary>
    /// Two simulations of the same scene on one dispatcher, both worlds first edited alike (<paramref name="edit"/>), the
    /// second's pipeline then set apart (<paramref name="setSecond"/>).
    /// </summary>
    /// <summary>
    /// Twins of a scene, a pass fused in the first and apart in the second (<paramref name="apart"/>), stepped 12 frames:
    /// the same bits after every frame, the same chunks, the fusion taken in every frame of the first twin exactly when
    /// <paramref name="taken"/> and never in the second, some chunk stepped, and the hair moved. Returns the first twin.
    /// </summary>
    private static (HairScene Fused, HairSimulation SimFused) FusedAgainstApart(string scene, int threads, Action<HairPipeline> apart,
        Func<HairPipeline, bool> switchedOn, Func<HairPipeline, bool> tookIt, bool taken, string what)
    {
        using var dispatcher = new ParallelDispatcher(threads);
        var (fused, other, simF, simA) = Twins(scene, dispatcher, apart);
        Assert.True(switchedOn(simF.Pipeline));
        int stepped = 0;
        for (int f = 1; f <= 12; f++)
        {
            simF.Step(1f / 60f, FastPathScenes.HeadAt(f));
            simA.Step(1f / 60f, FastPathScenes.HeadAt(f));
            Assert.Equal(taken, tookIt(simF.Pipeline));
            Assert.False(tookIt(simA.Pipeline));
            Assert.Equal(simF.Pipeline.LastFrameChunks.Stepped, simA.Pipeline.LastFrameChunks.Stepped);
            stepped += simF.Pipeline.LastFrameChunks.Stepped;
            Assert.True(fused.World.BitEquals(other.World), $"{scene}, {threads} thread(s): {what} differ after frame {f}");
        }
        Assert.True(stepped > 0, $"{scene}: no chunk was stepped");
        Assert.False(FastPathScenes.Build(scene, SolverPath.Fast).World.BitEquals(fused.World));
        return (fused, simF);
    }

    private static (HairScene First, HairScene Second, HairSimulation SimFirst, HairSimulation SimSecond) Twins(
        string scene, ParallelDispatcher dispatcher, Action<HairPipeline> setSecond, Action<HairWorld>? edit = null)
    {
        var first = FastPathScenes.Build(scene, SolverPath.Fast);
        var second = FastPathScenes.Build(scene, SolverPath.Fast);
        edit?.Invoke(first.World);
        edit?.Invoke(second.World);
        var simFirst = new HairSimulation(first, dispatcher: dispatcher);
        var simSecond = new HairSimulation(second, dispatcher: dispatcher);
        setSecond(simSecond.Pipeline);
        return (first, second, simFirst, simSecond);
    }

    private static (HairSimulation Chunked, HairSimulation Plain) Pair(HairScene chunked, HairScene plain)
    {
        var p = new HairSimulation(plain);
        p.Pipeline.UseStrandChunks = false;
        return (new HairSimulation(chunked), p);
    }

    private static void StepBoth(HairSimulation chunked, HairSimulation plain, int frame)
    {
        chunked.Step(1f / 60f, FastPathScenes.HeadAt(frame));
        plain.Step(1f / 60f, FastPathScenes.HeadAt(frame));
        Assert.True(chunked.Scene.World.BitEquals(plain.Scene.World), $"the paths differ after frame {frame}");
    }

    private sealed class Wind : IHairSystem
    {
        public string Name => "wind";
        public SystemPhase Phase => SystemPhase.Substep;
        public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
        {
            var w = scene.World;
            for (int s = begin; s < end; s++)
                for (int i = w.StrandFirst[s]; i < w.StrandFirst[s] + w.StrandParticleCount[s]; i++)
                    if (w.InvMass[i] > 0f) w.VelX[i] += 0.01f;
        }
    }
}
