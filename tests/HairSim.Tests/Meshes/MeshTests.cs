using System.Numerics;
using System.Text;
using HairSim.Editing;
using HairSim.Meshes;
using HairSim.Measurement;
using Xunit;

namespace HairSim.Tests.Meshes;

/// <summary>
/// Mesh heads: reading OBJ and glTF, the baked signed distance field against analytic distances, collision with it
/// against the analytic ellipsoid, thin parts between two particles, and hair grown on a mesh's scalp.
/// </summary>
public sealed class MeshTests
{
    private static readonly Vector3 HeadRadii = new(0.078f, 0.1f, 0.095f);

    [Fact]
    public void FieldOfASphereMeshMatchesTheAnalyticDistanceInItsBand()
    {
        const float r = 0.1f, cell = 0.004f;
        var mesh = TriangleMesh.Ellipsoid(Vector3.Zero, new Vector3(r), 64, 128);
        var sdf = SignedDistanceField.Bake(mesh, cell);
        // The tessellation lies inside the sphere by at most r(1 − cos(π/64)) ≈ 0.12 mm; trilinear error ≲ cell²/(8r).
        float tolerance = 0.0003f + cell * cell / (4 * r);
        var rng = new Random(5);
        for (int k = 0; k < 2000; k++)
        {
            var dir = Vector3.Normalize(new Vector3(rng.NextSingle() - 0.5f, rng.NextSingle() - 0.5f, rng.NextSingle() - 0.5f));
            float radius = r + (rng.NextSingle() * 2 - 1) * 0.8f * sdf.Band;
            var p = dir * radius;
            float d = sdf.Sample(p, out var g);
            Assert.InRange(d - (radius - r), -tolerance, tolerance);
            Assert.True(Vector3.Dot(Vector3.Normalize(g), dir) > 0.98f, $"gradient {g} at {p}");
        }
        Assert.InRange(sdf.Distance(Vector3.Zero), -1.1f * r, -0.9f * r);   // deep inside: the chamfer continuation
        // Outside the grid: the field at the grid's nearest point plus the distance to it. Along an axis that is the
        // distance to the sphere (the grid ends 4 cells beyond it: the pad, of which the band is 3, then the chamfer).
        float gridEnd = sdf.Origin.X + (sdf.Nx - 1) * cell;
        float atEnd = sdf.Distance(new Vector3(gridEnd, 0, 0));
        foreach (float x in new[] { gridEnd + 0.001f, gridEnd + 0.05f, 0.5f })
        {
            float d = sdf.Distance(new Vector3(x, 0, 0));
            Assert.Equal(atEnd + (x - gridEnd), d, 1e-5f);
            Assert.InRange(d - (x - r), -tolerance, tolerance);
        }
        // Off a corner it is farther than the band, so hair there is never pushed.
        var corner = new Vector3(gridEnd + 0.01f, gridEnd + 0.01f, 0);
        Assert.True(sdf.Distance(corner) > sdf.Band);
    }

    [Fact]
    public void OutsideTheGridTheFieldGoesOnAsSteeplyAsInsideAtMost()
    {
        // The collision kernel's records rely on this: the field changes by at most √3 × a move, anywhere. Pairs of
        // points a few cells apart around the grid's boundary, many crossing it, and pairs a hair's breadth across it.
        var mesh = TriangleMesh.Ellipsoid(Vector3.Zero, new Vector3(0.08f, 0.1f, 0.09f), 32, 64);
        var sdf = SignedDistanceField.Bake(mesh, 0.004f);
        var lo = sdf.Origin;
        var hi = sdf.Origin + new Vector3(sdf.Nx - 1, sdf.Ny - 1, sdf.Nz - 1) * sdf.CellSize;
        var rng = new Random(27);
        int crossing = 0;
        for (int n = 0; n < 50_000; n++)
        {
            // A point within 3 cells of a random face of the grid, and a step of up to 3 cells from it.
            var p = lo + (hi - lo) * new Vector3(rng.NextSingle(), rng.NextSingle(), rng.NextSingle());
            int axis = rng.Next(3);
            float edge = rng.Next(2) == 0 ? lo[axis] : hi[axis];
            p[axis] = edge + (rng.NextSingle() * 2 - 1) * 3 * sdf.CellSize;
            var step = new Vector3(rng.NextSingle() - 0.5f, rng.NextSingle() - 0.5f, rng.NextSingle() - 0.5f) * 6 * sdf.CellSize;
            if (n % 4 == 0) step *= 1e-4f;
            var q = p + step;
            if (Inside(sdf, p) != Inside(sdf, q)) crossing++;
            float change = MathF.Abs(sdf.Distance(p) - sdf.Distance(q));
            Assert.True(change <= MathF.Sqrt(3f) * step.Length() * 1.0001f + 1e-6f, $"{change} between {p} and {q}, {step.Length()} apart");
        }
        Assert.True(crossing > 5_000, $"{crossing} pairs crossed the boundary");
    }

    private static bool Inside(SignedDistanceField sdf, Vector3 p)
    {
        var g = (p - sdf.Origin) / sdf.CellSize;
        return g.X >= 0 && g.Y >= 0 && g.Z >= 0 && g.X < sdf.Nx - 1 && g.Y < sdf.Ny - 1 && g.Z < sdf.Nz - 1;
    }

    [Fact]
    public void SignIsRightAtTheEdgesAndCornersOfABox()
    {
        var box = TriangleMesh.Box(new Vector3(-0.01f), new Vector3(0.01f));
        var sdf = SignedDistanceField.Bake(box, 0.001f);
        var rng = new Random(9);
        for (int k = 0; k < 3000; k++)
        {
            var p = new Vector3(rng.NextSingle() - 0.5f, rng.NextSingle() - 0.5f, rng.NextSingle() - 0.5f) * 0.026f;
            // Exact box distance at grid points is piecewise; compare signs away from the surface's cell.
            var q = Vector3.Abs(p) - new Vector3(0.01f);
            float exact = Vector3.Max(q, Vector3.Zero).Length() + MathF.Min(MathF.Max(q.X, MathF.Max(q.Y, q.Z)), 0f);
            if (MathF.Abs(exact) < 0.0015f) continue;
            Assert.Equal(MathF.Sign(exact), MathF.Sign(sdf.Distance(p)));
        }
    }

    [Fact]
    public void BadMeshesAndFieldsAreRefused()
    {
        Assert.Throws<ArgumentException>(() => new TriangleMesh([new(float.NaN, 0, 0), Vector3.UnitX, Vector3.UnitY], [0, 1, 2]));
        Assert.Throws<ArgumentException>(() => new TriangleMesh([Vector3.Zero, Vector3.UnitX, Vector3.UnitY], [0, 1, 3]));
        Assert.Throws<ArgumentException>(() => new TriangleMesh([Vector3.Zero, Vector3.UnitX, Vector3.UnitY], [0, 1]));
        Assert.Throws<ArgumentException>(() => new TriangleMesh([], []));
        var sphere = TriangleMesh.Ellipsoid(Vector3.Zero, new Vector3(1f), 8, 16);
        Assert.Throws<ArgumentOutOfRangeException>(() => SignedDistanceField.Bake(sphere, 1e-4f));   // billions of cells
        Assert.Throws<ArgumentOutOfRangeException>(() => SignedDistanceField.Bake(sphere, float.NaN));
        Assert.Throws<ArgumentOutOfRangeException>(() => new MeshCollider(SignedDistanceField.Bake(sphere, 0.1f), margin: 1f));
    }

    [Fact]
    public void ObjRoundTripsAndReadsQuadsNegativeIndicesAndColours()
    {
        var mesh = TriangleMesh.Box(new Vector3(-1, -2, -3), new Vector3(1, 2, 3));
        var text = new StringWriter();
        ObjReader.Write(text, mesh);
        var back = ObjReader.Read(new StringReader(text.ToString()));
        Assert.Equal(mesh.Positions, back.Positions);
        Assert.Equal(mesh.Indices, back.Indices);

        var quad = ObjReader.Read(new StringReader("# a quad\nv 0 0 0 1 0 0\nv 1 0 0 1 0 0\nv 1 1 0 0 1 0\nv 0 1 0 0 1 0\nvn 0 0 1\nf -4//1 -3//1 -2//1 -1//1\n"));
        Assert.Equal(2, quad.TriangleCount);
        Assert.Equal([0, 1, 2, 0, 2, 3], quad.Indices);
        Assert.Equal(new Vector4(0, 1, 0, 1), quad.Colors![2]);

        var path = Path.Combine(Path.GetTempPath(), $"hairsim-bad-{Guid.NewGuid():N}.obj");
        File.WriteAllText(path, "v 0 0 0\nv 1 0 0\nf 1 2 7\n");
        try
        {
            var e = Assert.Throws<InvalidDataException>(() => MeshFile.Load(path));
            Assert.Contains("line 3", e.Message);
        }
        finally { File.Delete(path); }
    }

    [Fact]
    public void GltfIsReadThroughSharpGltfWithNodeTransformsAndVertexColours()
    {
        var path = Path.Combine(Path.GetTempPath(), $"hairsim-{Guid.NewGuid():N}.gltf");
        File.WriteAllText(path, MinimalGltf(translation: new Vector3(0, 1.5f, 0)));
        try
        {
            var mesh = MeshFile.Load(path);
            Assert.Equal(1, mesh.TriangleCount);
            Assert.Equal(new Vector3(1, 1.5f, 0), mesh.Positions[1]);
            Assert.Equal(new Vector4(1, 0, 0, 1), mesh.Colors![0]);
            File.WriteAllText(path, "{ \"asset\": { \"version\": \"2.0\" }, \"meshes\": [ { \"primitives\": [ { \"attributes\": { \"POSITION\": 9 } } ] } ] }");
            Assert.Throws<InvalidDataException>(() => MeshFile.Load(path));
        }
        finally { File.Delete(path); }
    }

    /// <summary>One triangle with per-vertex colours, its node translated: a .gltf with the buffer as a data URI.</summary>
    private static string MinimalGltf(Vector3 translation)
    {
        var bytes = new List<byte>();
        void F(float f) => bytes.AddRange(BitConverter.GetBytes(f));
        foreach (var p in new[] { Vector3.Zero, Vector3.UnitX, Vector3.UnitY }) { F(p.X); F(p.Y); F(p.Z); }
        foreach (var c in new[] { new Vector4(1, 0, 0, 1), new Vector4(0, 1, 0, 1), new Vector4(0, 0, 1, 1) }) { F(c.X); F(c.Y); F(c.Z); F(c.W); }
        string uri = "data:application/octet-stream;base64," + Convert.ToBase64String(bytes.ToArray());
        return $$"""
        { "asset": { "version": "2.0" }, "scene": 0, "scenes": [ { "nodes": [0] } ],
          "nodes": [ { "mesh": 0, "translation": [{{translation.X}}, {{translation.Y}}, {{translation.Z}}] } ],
          "meshes": [ { "primitives": [ { "attributes": { "POSITION": 0, "COLOR_0": 1 }, "mode": 4 } ] } ],
          "buffers": [ { "byteLength": {{bytes.Count}}, "uri": "{{uri}}" } ],
          "bufferViews": [ { "buffer": 0, "byteOffset": 0, "byteLength": 36 }, { "buffer": 0, "byteOffset": 36, "byteLength": 48 } ],
          "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0] },
            { "bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC4" } ] }
        """;
    }

    [Theory]
    [InlineData(SolverPath.Reference)]
    [InlineData(SolverPath.Fast)]
    public void HairOnAMeshHeadStaysOutOfItWhileTheHeadShakes(SolverPath path)
    {
        // The reference groom's head as a mesh: the hair collides with the mesh only (no analytic collider), and
        // penetration is measured against the analytic ellipsoid the mesh approximates.
        var groom = new GroomSettings { SheetCount = 60, StrandsPerSheet = 6 };
        var world = GroomBuilder.Build(groom);
        var scene = new HairScene(world, new SimulationSettings { Path = path });
        var sdf = SignedDistanceField.Bake(TriangleMesh.Ellipsoid(groom.HeadCenter, HeadRadii, 48, 96), 0.0025f);
        scene.SetComponent(new MeshCollider(sdf));
        using var threads = ThreadDispatchers.CreateDefault();
        var sim = new HairSimulation(scene, dispatcher: threads);
        Assert.Contains(sim.Pipeline.Systems, s => s.Name == MeshCollideSystem.SystemName);
        var ellipsoid = Collider.Ellipsoid(groom.HeadCenter, HeadRadii);
        float worst = 0;
        for (int f = 1; f <= 90; f++)
        {
            sim.Step(1f / 60f, HeadMotion.Shake(f / 60f));
            if (f % 10 != 0) continue;
            var e = ellipsoid.ToWorld(world.Head);
            for (int i = 0; i < world.ParticleCount; i++)
                if (world.InvMass[i] != 0f) worst = MathF.Max(worst, e.Penetration(world.GetPosition(i)));
        }
        Assert.Equal(0, world.CountNonFinite());
        Assert.True(worst < 0.001f, $"deepest particle {worst * 1000:F2} mm inside the head");
        Assert.True(WorldMetrics.Measure(scene).MaxPenetration < 0.001);
    }

    [Fact]
    public void WithoutAMeshColliderThePipelineLeavesTheSystemOut()
    {
        var scene = GroomBuilder.BuildScene(new GroomSettings { SheetCount = 4, StrandsPerSheet = 2 });
        Assert.DoesNotContain(new HairSimulation(scene).Pipeline.Systems, s => s.Name == MeshCollideSystem.SystemName);
    }

    [Fact]
    public void ASegmentAcrossAThinRimRidesOverIt()
    {
        // An ear-like slab 4 mm thick; two particles 16 mm apart on either side of it, the segment 1 mm below its rim:
        // neither particle is inside, only the segment's middle is.
        var slab = TriangleMesh.Box(new Vector3(-0.002f, -0.05f, -0.05f), new Vector3(0.002f, 0f, 0.05f));
        var sdf = SignedDistanceField.Bake(slab, 0.0005f);
        var world = new HairWorld(1, 1, 3);
        world.SetStrand(0, [new Vector3(-0.008f, 0.02f, 0), new Vector3(-0.008f, -0.001f, 0), new Vector3(0.008f, -0.001f, 0)], pinned: 1);
        world.ResetToRest();
        world.SetPosition(1, new Vector3(-0.008f, -0.001f, 0));
        world.SetPosition(2, new Vector3(0.008f, -0.001f, 0));
        var scene = new HairScene(world);
        scene.SetComponent(new MeshCollider(sdf));
        Assert.True(sdf.Distance(world.GetPosition(1)) > 0 && sdf.Distance(world.GetPosition(2)) > 0);
        Assert.True(sdf.Distance(0.5f * (world.GetPosition(1) + world.GetPosition(2))) < 0);
        var ctx = new FrameContext { Settings = scene.Settings };
        ctx.SubstepHeads = [RigidTransform.Identity];
        new MeshCollideSystem().Run(scene, ctx, 0, 0, 1);
        Assert.True(sdf.Distance(0.5f * (world.GetPosition(1) + world.GetPosition(2))) > -1e-4f, "the segment's middle is out of the rim");
        Assert.True(world.GetPosition(2).Y > -1e-4f);
    }

    [Fact]
    public void VisibleOnlySelectionAndCutSeeTheMeshHead()
    {
        var head = ProceduralHead.Create();
        var sdf = SignedDistanceField.Bake(head, 0.0025f);
        var scene = MeshScalp.BuildScene(head, sdf, new MeshGroomSettings { SheetCount = 60, StrandsPerSheet = 5, ScalpMaskThreshold = 0.5f });
        var camera = StrokeCamera.LookAtPerspective(new Vector3(0, 0.05f, 0.95f), new Vector3(0, -0.06f, 0), Vector3.UnitY, 0.6f, new Vector2(800, 800));
        var everything = SelectionArea.Rectangle(Vector2.Zero, new Vector2(800, 800));
        var all = HairEditor.Select(scene, camera, everything, new SelectionOptions { RootsOnly = true });
        var visible = HairEditor.Select(scene, camera, everything, new SelectionOptions { RootsOnly = true, VisibleOnly = true });
        Assert.Equal(scene.World.StrandCount, all.Count);
        Assert.InRange(visible.Count, 1, all.Count - 1);
        // What the head hides is at the back: no visible root is behind the head's centre and far from its outline.
        foreach (int s in visible.Strands)
        {
            var r = scene.World.GetPosition(scene.World.RootIndex(s));
            Assert.False(r.Z < -0.05f && MathF.Abs(r.X) < 0.04f, $"root {r} behind the head counted as visible");
        }
        // A cut across the whole head at ear height: through the head it reaches more strands than in front of it.
        Settle(scene);
        var line = new Stroke([new Vector2(0, 430), new Vector2(800, 430)], camera);
        int front = HairEditor.Cut(scene, line, new CutOptions { Reach = CutReach.VisibleOnly }).Cuts.Count;
        int through = HairEditor.Cut(scene, line, new CutOptions { Reach = CutReach.AllThrough }).Cuts.Count;
        Assert.InRange(front, 1, through - 1);
    }

    private static void Settle(HairScene scene)
    {
        var sim = new HairSimulation(scene);
        for (int f = 0; f < 30; f++) sim.Step(1f / 60f);
    }

    [Fact]
    public void HairGrowsOnlyOnTheMarkedScalpEvenlyAndOutsideTheMesh()
    {
        var head = TriangleMesh.Ellipsoid(Vector3.Zero, HeadRadii, 48, 96);
        // Vertex colours: red on the upper back of the head (the scalp), white elsewhere would count too, so black.
        var colours = head.Positions.Select(p => p.Y > 0.02f && p.Z < 0.06f ? new Vector4(1, 0, 0, 1) : new Vector4(0, 0, 0, 1)).ToArray();
        var painted = new TriangleMesh(head.Positions, head.Indices, colours);
        var sdf = SignedDistanceField.Bake(painted, 0.0025f);
        var g = new MeshGroomSettings { SheetCount = 40, StrandsPerSheet = 10, ParticlesPerStrand = 12, StrandLength = 0.2f, ScalpMaskThreshold = 0.5f };
        var world = MeshScalp.Grow(painted, sdf, g);
        Assert.Equal(400, world.StrandCount);
        Assert.InRange(world.SheetCount, 30, 40);
        var roots = Enumerable.Range(0, world.StrandCount).Select(s => world.GetPosition(world.RootIndex(s))).ToArray();
        foreach (var r in roots) Assert.True(r.Y > 0.01f && r.Z < 0.07f, $"root {r} off the painted scalp");
        // Even: no two roots closer than a third of the mean spacing (√(area / n)).
        double area = Enumerable.Range(0, painted.TriangleCount).Where(t => painted.Triangle(t).A.Y > 0.02f).Sum(t => (double)painted.TriangleArea(t));
        float spacing = (float)Math.Sqrt(area / roots.Length);
        for (int a = 0; a < roots.Length; a++)
            for (int b = a + 1; b < roots.Length; b++)
                Assert.True(Vector3.Distance(roots[a], roots[b]) > spacing / 3, "roots clump");
        for (int i = 0; i < world.ParticleCount; i++) Assert.True(sdf.Distance(world.GetPosition(i)) > -1e-4f, "a particle grew inside the head");
        Assert.InRange(world.TotalRestLength(), 400 * 0.2 * 0.999, 400 * 0.2 * 1.001);
    }

    [Fact]
    public void A_reference_size_groom_grows_on_the_projects_head_with_almost_no_particle_inside_its_ears()
    {
        // Strands that turn down past the 8 mm ears used to leave particles inside them (the collision then dug them out
        // in the first frames): the comb now pushes such a particle out along the field when keeping the segment's
        // length cannot.
        var head = ProceduralHead.Create();
        var sdf = SignedDistanceField.Bake(head, 0.0025f);
        var reference = GroomSettings.Reference();
        var world = MeshScalp.Grow(head, sdf, new MeshGroomSettings
        {
            SheetCount = reference.SheetCount, StrandsPerSheet = reference.StrandsPerSheet, ParticlesPerStrand = reference.ParticlesPerStrand,
            StrandLength = reference.StrandLength, ScalpMaskThreshold = 0.5f,
        });
        int inside = 0;
        float deepest = 0f;
        for (int i = 0; i < world.ParticleCount; i++)
        {
            float d = sdf.Distance(world.GetPosition(i));
            if (d < 0f) inside++;
            deepest = MathF.Min(deepest, d);
        }
        Assert.True(inside <= world.ParticleCount / 50_000, $"{inside} of {world.ParticleCount} grown particles inside the head");
        Assert.True(deepest > -0.0015f, $"a grown particle is {-deepest * 1000:F2} mm inside the head");
    }
}
