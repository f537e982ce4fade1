using System.Numerics;
using HairSim.Fast;
using HairSim.Measurement;
using HairSim.Meshes;
using Xunit;

namespace HairSim.Tests.Meshes;

/// <summary>
/// Mesh collision on strand chunks (<see cref="FastMeshCollideSystem"/>): the same bits as the reference
/// <see cref="MeshCollideSystem"/> (whole and cut strands, one and two threads), the brick bounds it skips samples
/// with, thin parts not tunnelled, and the penetration bound on the project's head.
/// </summary>
public sealed class FastMeshCollideTests
{
    private static readonly Lazy<(TriangleMesh Mesh, SignedDistanceField Field)> Head = new(() =>
    {
        var mesh = ProceduralHead.Create();
        return (mesh, SignedDistanceField.Bake(mesh, 0.0025f));
    });

    private static bool ChunksExpected => FastPathInfo.Avx512 && System.Runtime.Intrinsics.X86.Avx2.IsSupported;

    /// <summary>Hair grown on the project's head: 48 sheets × 16 strands (24 chunks), colliding with the mesh only.</summary>
    private static HairScene MeshScene(int sheets = 48)
    {
        var (mesh, field) = Head.Value;
        return MeshScalp.BuildScene(mesh, field, new MeshGroomSettings { SheetCount = sheets, StrandsPerSheet = 16, ScalpMaskThreshold = 0.5f },
            new SimulationSettings { Path = SolverPath.Fast });
    }

    [Theory]
    [InlineData(false, 1)]
    [InlineData(false, 2)]
    [InlineData(true, 1)]
    [InlineData(true, 2)]
    public void ChunksGiveTheBitsOfTheReferenceMeshPass(bool cut, int threads)
    {
        var chunked = MeshScene();
        var plain = MeshScene();
        if (cut)
            foreach (var w in new[] { chunked.World, plain.World })
            {
                // Cuts leave 2 … 16 live particles (a deterministic spread; whole strands in between).
                for (int s = 0; s < w.StrandCount; s++) if (s % 3 != 0) w.StrandParticleCount[s] = 2 + (s * 7) % 15;
                w.MarkEdited();
            }
        using var dispatcher = new ParallelDispatcher(threads);
        var simC = new HairSimulation(chunked, dispatcher: dispatcher);
        var simP = new HairSimulation(plain, dispatcher: dispatcher);
        simP.Pipeline.UseStrandChunks = false;
        Assert.Contains(MeshCollideSystem.SystemName, simC.Pipeline.SystemNames);
        Assert.Equal(ChunksExpected, simC.Pipeline.UsesStrandChunks);
        int stepped = 0;
        for (int f = 1; f <= 40; f++)
        {
            simC.Step(1f / 60f, HeadMotion.Shake(f / 60f));
            simP.Step(1f / 60f, HeadMotion.Shake(f / 60f));
            stepped += simC.Pipeline.LastFrameChunks.Stepped;
            Assert.True(chunked.World.BitEquals(plain.World), $"cut {cut}, {threads} thread(s): the chunk and reference mesh passes differ after frame {f}");
        }
        Assert.Equal(0, chunked.World.CountNonFinite());
        if (ChunksExpected) Assert.True(stepped >= 40 * 24 / (cut ? 3 : 1), $"only {stepped} chunks stepped");
#if DEBUG
        // The bits above came through rows settled with bounds and rows measured later for a decision, not only through
        // exact samples (debug builds count them; other tests running meanwhile can only add to the counts).
        if (ChunksExpected)
        {
            Assert.True(FastMeshCollideSystem.Counts.BoundedRows > 0, "no row was settled with bounds");
            Assert.True(FastMeshCollideSystem.Counts.Measured > 0, "no bounded row was measured for a decision");
        }
#endif
    }

    /// <summary>The same grid with every distance <paramref name="by"/> less: the head that much thicker.</summary>
    private static SignedDistanceField Thicker(SignedDistanceField field, float by)
    {
        var data = (float[])field.Data.Clone();
        for (int i = 0; i < data.Length; i++) data[i] -= by;
        return SignedDistanceField.FromData(field.Origin, field.CellSize, field.Nx, field.Ny, field.Nz, data);
    }

    [Fact]
    public void ClearancesSurviveChunksStartingElsewhereAfterAnEdit()
    {
        // Records are kept per particle slot in the chunk's row layout. With 20-particle strands, chunks that start 3
        // strands later (a freed strand refuses the first chunk) lay their rows 7.5 rows off the old ones: records
        // read there would mix one row's x with another's distance. The chunk path must keep the reference's bits.
        var (mesh, field) = Head.Value;
        HairScene Build() => MeshScalp.BuildScene(mesh, field,
            new MeshGroomSettings { SheetCount = 8, StrandsPerSheet = 16, ParticlesPerStrand = 20, ScalpMaskThreshold = 0.5f },
            new SimulationSettings { Path = SolverPath.Fast });
        var chunked = Build();
        var plain = Build();
        var simC = new HairSimulation(chunked, dispatcher: SequentialDispatcher.Instance);
        var simP = new HairSimulation(plain, dispatcher: SequentialDispatcher.Instance);
        simP.Pipeline.UseStrandChunks = false;
        int stepped = 0;
        for (int f = 1; f <= 40; f++)
        {
            if (f == 16)
                foreach (var w in new[] { chunked.World, plain.World })
                {
                    // Strand 2 let go: held by nothing, it leaves the chunk path, and chunks start from strand 3.
                    int first = w.StrandFirst[2];
                    float free = w.InvMass[first + w.StrandParticleCount[2] - 1];
                    for (int i = first; i < first + w.StrandParticleCount[2]; i++) w.InvMass[i] = free;
                    w.MarkEdited();
                }
            simC.Step(1f / 60f, HeadMotion.Shake(f / 60f));
            simP.Step(1f / 60f, HeadMotion.Shake(f / 60f));
            if (f > 16) stepped += simC.Pipeline.LastFrameChunks.Stepped;
            Assert.True(chunked.World.BitEquals(plain.World), $"the chunk and reference mesh passes differ after frame {f}");
        }
        Assert.True(chunked.World.IsFreeStrand(2));
        if (ChunksExpected) Assert.True(stepped >= 24 * 3, $"only {stepped} chunks stepped after the edit");
    }

    [Fact]
    public void TwoScenesWithDifferentFieldsOnOneThreadKeepTheReferenceBits()
    {
        // The chunk kernel remembers each row's last gathered cells per thread and mesh slot: a scene whose field is
        // another on the same grid (the head 1.5 mm thicker) must not read the first scene's values, stepped in turn on one thread.
        var (mesh, field) = Head.Value;
        var coarse = Thicker(field, 0.0015f);
        HairScene Build(SignedDistanceField f)
        {
            // One chunk (2 × 16 strands), so each scene's chunk finds the rows the other scene's chunk left.
            var scene = MeshScalp.BuildScene(mesh, field, new MeshGroomSettings { SheetCount = 2, StrandsPerSheet = 16, ScalpMaskThreshold = 0.5f },
                new SimulationSettings { Path = SolverPath.Fast });
            var grown = scene.GetComponent<MeshCollider>()!;
            scene.SetComponent(new MeshCollider(f, grown.Margin, mesh));
            return scene;
        }
        var scenes = new[] { Build(field), Build(coarse), Build(field), Build(coarse) };
        var sims = scenes.Select(s => new HairSimulation(s, dispatcher: SequentialDispatcher.Instance)).ToArray();
        sims[2].Pipeline.UseStrandChunks = false;
        sims[3].Pipeline.UseStrandChunks = false;
        for (int f = 1; f <= 20; f++)
        {
            foreach (var sim in sims) sim.Step(1f / 60f, HeadMotion.Shake(f / 60f));
            Assert.True(scenes[0].World.BitEquals(scenes[2].World), $"first field: chunks and the reference pass differ after frame {f}");
            Assert.True(scenes[1].World.BitEquals(scenes[3].World), $"thicker field: chunks and the reference pass differ after frame {f}");
        }
    }

    [Fact]
    public void ClearancesCarriedFromFrameToFrameKeepTheReferenceBitsThroughNewFieldsMarginsAndRestLengths()
    {
        // A chunk's first substep settles far rows on the distances its last frame measured (facts about one field):
        // through a thicker head, a wider margin and longer segments (a larger far distance), the chunk path must keep
        // the reference's bits.
        var (mesh, field) = Head.Value;
        var thicker = Thicker(field, 0.02f);
        var chunked = MeshScene(8);
        var plain = MeshScene(8);
        var simC = new HairSimulation(chunked, dispatcher: SequentialDispatcher.Instance);
        var simP = new HairSimulation(plain, dispatcher: SequentialDispatcher.Instance);
        simP.Pipeline.UseStrandChunks = false;
        float margin = chunked.GetComponent<MeshCollider>()!.Margin;
        int stepped = 0;
        for (int f = 1; f <= 40; f++)
        {
            foreach (var scene in new[] { chunked, plain })
            {
                if (f == 11) scene.SetComponent(new MeshCollider(thicker, margin, mesh));
                if (f == 21) scene.SetComponent(new MeshCollider(field, 3f * margin, mesh));
                if (f == 31)
                {
                    var w = scene.World;
                    for (int i = 0; i < w.ParticleCount; i++) w.RestLength[i] *= 3f;
                    w.MarkEdited();
                }
            }
            simC.Step(1f / 60f, HeadMotion.Shake(f / 60f));
            simP.Step(1f / 60f, HeadMotion.Shake(f / 60f));
            stepped += simC.Pipeline.LastFrameChunks.Stepped;
            Assert.True(chunked.World.BitEquals(plain.World), $"the chunk and reference mesh passes differ after frame {f}");
        }
        if (ChunksExpected) Assert.True(stepped >= 40 * 4, $"only {stepped} chunks stepped");
        // The thicker head and the wider margin changed the hair: the swaps were felt, not idle.
        Assert.False(MeshScene(8).World.BitEquals(chunked.World));
    }

    [Fact]
    public void MeshCollisionAllocatesNothingPerStep()
    {
        var scene = MeshScene();
        var sim = new HairSimulation(scene);
        for (int f = 1; f <= 40; f++) sim.Step(1f / 60f, HeadMotion.Shake(f / 60f));
        Action<int> step = f => sim.Step(1f / 60f, HeadMotion.Shake(f / 60f));
        Assert.Equal(0, Allocation.InQuieterWindow(step, 41, 20));
    }

    [Fact]
    public void BricksBoundTheFieldFromBelowAndTheSampleIsTheReferences()
    {
        var field = Head.Value.Field;
        var rng = new Random(18);
        var lo = field.Origin - new Vector3(0.01f);
        var size = new Vector3(field.Nx, field.Ny, field.Nz) * field.CellSize + new Vector3(0.02f);
        int inside = 0;
        for (int n = 0; n < 200_000; n++)
        {
            var p = lo + size * new Vector3(rng.NextSingle(), rng.NextSingle(), rng.NextSingle());
            float d = field.Distance(p);
            Assert.Equal(d, field.Sample(p, out _));
            var g = (p - field.Origin) * field.InvCell;
            if (!(g.X >= 0f && g.Y >= 0f && g.Z >= 0f && g.X < field.Nx - 1 && g.Y < field.Ny - 1 && g.Z < field.Nz - 1))
            {
                Assert.True(d >= field.Band, $"outside the grid {d} is below the band");
                continue;
            }
            inside++;
            float bound = field.BrickBound((int)g.X, (int)g.Y, (int)g.Z);
            Assert.True(bound <= d, $"brick bound {bound} above the field {d} at {p}");
            Assert.True(bound > d - 0.02f, $"brick bound {bound} far below the field {d} at {p}: the bricks are not the cells'");
        }
        Assert.True(inside > 100_000);
    }

    [Fact]
    public void ASegmentAcrossAThinRimRidesOverItInAChunk()
    {
        // An ear-like slab 4 mm thick; 32 strands (one chunk) whose second segment crosses it 1 mm below its rim:
        // neither end is inside, only the segment's middle is. Chunks must lift every one of them as the reference does.
        var slab = TriangleMesh.Box(new Vector3(-0.002f, -0.05f, -0.05f), new Vector3(0.002f, 0f, 0.05f));
        var sdf = SignedDistanceField.Bake(slab, 0.0005f);
        HairScene Build()
        {
            var world = new HairWorld(1, 32, 16);
            for (int s = 0; s < 32; s++)
            {
                float z = -0.03f + 0.002f * s;
                var points = new Vector3[16];
                points[0] = new Vector3(-0.008f, 0.02f, z);
                points[1] = new Vector3(-0.008f, -0.001f, z);
                for (int k = 2; k < 16; k++) points[k] = new Vector3(-0.008f + 0.016f * (k - 1), -0.001f - 0.0001f * s, z);
                world.SetStrand(s, points, pinned: 1);
            }
            world.ResetToRest();
            var scene = new HairScene(world, new SimulationSettings { Path = SolverPath.Fast });
            scene.SetComponent(new MeshCollider(sdf));
            return scene;
        }
        var only = new PipelineBuilder();
        foreach (var f in PipelineBuilder.CreateDefault().Factories) if (f.Name == MeshCollideSystem.SystemName) only.Add(f);
        var chunked = Build();
        var plain = Build();
        var pc = only.Build(chunked);
        var pp = only.Build(plain);
        pp.UseStrandChunks = false;
        Assert.Equal(ChunksExpected, pc.UsesStrandChunks);
        var w = chunked.World;
        for (int s = 0; s < 32; s++)
            Assert.True(sdf.Distance(0.5f * (w.GetPosition(w.StrandFirst[s] + 1) + w.GetPosition(w.StrandFirst[s] + 2))) < -1e-4f);
        pc.Step(1f / 60f, RigidTransform.Identity);
        pp.Step(1f / 60f, RigidTransform.Identity);
        if (ChunksExpected) Assert.Equal(1, pc.LastFrameChunks.Stepped);
        Assert.True(w.BitEquals(plain.World), "chunk and reference differ");
        for (int s = 0; s < 32; s++)
        {
            int f = w.StrandFirst[s];
            for (int k = 1; k < 16; k++)
                Assert.True(sdf.Distance(0.5f * (w.GetPosition(f + k - 1) + w.GetPosition(f + k))) > -1e-4f, $"strand {s}: segment {k}'s middle is in the rim");
        }
    }

    [Theory]
    [InlineData(true)]
    [InlineData(false)]
    public void HairFallingOnAThinRimDrapesOverItInsteadOfThroughIt(bool chunks)
    {
        // An ear seen edge-on: a slab 4 mm thick, far thinner than the 16.7 mm segments. 32 limp strands (one chunk) lie
        // 3 mm above its rim, each pinned at its root on one side with its first free particle on the other, so as the
        // strand falls its first segment swings down across the rim; only that segment's midpoint sees the slab. The
        // strands must drape over the rim, not pass through it.
        var slab = TriangleMesh.Box(new Vector3(-0.002f, -0.1f, -0.05f), new Vector3(0.002f, 0f, 0.05f));
        var sdf = SignedDistanceField.Bake(slab, 0.0005f);
        const float L = 0.0167f;
        var world = new HairWorld(1, 32, 16);
        for (int s = 0; s < 32; s++)
        {
            var points = new Vector3[16];
            for (int k = 0; k < 16; k++) points[k] = new Vector3(-0.0083f + k * L, 0.003f, -0.03f + 0.002f * s);
            world.SetStrand(s, points, pinned: 1);
        }
        world.ResetToRest();
        var scene = new HairScene(world, new SimulationSettings { Path = SolverPath.Fast, Bend = BendModel.Limp });
        scene.SetComponent(new MeshCollider(sdf));
        var sim = new HairSimulation(scene);
        sim.Pipeline.UseStrandChunks = chunks;
        Assert.Equal(chunks && ChunksExpected, sim.Pipeline.UsesStrandChunks);
        // How deep the strands' segments reach into the slab: through it is 2 mm (its middle plane) or more.
        float Deepest()
        {
            float deepest = 0f;
            for (int s = 0; s < 32; s++)
            {
                int first = world.StrandFirst[s];
                for (int i = first + 1; i < first + 16; i++)
                    for (int t = 0; t <= 16; t++)
                        deepest = MathF.Max(deepest, -sdf.Distance(Vector3.Lerp(world.GetPosition(i - 1), world.GetPosition(i), t / 16f)));
            }
            return deepest;
        }
        float falling = 0f;
        for (int f = 1; f <= 90; f++)
        {
            sim.Step(1f / 60f, RigidTransform.Identity);
            falling = MathF.Max(falling, Deepest());
        }
        Assert.Equal(0, world.CountNonFinite());
        for (int s = 0; s < 32; s++)
        {
            int first = world.StrandFirst[s];
            Assert.True(world.GetPosition(first + 15).Y < -0.05f, $"strand {s} did not fall: the test sees nothing");
            Assert.True(world.GetPosition(first + 15).X > 0.002f, $"strand {s}'s tip is on the root's side of the rim: it went through");
        }
        // Without the midpoint tests the first segment cuts through the slab (2.00 mm); with them it rides on the rim.
        Assert.True(falling < 1.9f * 0.001f, $"a segment went {falling * 1000:F2} mm into the 4 mm rim while falling");
        float resting = Deepest();
        Assert.True(resting < 0.001f, $"a segment rests {resting * 1000:F2} mm inside the rim (target: below 1 mm)");
    }

    [Fact]
    public void NoSegmentPassesThroughAnEarAndPenetrationStaysBelowAMillimetreOnChunks()
    {
        // The project's head: hair hangs beside the 8 mm ears while the head shakes for 3 s on the chunk path. Every
        // segment near an ear is checked at 7 inner points against the field: a segment across an ear would have its
        // middle points deep inside it while both its ends are out.
        var scene = MeshScene(120);
        var field = Head.Value.Field;
        using var dispatcher = new ParallelDispatcher(2);
        var sim = new HairSimulation(scene, dispatcher: dispatcher);
        Assert.Equal(ChunksExpected, sim.Pipeline.UsesStrandChunks);
        var w = scene.World;
        var ears = new[] { new Vector3(-0.079f, -0.008f, -0.006f), new Vector3(0.079f, -0.008f, -0.006f) };
        int nearEars = 0;
        float deepest = 0f, worstSegment = float.MaxValue;
        for (int f = 1; f <= 180; f++)
        {
            var head = HeadMotion.Shake(f / 60f);
            sim.Step(1f / 60f, head);
            if (f % 10 != 0) continue;
            var toLocal = Quaternion.Conjugate(head.Rotation);
            deepest = MathF.Max(deepest, (float)WorldMetrics.Measure(scene).MaxPenetration);
            for (int s = 0; s < w.StrandCount; s++)
            {
                int first = w.StrandFirst[s];
                for (int i = first + 1; i < first + w.StrandParticleCount[s]; i++)
                {
                    var a = Vector3.Transform(w.GetPosition(i - 1) - head.Position, toLocal);
                    var b = Vector3.Transform(w.GetPosition(i) - head.Position, toLocal);
                    var m = 0.5f * (a + b);
                    if (MathF.Min((m - ears[0]).Length(), (m - ears[1]).Length()) > 0.03f) continue;
                    nearEars++;
                    for (int t = 1; t < 8; t++) worstSegment = MathF.Min(worstSegment, field.Distance(Vector3.Lerp(a, b, t / 8f)));
                }
            }
        }
        Assert.Equal(0, w.CountNonFinite());
        Assert.True(nearEars > 1000, $"only {nearEars} segments came within 3 cm of an ear: the test sees nothing");
        // Through the 8 mm ear would be 4 mm; a segment's chord over the rounded rim clips it by up to about 1.5 mm.
        Assert.True(worstSegment > -0.002f, $"a segment passes through an ear: a point along it is {-worstSegment * 1000:F2} mm inside");
        Assert.True(deepest < 0.001f, $"deepest particle {deepest * 1000:F3} mm inside the mesh");
    }
}
