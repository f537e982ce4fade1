using System.Numerics;
using HairSim;

namespace HairSheet.Logic;

/// <summary>
/// Layout A: one MultiMesh instance per strand segment. The instanced mesh is a unit segment from local
/// (0,0,0) to (0,1,0) with its width along local X and Z; each instance's basis Y spans the segment and
/// X/Z carry the width. Floats per instance follow Godot's MultiMesh buffer: a row-major 3×4 transform
/// (12), then colour (4) if UseColors, then custom data (4) if UseCustomData. The buffer is sized once for
/// every segment a full-length strand can have; cut strands simply produce fewer instances, and the
/// renderer draws the first <see cref="VisibleInstances"/> (MultiMesh.VisibleInstanceCount).
/// </summary>
public sealed class SegmentInstanceBuffer
{
    public SegmentInstanceBuffer(int renderStrands, int stride, bool useColors, bool useCustomData, StrandLook look)
    {
        if (renderStrands < 1) throw new ArgumentOutOfRangeException(nameof(renderStrands), renderStrands, "At least one render strand is needed.");
        if (stride < 2) throw new ArgumentOutOfRangeException(nameof(stride), stride, "A strand has at least two points.");
        look.Validate();
        long instances = (long)renderStrands * (stride - 1);
        int floats = 12 + (useColors ? 4 : 0) + (useCustomData ? 4 : 0);
        if (instances * floats > Array.MaxLength)
            throw new ArgumentOutOfRangeException(nameof(renderStrands), instances, "Too many strand segments for one MultiMesh buffer.");
        RenderStrands = renderStrands;
        Stride = stride;
        UseColors = useColors;
        UseCustomData = useCustomData;
        Look = look;
        FloatsPerInstance = floats;
        MaxInstances = (int)instances;
        Buffer = new float[MaxInstances * floats];
    }

    /// <summary>Sized for a scene's render output (render strand count and points per strand).</summary>
    public SegmentInstanceBuffer(RenderStrands strands, bool useColors, bool useCustomData, StrandLook look)
        : this(strands.StrandCount, strands.Stride, useColors, useCustomData, look) { }

    public int RenderStrands { get; }
    public int Stride { get; }
    public bool UseColors { get; }
    public bool UseCustomData { get; }
    public StrandLook Look { get; }
    public int FloatsPerInstance { get; }
    /// <summary>MultiMesh.InstanceCount: every segment of every uncut render strand.</summary>
    public int MaxInstances { get; }
    /// <summary>The whole MultiMesh buffer; reused every frame (uploaded in one call).</summary>
    public float[] Buffer { get; }
    /// <summary>Segments written by the last Fill (MultiMesh.VisibleInstanceCount).</summary>
    public int VisibleInstances { get; private set; }
    public StrandBounds Bounds { get; private set; } = StrandBounds.Empty;
    /// <summary>Bytes one upload moves: Godot's MultimeshSetBuffer takes the whole buffer, hidden instances included.</summary>
    public long BytesPerUpload => Buffer.LongLength * sizeof(float);
    /// <summary>Bytes of the instances actually drawn.</summary>
    public long VisibleBytes => (long)VisibleInstances * FloatsPerInstance * sizeof(float);

    /// <summary>Colour written per instance when UseColors (root and tip, linear RGBA).</summary>
    public Vector4 RootColor { get; set; } = new(0.16f, 0.10f, 0.06f, 1f);
    public Vector4 TipColor { get; set; } = new(0.45f, 0.32f, 0.20f, 1f);

    /// <summary>Writes every live segment of every render strand; returns the visible instance count. Allocates nothing.</summary>
    public int Fill(RenderStrands strands)
    {
        ArgumentNullException.ThrowIfNull(strands);
        if (strands.StrandCount != RenderStrands || strands.Stride != Stride)
            throw new ArgumentException($"Render strands are {strands.StrandCount} × {strands.Stride} but the buffer was built for {RenderStrands} × {Stride}.", nameof(strands));
        var pts = strands.Points;
        var counts = strands.Counts;
        var buf = Buffer;
        int fpi = FloatsPerInstance, o = 0, n = 0;
        float invLast = 1f / (Stride - 1);
        var bounds = StrandBounds.Empty;
        for (int r = 0; r < RenderStrands; r++)
        {
            int count = counts[r], first = r * Stride;
            if (count < 2) continue;
            float strandRandom = StrandRandom(r);
            for (int k = 0; k + 1 < count; k++)
            {
                var p0 = pts[first + k];
                var p1 = pts[first + k + 1];
                bounds = bounds.Include(p0).Include(p1);
                float t0 = k * invLast, t1 = (k + 1) * invLast;
                WriteSegment(buf.AsSpan(o, fpi), p0, p1, Look.WidthAt(0.5f * (t0 + t1)));
                int c = 12;
                if (UseColors)
                {
                    var col = Vector4.Lerp(RootColor, TipColor, 0.5f * (t0 + t1));
                    buf[o + c] = col.X; buf[o + c + 1] = col.Y; buf[o + c + 2] = col.Z; buf[o + c + 3] = col.W;
                    c += 4;
                }
                if (UseCustomData)
                {
                    // Half floats in the Compatibility renderer: t and a [0,1) random survive that precision.
                    buf[o + c] = t0; buf[o + c + 1] = t1; buf[o + c + 2] = strandRandom; buf[o + c + 3] = 0f;
                }
                o += fpi;
                n++;
            }
        }
        VisibleInstances = n;
        Bounds = bounds.Grow(Look.RootWidth);
        return n;
    }

    /// <summary>
    /// Row-major 3×4 transform taking the unit segment onto p0 → p1 (Godot's MultiMesh order:
    /// basis.x.x, basis.y.x, basis.z.x, origin.x, then the y row, then the z row).
    /// A zero-length segment gets a zero basis (an invisible instance), never NaN.
    /// </summary>
    public static void WriteSegment(Span<float> dst, Vector3 p0, Vector3 p1, float width)
    {
        var axis = p1 - p0;
        float len = axis.Length();
        Vector3 bx, bz;
        if (len < 1e-12f || !float.IsFinite(len)) { bx = bz = Vector3.Zero; axis = Vector3.Zero; }
        else
        {
            Orthonormal(axis / len, out var u, out var v);
            bx = u * width; bz = v * width;
        }
        dst[0] = bx.X; dst[1] = axis.X; dst[2] = bz.X; dst[3] = p0.X;
        dst[4] = bx.Y; dst[5] = axis.Y; dst[6] = bz.Y; dst[7] = p0.Y;
        dst[8] = bx.Z; dst[9] = axis.Z; dst[10] = bz.Z; dst[11] = p0.Z;
    }

    /// <summary>Applies a row-major 3×4 transform to a local point (what the GPU does with an instance).</summary>
    public static Vector3 TransformPoint(ReadOnlySpan<float> m, Vector3 p) => new(
        m[0] * p.X + m[1] * p.Y + m[2] * p.Z + m[3],
        m[4] * p.X + m[5] * p.Y + m[6] * p.Z + m[7],
        m[8] * p.X + m[9] * p.Y + m[10] * p.Z + m[11]);

    /// <summary>Two unit vectors completing n to a right-handed frame (Duff et al. 2017, branch-free, no singular direction).</summary>
    public static void Orthonormal(Vector3 n, out Vector3 u, out Vector3 v)
    {
        float sign = MathF.CopySign(1f, n.Z);
        float a = -1f / (sign + n.Z);
        float b = n.X * n.Y * a;
        u = new Vector3(1f + sign * n.X * n.X * a, sign * b, -sign * n.X);
        v = new Vector3(b, sign + n.Y * n.Y * a, -n.Y);
    }

    /// <summary>A stable per-strand value in [0, 1) for colour variation (same strand, same value, every frame).</summary>
    public static float StrandRandom(int strand)
    {
        uint h = (uint)strand * 0x9E3779B1u;
        h ^= h >> 15; h *= 0x85EBCA77u; h ^= h >> 13;
        return (h >> 8) * (1f / (1 << 24));
    }
}
