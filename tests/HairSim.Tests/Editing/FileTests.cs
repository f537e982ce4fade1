using System.Buffers.Binary;
using System.Numerics;
using HairSim;
using HairSim.Editing;
using HairSim.IO;

namespace HairSim.Tests.Editing;

public sealed class FileTests : IDisposable
{
    private readonly string _dir = Path.Combine(Path.GetTempPath(), "hairsheet-tests-" + Guid.NewGuid().ToString("N"));

    public FileTests() => Directory.CreateDirectory(_dir);
    public void Dispose() { try { Directory.Delete(_dir, true); } catch (IOException) { } }

    /// <summary>A small styled scene: cut, head moved, extra colliders, non-default settings, render on.</summary>
    private static HairScene Styled()
    {
        var settings = new SimulationSettings { Bend = BendModel.SourceTriples, Sag = 0.2f, BendDamping = 0.7f, StaticFriction = 0.6f, KineticFriction = 0.4f, Alpha = 0.7f, GlobalShapeStiffness = 0.04f, Substeps = 3, Length = LengthMode.Pbd, Mode = ShapeMatchMode.LiteralForce, Gravity = new Vector3(0.1f, -9f, 0.2f) };
        var scene = GroomBuilder.BuildScene(new GroomSettings { SheetCount = 5, StrandsPerSheet = 3, ParticlesPerStrand = 6 }, settings);
        scene.AddCollider(Collider.Sphere(new Vector3(0, -0.1f, 0.05f), 0.04f));
        scene.AddCollider(Collider.Capsule(new Vector3(0, -0.15f, 0), new Vector3(0, -0.3f, 0), 0.05f));
        scene.Render = new RenderSettings { StrandsPerGap = 2 };
        var sim = new HairSimulation(scene);
        for (int f = 0; f < 5; f++) sim.Step(1f / 60f, new RigidTransform(new Vector3(0, 0.01f * f, 0), Quaternion.CreateFromAxisAngle(Vector3.UnitY, 0.05f * f)));
        var cam = StrokeCamera.LookAtOrthographic(new Vector3(0, 0, 1), Vector3.Zero, Vector3.UnitY, 0.6f, new Vector2(600, 600));
        HairEditor.Cut(scene, new Stroke([new Vector2(0, 250), new Vector2(600, 250)], cam), new CutOptions { Reach = CutReach.AllThrough }).Apply();
        return scene;
    }

    private static byte[] Bytes(HairScene scene)
    {
        using var ms = new MemoryStream();
        HairstyleFile.Save(scene, ms);
        return ms.ToArray();
    }

    private static void FixCrc(byte[] data) => BinaryPrimitives.WriteUInt32LittleEndian(data.AsSpan(data.Length - 4), Crc32.Compute(data.AsSpan(0, data.Length - 4)));

    [Fact]
    public void VersionOneFilesLoadWithTheSourcesScheme()
    {
        // A version 1 file is a version 2 (or 3, the same layout) file without the 20 bytes of bend and friction settings that end the settings block.
        var scene = Styled();
        scene.Settings.Bend = BendModel.RestShape;
        var v2 = Bytes(scene);
        const int settingsEnd = HairstyleFile.HeaderBytes + 64;
        var v1 = new byte[v2.Length - 20];
        v2.AsSpan(0, settingsEnd).CopyTo(v1);
        v2.AsSpan(settingsEnd + 20).CopyTo(v1.AsSpan(settingsEnd));
        BinaryPrimitives.WriteInt32LittleEndian(v1.AsSpan(8), 1);
        BinaryPrimitives.WriteInt64LittleEndian(v1.AsSpan(16), v1.Length - HairstyleFile.HeaderBytes - 4L);
        FixCrc(v1);
        var loaded = HairstyleFile.Load(v1);
        Assert.Equal(BendModel.SourceTriples, loaded.Settings.Bend);
        Assert.True(loaded.World.BitEquals(scene.World));
        Assert.Equal(BendModel.RestShape, HairstyleFile.Load(v2).Settings.Bend);
        // Versions this build does not know are refused with the range it reads.
        BinaryPrimitives.WriteInt32LittleEndian(v1.AsSpan(8), HairstyleFile.Version + 1);
        FixCrc(v1);
        var e = Assert.Throws<InvalidDataException>(() => HairstyleFile.Load(v1));
        Assert.Contains($"versions 1 … {HairstyleFile.Version}", e.Message);
    }

    [Fact]
    public void RoundTripIsExact()
    {
        var scene = Styled();
        var path = Path.Combine(_dir, "style.hairstyle");
        HairstyleFile.Save(scene, path);
        var loaded = HairstyleFile.Load(path);
        Assert.True(loaded.World.BitEquals(scene.World));
        Assert.Equal(scene.World.SheetStrandCount, loaded.World.SheetStrandCount);
        var a = scene.Settings; var b = loaded.Settings;
        Assert.Equal((a.Gravity, a.Alpha, a.GlobalShapeStiffness, a.Mode, a.Damping, a.Substeps, a.Length, a.LengthIterations),
                     (b.Gravity, b.Alpha, b.GlobalShapeStiffness, b.Mode, b.Damping, b.Substeps, b.Length, b.LengthIterations));
        Assert.Equal((a.LengthDamping, a.ContactSlide, a.MaxSpeed, a.TeleportDistance, a.TeleportAngle, a.Path),
                     (b.LengthDamping, b.ContactSlide, b.MaxSpeed, b.TeleportDistance, b.TeleportAngle, b.Path));
        Assert.Equal((a.Bend, a.Sag, a.BendDamping, a.StaticFriction, a.KineticFriction), (b.Bend, b.Sag, b.BendDamping, b.StaticFriction, b.KineticFriction));
        Assert.Equal(scene.Colliders.Count, loaded.Colliders.Count);
        for (int c = 0; c < scene.Colliders.Count; c++)
        {
            Assert.Equal(scene.Colliders[c].Kind, loaded.Colliders[c].Kind);
            Assert.Equal(scene.Colliders[c].Center, loaded.Colliders[c].Center);
            Assert.Equal(scene.Colliders[c].End, loaded.Colliders[c].End);
            Assert.Equal(scene.Colliders[c].Radii, loaded.Colliders[c].Radii);
            Assert.Equal(scene.Colliders[c].Rotation, loaded.Colliders[c].Rotation);
        }
        Assert.Equal(2, loaded.Render!.StrandsPerGap);
        Assert.Equal(Bytes(scene), Bytes(loaded));
        Assert.Empty(Directory.GetFiles(_dir, "*.tmp"));
    }

    [Fact]
    public void TruncatedCorruptedAndWrongVersionFilesGiveClearErrors()
    {
        var data = Bytes(Styled());
        for (int n = 0; n < data.Length; n += Math.Max(1, n / 16))
        {
            var e = Assert.Throws<InvalidDataException>(() => HairstyleFile.Load(data.AsSpan(0, n)));
            Assert.False(string.IsNullOrWhiteSpace(e.Message));
        }
        var unknown = (byte[])data.Clone();
        BinaryPrimitives.WriteInt32LittleEndian(unknown.AsSpan(8), 9);
        FixCrc(unknown);
        Assert.Contains("version 9", Assert.Throws<InvalidDataException>(() => HairstyleFile.Load(unknown)).Message);
        var flipped = (byte[])data.Clone();
        flipped[data.Length / 2] ^= 0x10;
        Assert.Contains("checksum", Assert.Throws<InvalidDataException>(() => HairstyleFile.Load(flipped)).Message);
        Assert.Contains("magic", Assert.Throws<InvalidDataException>(() => HairstyleFile.Load(new byte[64])).Message);
    }

    [Fact]
    public void FuzzedFilesOnlyEverGiveInvalidDataException()
    {
        var data = Bytes(Styled());
        var rng = new SplitMix64(2024);
        int rejected = 0, accepted = 0;
        for (int trial = 0; trial < 3000; trial++)
        {
            var d = (byte[])data.Clone();
            int flips = 1 + (int)(rng.Next() % 6);
            for (int f = 0; f < flips; f++)
            {
                // Mostly the header and layout (where sizes live), sometimes anywhere.
                int at = rng.Next() % 3 == 0 ? (int)(rng.Next() % (ulong)d.Length) : (int)(rng.Next() % 200);
                d[at] = (byte)rng.Next();
            }
            int len = rng.Next() % 5 == 0 ? (int)(rng.Next() % (ulong)d.Length) : d.Length;
            var cut = d.AsSpan(0, len).ToArray();
            if (trial % 2 == 0 && cut.Length >= 4) FixCrc(cut); // half with a valid checksum, so the parser itself is exercised
            try { HairstyleFile.Load(cut); accepted++; }
            catch (InvalidDataException) { rejected++; }
        }
        Assert.True(rejected > 1000);
        Assert.True(accepted + rejected == 3000);
    }

    [Fact]
    public void HostileSizesAreRefusedBeforeAllocating()
    {
        var data = Bytes(Styled());
        // Payload offsets: settings 84, render 8, head 28, colliders 4 + 56·3, then the sheet count.
        int sheetAt = 24 + 84 + 8 + 28 + 4 + 56 * 3;
        Assert.Equal(5, BinaryPrimitives.ReadInt32LittleEndian(data.AsSpan(sheetAt)));
        foreach (int evil in new[] { int.MaxValue, 1 << 28, -1, 0 })
        {
            var d = (byte[])data.Clone();
            BinaryPrimitives.WriteInt32LittleEndian(d.AsSpan(sheetAt), evil);
            FixCrc(d);
            long before = GC.GetAllocatedBytesForCurrentThread();
            Assert.Throws<InvalidDataException>(() => HairstyleFile.Load(d));
            Assert.True(GC.GetAllocatedBytesForCurrentThread() - before < 1 << 20, "the loader allocated from an unchecked size");
        }
        var big = (byte[])data.Clone();
        BinaryPrimitives.WriteInt64LittleEndian(big.AsSpan(16), long.MaxValue);
        FixCrc(big);
        Assert.Throws<InvalidDataException>(() => HairstyleFile.Load(big));
    }

    [Fact]
    public void AFailedSaveLeavesThePreviousFileIntactAndNoTemporaryFiles()
    {
        var scene = Styled();
        var path = Path.Combine(_dir, "keep.hairstyle");
        HairstyleFile.Save(scene, path);
        var good = File.ReadAllBytes(path);
        scene.World.VelY[scene.World.ParticleCount - 1] = float.NaN; // found late, after most of the file is written
        Assert.Throws<InvalidDataException>(() => HairstyleFile.Save(scene, path));
        Assert.Equal(good, File.ReadAllBytes(path));
        Assert.Single(Directory.GetFiles(_dir));
        Assert.True(HairstyleFile.Load(path).World.CountNonFinite() == 0);
    }
}
