using System.Buffers.Binary;
using System.Numerics;

namespace HairSim.IO;

/// <summary>
/// The hairstyle file: head pose, colliders, settings, render settings and every world buffer (rest pose, rest
/// shape, cut lengths, positions, velocities), so a round trip is bit-exact. Binary, little-endian:
/// <code>
/// "HAIRSTYL" | u32 version | u32 flags (0) | u64 payload length | payload | u32 CRC-32 of everything before it
/// payload: settings (64 B; version 2 adds the bend model, Sag, bend damping and the two friction coefficients: 84 B) | render (8 B) | head (28 B) | colliders (4 + 56·n B) |
///          sheets, strands per sheet, strands, capacities, live counts | 15 float buffers × particles
/// </code>
/// Loading checks size caps, the checksum, the version and every count against the bytes that remain before
/// allocating, and every value's range; anything wrong is an <see cref="InvalidDataException"/> with a clear message.
/// A collider is its kind word (kind | 0x100 when fixed in the world), centre, end, radii and rotation; a plane (kind 3,
/// version 3 on) keeps its point in the centre and its unit normal in the end.
/// Version 1 files (before the bend models) load with <see cref="BendModel.SourceTriples"/>, the model they were made with,
/// and their damping, speed limit and teleport distance turned from SI units into this build's groom-relative ones.
/// </summary>
public static class HairstyleFile
{
    /// <summary>3: plane colliders (kind 3); the layout is version 2's, so versions 1 and 2 still load.</summary>
    public const int Version = 3;
    /// <summary>The oldest version this build still reads.</summary>
    public const int OldestVersion = 1;
    private const int SettingsBytes = 84;
    public const int MaxColliders = 256;
    /// <summary>Set in a collider's kind word for a collider fixed in the world (files without it read as head-attached).</summary>
    private const int WorldColliderFlag = 0x100;
    public const int HeaderBytes = 24;
    private const int BufferCount = 15;
    private static ReadOnlySpan<byte> Magic => "HAIRSTYL"u8;
    /// <summary>Largest file accepted: a full world at the particle limit plus its layout.</summary>
    public static readonly long MaxFileBytes = HeaderBytes + 4 + SettingsBytes + 8 + 28 + 4 + 56L * MaxColliders +
        8 + 4L * HairWorld.MaxParticles / 2 * 3 + 4L * BufferCount * HairWorld.MaxParticles;

    // ---------------- save ----------------

    /// <summary>Saves through a temporary file and a rename: a failed save leaves any previous file untouched.</summary>
    public static void Save(HairScene scene, string path)
    {
        ArgumentNullException.ThrowIfNull(scene);
        SafeFile.Write(path, s => Save(scene, s));
    }

    public static void Save(HairScene scene, Stream stream)
    {
        ArgumentNullException.ThrowIfNull(scene);
        ArgumentNullException.ThrowIfNull(stream);
        var w = scene.World;
        var o = new Writer(stream);
        o.Bytes(Magic);
        o.Int(Version); o.Int(0);
        o.Long(PayloadLength(scene));

        var st = scene.Settings;
        o.Float(st.Gravity.X); o.Float(st.Gravity.Y); o.Float(st.Gravity.Z);
        o.Float(st.Alpha); o.Float(st.GlobalShapeStiffness); o.Float(st.Damping); o.Float(st.LengthDamping);
        o.Float(st.ContactSlide); o.Float(st.MaxSpeed); o.Float(st.TeleportDistance); o.Float(st.TeleportAngle);
        o.Int((int)st.Mode); o.Int(st.Substeps); o.Int((int)st.Length); o.Int(st.LengthIterations); o.Int((int)st.Path);
        o.Int((int)st.Bend); o.Float(st.Sag); o.Float(st.BendDamping); o.Float(st.StaticFriction); o.Float(st.KineticFriction);

        o.Int(scene.Render != null ? 1 : 0); o.Int(scene.Render?.StrandsPerGap ?? 0);
        o.Vec(w.Head.Position); o.Quat(w.Head.Rotation);

        o.Int(scene.Colliders.Count);
        foreach (var c in scene.Colliders) { o.Int((int)c.Kind | (c.InWorld ? WorldColliderFlag : 0)); o.Vec(c.Center); o.Vec(c.End); o.Vec(c.Radii); o.Quat(c.Rotation); }

        o.Int(w.SheetCount);
        for (int q = 0; q < w.SheetCount; q++) o.Int(w.SheetStrandCount[q]);
        o.Int(w.StrandCount);
        for (int s = 0; s < w.StrandCount; s++) o.Int(w.StrandCapacity[s]);
        for (int s = 0; s < w.StrandCount; s++) o.Int(w.StrandParticleCount[s]);
        var buffers = w.Buffers();
        for (int b = 0; b < buffers.Length; b++)
            foreach (float v in buffers[b])
            {
                if (!float.IsFinite(v)) throw new InvalidDataException($"Cannot save: the world holds a non-finite value in buffer {b}; the hairstyle was not written.");
                o.Float(v);
            }
        o.Finish();
    }

    private static long PayloadLength(HairScene scene)
    {
        var w = scene.World;
        return SettingsBytes + 8 + 28 + 4 + 56L * scene.Colliders.Count + 4 + 4L * w.SheetCount + 4 + 8L * w.StrandCount + 4L * BufferCount * w.ParticleCount;
    }

    // ---------------- load ----------------

    public static HairScene Load(string path)
    {
        ArgumentException.ThrowIfNullOrEmpty(path);
        var info = new FileInfo(path);
        if (!info.Exists) throw new FileNotFoundException($"No hairstyle file at {path}.", path);
        if (info.Length > MaxFileBytes) throw new InvalidDataException($"{path} is {info.Length:N0} bytes, larger than any hairstyle ({MaxFileBytes:N0} bytes at most).");
        return Load(File.ReadAllBytes(path));
    }

    /// <summary>
    /// Applies a saved hairstyle to an existing scene whose world has the same layout (same groom): cut lengths,
    /// rest shapes and particle state are copied, the scene keeps its own settings, colliders and head pose.
    /// A corrupt file or a different layout throws InvalidDataException and leaves the scene unchanged.
    /// </summary>
    public static void LoadInto(HairScene scene, ReadOnlySpan<byte> data)
    {
        ArgumentNullException.ThrowIfNull(scene);
        var loaded = Load(data);
        if (!loaded.World.SameLayout(scene.World))
            throw new InvalidDataException($"The hairstyle was made for another groom ({loaded.World.SheetCount} sheets, {loaded.World.StrandCount} strands, {loaded.World.ParticleCount} particles) than this one ({scene.World.SheetCount}, {scene.World.StrandCount}, {scene.World.ParticleCount}).");
        var head = scene.World.Head;
        loaded.World.CopyTo(scene.World);
        scene.World.PlaceHead(head);
        scene.World.MarkEdited();
    }

    public static HairScene Load(ReadOnlySpan<byte> data)
    {
        if (data.Length < HeaderBytes + 4) throw new InvalidDataException($"Not a hairstyle file: {data.Length} bytes is shorter than the header.");
        if (!data[..8].SequenceEqual(Magic)) throw new InvalidDataException("Not a hairstyle file: the magic bytes 'HAIRSTYL' are missing.");
        int version = BinaryPrimitives.ReadInt32LittleEndian(data[8..]);
        if (version < OldestVersion || version > Version)
            throw new InvalidDataException($"Unsupported hairstyle file version {version}; this build reads versions {OldestVersion} … {Version}.");
        long payload = BinaryPrimitives.ReadInt64LittleEndian(data[16..]);
        if (payload < 0 || payload != data.Length - HeaderBytes - 4L)
            throw new InvalidDataException($"The hairstyle file is truncated or has trailing bytes: the header announces {payload} payload bytes, the file holds {data.Length - HeaderBytes - 4}.");
        uint stored = BinaryPrimitives.ReadUInt32LittleEndian(data[^4..]);
        if (Crc32.Compute(data[..^4]) != stored) throw new InvalidDataException("The hairstyle file is corrupted (checksum mismatch).");
        if (BinaryPrimitives.ReadInt32LittleEndian(data[12..]) != 0) throw new InvalidDataException("The hairstyle file uses flags this build does not know.");
        try
        {
            return Parse(new Reader(data[HeaderBytes..^4]), version);
        }
        catch (ArgumentException e)
        {
            throw new InvalidDataException($"The hairstyle file holds an invalid value: {e.Message}", e);
        }
    }

    private static HairScene Parse(Reader r, int version)
    {
        var st = new SimulationSettings
        {
            Gravity = new Vector3(r.Float(), r.Float(), r.Float()),
            Alpha = r.Float(), GlobalShapeStiffness = r.Float(), Damping = r.Float(), LengthDamping = r.Float(),
            ContactSlide = r.Float(), MaxSpeed = r.Float(), TeleportDistance = r.Float(), TeleportAngle = r.Float(),
            Mode = (ShapeMatchMode)r.Int(), Substeps = r.Int(), Length = (LengthMode)r.Int(), LengthIterations = r.Int(), Path = (SolverPath)r.Int(),
        };
        if (version >= 2)
        {
            st.Bend = (BendModel)r.Int(); st.Sag = r.Float(); st.BendDamping = r.Float();
            st.StaticFriction = r.Float(); st.KineticFriction = r.Float();
        }
        else st.Bend = BendModel.SourceTriples;
        st.Validate();
        int hasRender = r.Int(), perGap = r.Int();
        if (hasRender is not (0 or 1)) throw new InvalidDataException($"Render flag must be 0 or 1, got {hasRender}.");
        var head = new RigidTransform(r.Vec(), r.Quat());

        int nc = r.Count(MaxColliders, 56, "colliders");
        var colliders = new Collider[nc];
        for (int c = 0; c < nc; c++)
        {
            int word = r.Int(), kind = word & ~WorldColliderFlag;
            Vector3 center = r.Vec(), end = r.Vec(), radii = r.Vec();
            var rot = r.Quat();
            colliders[c] = kind switch
            {
                (int)ColliderKind.Ellipsoid => Collider.Ellipsoid(center, radii, rot),
                (int)ColliderKind.Sphere => Collider.Sphere(center, radii.X),
                (int)ColliderKind.Capsule => Collider.Capsule(center, end, radii.X),
                (int)ColliderKind.Plane when version >= 3 => Collider.Plane(center, end),
                _ => throw new InvalidDataException($"Collider {c} has unknown kind {word}."),
            };
            if ((word & WorldColliderFlag) != 0) colliders[c] = colliders[c].InWorldSpace();
        }

        int sheets = r.Count(HairWorld.MaxParticles / 2, 4 + 8 + 8 * BufferCount, "sheets");
        if (sheets < 1) throw new InvalidDataException("The hairstyle has no sheets.");
        var perSheet = new int[sheets];
        long strandSum = 0;
        for (int q = 0; q < sheets; q++) { perSheet[q] = r.Int(); strandSum += perSheet[q]; }
        int strands = r.Count(HairWorld.MaxParticles / 2, 8 + 8 * BufferCount, "strands");
        if (strands != strandSum) throw new InvalidDataException($"Sheets hold {strandSum} strands but the file lists {strands}.");
        var caps = new int[strands];
        long particles = 0;
        for (int s = 0; s < strands; s++)
        {
            caps[s] = r.Int();
            if (caps[s] < 2 || caps[s] > HairWorld.MaxParticlesPerStrand) throw new InvalidDataException($"Strand {s} has capacity {caps[s]}, outside 2 … {HairWorld.MaxParticlesPerStrand}.");
            particles += caps[s];
        }
        if (particles > HairWorld.MaxParticles) throw new InvalidDataException($"{particles:N0} particles exceed the limit of {HairWorld.MaxParticles:N0}.");
        var live = new int[strands];
        for (int s = 0; s < strands; s++)
        {
            live[s] = r.Int();
            if (live[s] < 2 || live[s] > caps[s]) throw new InvalidDataException($"Strand {s} has {live[s]} live particles, outside 2 … {caps[s]}.");
        }
        if (r.Remaining != 4L * BufferCount * particles)
            throw new InvalidDataException($"The particle data should be {4L * BufferCount * particles:N0} bytes, the file holds {r.Remaining:N0}.");

        var w = new HairWorld(perSheet, caps);
        var buffers = w.Buffers();
        for (int b = 0; b < buffers.Length; b++)
        {
            var buf = buffers[b];
            for (int i = 0; i < buf.Length; i++)
            {
                float v = r.Float();
                if (!float.IsFinite(v)) throw new InvalidDataException($"Buffer {b} holds a non-finite value at particle {i}.");
                buf[i] = v;
            }
        }
        foreach (float m in w.InvMass) if (m < 0f) throw new InvalidDataException("An inverse mass is negative.");
        foreach (float l in w.RestLength) if (l < 0f) throw new InvalidDataException("A rest length is negative.");
        Array.Copy(live, w.StrandParticleCount, strands);
        w.Head = head;
        if (version == 1)
        {
            // Version 1 stored SI values (1/s, m/s, m); this build's are relative to the groom (see GroomScale).
            var scale = GroomScale.Of(w);
            st.Damping = (float)Math.Min(100.0, st.Damping * scale.NaturalTime);
            st.MaxSpeed = (float)(st.MaxSpeed / scale.NaturalSpeed);
            if (scale.Reach > 0f) st.TeleportDistance /= scale.Reach;
            st.Validate();
        }

        var scene = new HairScene(w, st);
        foreach (var c in colliders) scene.AddCollider(c);
        if (hasRender == 1) scene.Render = new RenderSettings { StrandsPerGap = perGap };
        return scene;
    }

    /// <summary>Little-endian reads that fail with <see cref="InvalidDataException"/> instead of running past the end.</summary>
    private ref struct Reader
    {
        private readonly ReadOnlySpan<byte> _data;
        private int _pos;

        public Reader(ReadOnlySpan<byte> data) { _data = data; _pos = 0; }

        public long Remaining => _data.Length - _pos;

        private ReadOnlySpan<byte> Take(int n)
        {
            if (_data.Length - _pos < n) throw new InvalidDataException($"The hairstyle file ends early (at payload byte {_pos}, {n} more bytes needed).");
            var s = _data.Slice(_pos, n);
            _pos += n;
            return s;
        }

        public int Int() => BinaryPrimitives.ReadInt32LittleEndian(Take(4));
        public float Float() => BinaryPrimitives.ReadSingleLittleEndian(Take(4));
        public Vector3 Vec() => new(Float(), Float(), Float());
        public Quaternion Quat() => new(Float(), Float(), Float(), Float());

        /// <summary>A count that must be in 0 … max, and whose items (at least bytesEach) must fit in what remains.</summary>
        public int Count(int max, long bytesEach, string what)
        {
            int n = Int();
            if (n < 0 || n > max) throw new InvalidDataException($"The file lists {n} {what}, outside 0 … {max}.");
            if (n * bytesEach > Remaining) throw new InvalidDataException($"The file lists {n} {what} but only {Remaining} bytes remain.");
            return n;
        }
    }

    /// <summary>Buffered little-endian writer that keeps a running CRC of everything written.</summary>
    private sealed class Writer
    {
        private readonly Stream _stream;
        private readonly byte[] _buf = new byte[1 << 16];
        private int _n;
        private uint _crc;

        public Writer(Stream stream) => _stream = stream;

        private Span<byte> Room(int n)
        {
            if (_n + n > _buf.Length) Flush();
            var s = _buf.AsSpan(_n, n);
            _n += n;
            return s;
        }

        private void Flush()
        {
            _crc = Crc32.Append(_crc, _buf.AsSpan(0, _n));
            _stream.Write(_buf, 0, _n);
            _n = 0;
        }

        public void Bytes(ReadOnlySpan<byte> b) => b.CopyTo(Room(b.Length));
        public void Int(int v) => BinaryPrimitives.WriteInt32LittleEndian(Room(4), v);
        public void Long(long v) => BinaryPrimitives.WriteInt64LittleEndian(Room(8), v);
        public void Float(float v) => BinaryPrimitives.WriteSingleLittleEndian(Room(4), v);
        public void Vec(Vector3 v) { Float(v.X); Float(v.Y); Float(v.Z); }
        public void Quat(Quaternion q) { Float(q.X); Float(q.Y); Float(q.Z); Float(q.W); }

        public void Finish()
        {
            Flush();
            Span<byte> tail = stackalloc byte[4];
            BinaryPrimitives.WriteUInt32LittleEndian(tail, _crc);
            _stream.Write(tail);
        }
    }
}
