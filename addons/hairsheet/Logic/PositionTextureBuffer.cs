using System.Numerics;
using System.Runtime.InteropServices;
using HairSim;

namespace HairSheet.Logic;

/// <summary>
/// Layout B: one ribbon mesh per render strand (one MultiMesh instance each), its vertex shader reading
/// particle positions from an RGBAF texture. Strand r's points sit in a run of <see cref="Stride"/> texels;
/// runs never wrap a texture row because the width is a whole number of strands (at most
/// <see cref="MaxTextureWidth"/> texels; more strands take more rows). 4096 is the size many mobile and web GPUs
/// guarantee (Godot's 16384 maximum is not: godotengine/godot PR #48269), and the project targets Compatibility on mobile.
/// Texel = (x, y, z, live): live is 1 for a live point and 0 past a cut tip, where the point repeats the
/// tip so the ribbon collapses. The instance buffer (identity transform + custom data carrying the strand
/// index) is static: written once, uploaded only when the layout changes. Per frame only the texture moves.
/// </summary>
public sealed class PositionTextureBuffer
{
    public const int MaxTextureWidth = 4096;
    /// <summary>Custom data is half precision in the Compatibility renderer: integers up to 2048 are exact, so the index is split base 1024.</summary>
    public const int IndexBase = 1024;
    /// <summary>Transform (12) + custom data (4); no colour.</summary>
    public const int InstanceFloats = 16;

    public PositionTextureBuffer(int renderStrands, int stride, StrandLook look)
    {
        if (renderStrands < 1) throw new ArgumentOutOfRangeException(nameof(renderStrands), renderStrands, "At least one render strand is needed.");
        if (stride < 2 || stride > MaxTextureWidth) throw new ArgumentOutOfRangeException(nameof(stride), stride, $"Points per strand must be in 2 … {MaxTextureWidth}.");
        if (renderStrands >= IndexBase * 2048) throw new ArgumentOutOfRangeException(nameof(renderStrands), renderStrands, $"At most {IndexBase * 2048 - 1} render strands fit the instance index encoding.");
        look.Validate();
        RenderStrands = renderStrands;
        Stride = stride;
        Look = look;
        StrandsPerRow = Math.Min(MaxTextureWidth / stride, renderStrands);
        Width = StrandsPerRow * stride;
        Height = (renderStrands + StrandsPerRow - 1) / StrandsPerRow;
        if (Height > MaxTextureWidth) throw new ArgumentOutOfRangeException(nameof(renderStrands), renderStrands, "Too many render strands for one position texture.");
        TexelBytes = new byte[(long)Width * Height * 4 * sizeof(float)];
        InstanceBuffer = new float[renderStrands * InstanceFloats];
        WriteInstances();
    }

    public PositionTextureBuffer(RenderStrands strands, StrandLook look) : this(strands.StrandCount, strands.Stride, look) { }

    public int RenderStrands { get; }
    public int Stride { get; }
    public StrandLook Look { get; }
    public int StrandsPerRow { get; }
    /// <summary>Texture size in texels.</summary>
    public int Width { get; }
    public int Height { get; }
    /// <summary>RGBA float texels, row-major, as raw bytes: exactly what Image.SetData(Width, Height, false, Rgbaf, bytes) takes, so no copy is needed.</summary>
    public byte[] TexelBytes { get; }
    /// <summary>The same memory seen as floats (4 per texel).</summary>
    public Span<float> Texels => MemoryMarshal.Cast<byte, float>(TexelBytes.AsSpan());
    /// <summary>MultiMesh buffer: one instance per render strand; static.</summary>
    public float[] InstanceBuffer { get; }
    public int InstanceCount => RenderStrands;
    public StrandBounds Bounds { get; private set; } = StrandBounds.Empty;
    public long BytesPerUpload => TexelBytes.LongLength;
    /// <summary>Live points written by the last Fill.</summary>
    public int LivePoints { get; private set; }

    /// <summary>Texel of point k of render strand r (the shader computes the same from the instance index).</summary>
    public (int X, int Y) TexelOf(int strand, int point)
    {
        if ((uint)strand >= (uint)RenderStrands || (uint)point >= (uint)Stride) throw new ArgumentOutOfRangeException(nameof(strand));
        return ((strand % StrandsPerRow) * Stride + point, strand / StrandsPerRow);
    }

    /// <summary>Strand index as the shader decodes it from custom data (x + y · 1024).</summary>
    public static (float Low, float High) EncodeIndex(int strand) => (strand % IndexBase, strand / IndexBase);

    public static int DecodeIndex(float low, float high) => (int)MathF.Round(low) + (int)MathF.Round(high) * IndexBase;

    private void WriteInstances()
    {
        var b = InstanceBuffer;
        for (int r = 0; r < RenderStrands; r++)
        {
            int o = r * InstanceFloats;
            // Identity transform: positions in the texture are already in world space.
            b[o] = 1f; b[o + 5] = 1f; b[o + 10] = 1f;
            var (lo, hi) = EncodeIndex(r);
            b[o + 12] = lo; b[o + 13] = hi; b[o + 14] = SegmentInstanceBuffer.StrandRandom(r); b[o + 15] = 0f;
        }
    }

    /// <summary>Writes every render strand's points into the texels; returns live points. Allocates nothing.</summary>
    public int Fill(RenderStrands strands)
    {
        ArgumentNullException.ThrowIfNull(strands);
        if (strands.StrandCount != RenderStrands || strands.Stride != Stride)
            throw new ArgumentException($"Render strands are {strands.StrandCount} × {strands.Stride} but the texture was built for {RenderStrands} × {Stride}.", nameof(strands));
        var pts = strands.Points;
        var counts = strands.Counts;
        var tex = Texels;
        var bounds = StrandBounds.Empty;
        int live = 0;
        for (int r = 0; r < RenderStrands; r++)
        {
            int count = Math.Min(counts[r], Stride), first = r * Stride;
            int o = ((r / StrandsPerRow) * Width + (r % StrandsPerRow) * Stride) * 4;
            Vector3 last = count > 0 ? pts[first + count - 1] : Vector3.Zero;
            for (int k = 0; k < Stride; k++, o += 4)
            {
                bool alive = k < count;
                var p = alive ? pts[first + k] : last;
                tex[o] = p.X; tex[o + 1] = p.Y; tex[o + 2] = p.Z; tex[o + 3] = alive ? 1f : 0f;
                if (alive) bounds = bounds.Include(p);
            }
            live += count;
        }
        LivePoints = live;
        Bounds = bounds.Grow(Look.RootWidth);
        return live;
    }
}
