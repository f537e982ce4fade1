using System.Buffers.Binary;
using System.Numerics;
using System.Runtime.InteropServices;

namespace HairSim.Cli.Studio;

/// <summary>
/// The studio's binary wire formats (little-endian). A frame is 6 bytes per particle: positions quantised to
/// 16-bit integers over the hair's bounding box (a 60 cm groom gets ~10 µm steps, far below a pixel), a third of
/// float32's size, so the reference scene's 278k particles stream at ~1.7 MB per frame on loopback.
/// </summary>
public static class FrameEncoder
{
    public const int FrameHeaderBytes = 64;
    public const int TopologyHeaderBytes = 16;
    public static ReadOnlySpan<byte> FrameMagic => "HSF1"u8;
    public static ReadOnlySpan<byte> TopologyMagic => "HST1"u8;

    public static int FrameBytes(HairWorld w) => FrameHeaderBytes + 6 * w.ParticleCount;

    /// <summary>
    /// Frame layout: magic "HSF1", uint32 frame, uint32 revision (changes when strand counts may have changed),
    /// uint32 particle count, float32 origin xyz, float32 quantum (metres per step), float32 head position xyz,
    /// float32 head rotation xyzw, float32 step milliseconds; then int16 x, y, z per particle.
    /// Particle i decodes as origin + quantum · q. Non-finite positions are sent as the origin.
    /// </summary>
    public static void EncodeFrame(HairWorld w, long frame, int revision, float stepMs, Span<byte> output)
    {
        int n = w.ParticleCount;
        if (output.Length < FrameBytes(w)) throw new ArgumentException("Output buffer too small for this world's frame.", nameof(output));
        var min = new Vector3(float.MaxValue);
        var max = new Vector3(float.MinValue);
        float[] x = w.PosX, y = w.PosY, z = w.PosZ;
        for (int i = 0; i < n; i++)
        {
            var p = new Vector3(x[i], y[i], z[i]);
            if (!float.IsFinite(p.X + p.Y + p.Z)) continue;
            min = Vector3.Min(min, p); max = Vector3.Max(max, p);
        }
        if (min.X > max.X) { min = max = Vector3.Zero; }
        var origin = (min + max) * 0.5f;
        var half = (max - min) * 0.5f;
        float extent = MathF.Max(half.X, MathF.Max(half.Y, half.Z));
        float quantum = extent > 0f ? extent / 32000f : 1e-6f;   // a margin below 32767 for rounding

        var h = output;
        FrameMagic.CopyTo(h);
        BinaryPrimitives.WriteUInt32LittleEndian(h[4..], (uint)frame);
        BinaryPrimitives.WriteInt32LittleEndian(h[8..], revision);
        BinaryPrimitives.WriteInt32LittleEndian(h[12..], n);
        WriteVec(h[16..], origin);
        BinaryPrimitives.WriteSingleLittleEndian(h[28..], quantum);
        WriteVec(h[32..], w.Head.Position);
        var q = w.Head.Rotation;
        BinaryPrimitives.WriteSingleLittleEndian(h[44..], q.X);
        BinaryPrimitives.WriteSingleLittleEndian(h[48..], q.Y);
        BinaryPrimitives.WriteSingleLittleEndian(h[52..], q.Z);
        BinaryPrimitives.WriteSingleLittleEndian(h[56..], q.W);
        BinaryPrimitives.WriteSingleLittleEndian(h[60..], stepMs);

        float inv = 1f / quantum;
        var data = output.Slice(FrameHeaderBytes, 6 * n);
        if (BitConverter.IsLittleEndian)
        {
            // The wire is little-endian: write the shorts straight into the buffer (this runs once per streamed frame).
            var q16 = MemoryMarshal.Cast<byte, short>(data);
            for (int i = 0; i < n; i++)
            {
                var p = new Vector3(x[i], y[i], z[i]);
                if (!float.IsFinite(p.X + p.Y + p.Z)) p = origin;
                var d = (p - origin) * inv;
                q16[3 * i] = Quantise(d.X); q16[3 * i + 1] = Quantise(d.Y); q16[3 * i + 2] = Quantise(d.Z);
            }
            return;
        }
        for (int i = 0; i < n; i++)
        {
            var p = new Vector3(x[i], y[i], z[i]);
            if (!float.IsFinite(p.X + p.Y + p.Z)) p = origin;
            var d = (p - origin) * inv;
            int o = 6 * i;
            BinaryPrimitives.WriteInt16LittleEndian(data[o..], Quantise(d.X));
            BinaryPrimitives.WriteInt16LittleEndian(data[(o + 2)..], Quantise(d.Y));
            BinaryPrimitives.WriteInt16LittleEndian(data[(o + 4)..], Quantise(d.Z));
        }
    }

    private static short Quantise(float v) => (short)Math.Clamp(MathF.Round(v), -32767f, 32767f);

    private static void WriteVec(Span<byte> s, Vector3 v)
    {
        BinaryPrimitives.WriteSingleLittleEndian(s, v.X);
        BinaryPrimitives.WriteSingleLittleEndian(s[4..], v.Y);
        BinaryPrimitives.WriteSingleLittleEndian(s[8..], v.Z);
    }

    /// <summary>Decodes particle i of an encoded frame (for tests and tools).</summary>
    public static Vector3 DecodePosition(ReadOnlySpan<byte> frame, int i)
    {
        var origin = new Vector3(BinaryPrimitives.ReadSingleLittleEndian(frame[16..]), BinaryPrimitives.ReadSingleLittleEndian(frame[20..]),
            BinaryPrimitives.ReadSingleLittleEndian(frame[24..]));
        float quantum = BinaryPrimitives.ReadSingleLittleEndian(frame[28..]);
        var d = frame[(FrameHeaderBytes + 6 * i)..];
        return origin + quantum * new Vector3(BinaryPrimitives.ReadInt16LittleEndian(d), BinaryPrimitives.ReadInt16LittleEndian(d[2..]),
            BinaryPrimitives.ReadInt16LittleEndian(d[4..]));
    }

    /// <summary>
    /// Mesh layout (head space, for drawing the head): magic "HSM1", int32 vertex count, int32 triangle count, then
    /// float32 x, y, z per vertex and int32 indices, three per triangle.
    /// </summary>
    public static byte[] EncodeMesh(HairSim.Meshes.TriangleMesh mesh)
    {
        int nv = mesh.Positions.Length, ni = mesh.Indices.Length;
        var b = new byte[12 + 12 * nv + 4 * ni];
        "HSM1"u8.CopyTo(b);
        BinaryPrimitives.WriteInt32LittleEndian(b.AsSpan(4), nv);
        BinaryPrimitives.WriteInt32LittleEndian(b.AsSpan(8), ni / 3);
        int o = 12;
        foreach (var p in mesh.Positions) { WriteVec(b.AsSpan(o), p); o += 12; }
        foreach (int i in mesh.Indices) { BinaryPrimitives.WriteInt32LittleEndian(b.AsSpan(o), i); o += 4; }
        return b;
    }

    /// <summary>
    /// Scalp layout (the painted scalp of the mesh <see cref="EncodeMesh"/> sends): magic "HSS1", int32 revision, int32
    /// triangle count, then one byte per triangle, 1 where hair grows and 0 elsewhere.
    /// </summary>
    public static byte[] EncodeScalp(HairSim.Meshes.ScalpPaint paint, int revision)
    {
        var mask = paint.Triangles;
        var b = new byte[12 + mask.Length];
        "HSS1"u8.CopyTo(b);
        BinaryPrimitives.WriteInt32LittleEndian(b.AsSpan(4), revision);
        BinaryPrimitives.WriteInt32LittleEndian(b.AsSpan(8), mask.Length);
        for (int t = 0; t < mask.Length; t++) b[12 + t] = mask[t] ? (byte)1 : (byte)0;
        return b;
    }

    /// <summary>
    /// Topology layout: magic "HST1", int32 revision, int32 strand count, int32 particle count; then per strand
    /// int32 first particle, int32 live particle count, int32 capacity, int32 sheet.
    /// </summary>
    public static byte[] EncodeTopology(HairWorld w, int revision)
    {
        int s = w.StrandCount;
        var b = new byte[TopologyHeaderBytes + 16 * s];
        TopologyMagic.CopyTo(b);
        BinaryPrimitives.WriteInt32LittleEndian(b.AsSpan(4), revision);
        BinaryPrimitives.WriteInt32LittleEndian(b.AsSpan(8), s);
        BinaryPrimitives.WriteInt32LittleEndian(b.AsSpan(12), w.ParticleCount);
        for (int k = 0; k < s; k++)
        {
            var o = b.AsSpan(TopologyHeaderBytes + 16 * k);
            BinaryPrimitives.WriteInt32LittleEndian(o, w.StrandFirst[k]);
            BinaryPrimitives.WriteInt32LittleEndian(o[4..], w.StrandParticleCount[k]);
            BinaryPrimitives.WriteInt32LittleEndian(o[8..], w.StrandCapacity[k]);
            BinaryPrimitives.WriteInt32LittleEndian(o[12..], w.StrandSheet[k]);
        }
        return b;
    }
}
