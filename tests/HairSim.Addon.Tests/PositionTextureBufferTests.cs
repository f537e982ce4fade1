using System.Numerics;
using HairSheet.Logic;
using static HairSheet.Addon.Tests.TestScenes;

namespace HairSheet.Addon.Tests;

public class PositionTextureBufferTests
{
    [Fact]
    public void Each_live_point_lands_in_its_texel_and_cut_tails_collapse_onto_the_tip()
    {
        var rs = SteppedScene().RenderOutput!;
        rs.Counts[2] = 4; // as if cut
        var b = new PositionTextureBuffer(rs, StrandLook.Default);
        int live = b.Fill(rs);
        var texels = b.Texels.ToArray();
        int expectedLive = 0;
        for (int r = 0; r < rs.StrandCount; r++)
        {
            var pts = rs.Strand(r);
            expectedLive += pts.Length;
            for (int k = 0; k < rs.Stride; k++)
            {
                var (x, y) = b.TexelOf(r, k);
                int o = (y * b.Width + x) * 4;
                var p = new Vector3(texels[o], texels[o + 1], texels[o + 2]);
                if (k < pts.Length) { AssertClose(pts[k], p, 0f); Assert.Equal(1f, texels[o + 3]); }
                else { AssertClose(pts[^1], p, 0f); Assert.Equal(0f, texels[o + 3]); }
            }
        }
        Assert.Equal(expectedLive, live);
    }

    [Theory]
    [InlineData(34365, 16)]   // the reference scene's render strands at density 1
    [InlineData(1, 2)]
    [InlineData(4096, 4096)]
    [InlineData(100, 4096)]
    [InlineData(100_000, 33)]
    public void Texture_rows_hold_whole_strands_within_the_size_limit(int strands, int stride)
    {
        var b = new PositionTextureBuffer(strands, stride, StrandLook.Default);
        Assert.Equal(0, b.Width % stride);
        Assert.InRange(b.Width, stride, PositionTextureBuffer.MaxTextureWidth);
        Assert.InRange(b.Height, 1, PositionTextureBuffer.MaxTextureWidth);
        Assert.True((long)b.Height * b.StrandsPerRow >= strands);
        Assert.True((long)(b.Height - 1) * b.StrandsPerRow < strands);
        var (x, y) = b.TexelOf(strands - 1, stride - 1);
        Assert.InRange(x, 0, b.Width - 1);
        Assert.InRange(y, 0, b.Height - 1);
        Assert.Equal((long)b.Width * b.Height * 16, b.TexelBytes.LongLength);
        // The size mobile and web GPUs guarantee, in both directions.
        Assert.True(b.Width <= 4096 && b.Height <= 4096, $"{b.Width} × {b.Height}");
    }

    [Fact]
    public void Points_per_strand_past_the_texture_width_are_refused()
    {
        Assert.Throws<ArgumentOutOfRangeException>(() => new PositionTextureBuffer(10, 4097, StrandLook.Default));
        // And more strands of the widest kind than 4096 rows hold.
        Assert.Throws<ArgumentOutOfRangeException>(() => new PositionTextureBuffer(4097, 4096, StrandLook.Default));
    }

    [Fact]
    public void Strand_index_survives_half_precision_custom_data()
    {
        foreach (int r in new[] { 0, 1, 1023, 1024, 2047, 2048, 34364, 500_000, 1024 * 2048 - 1 })
        {
            var (lo, hi) = PositionTextureBuffer.EncodeIndex(r);
            // The Compatibility renderer stores custom data as 16-bit floats.
            float loHalf = (float)(Half)lo, hiHalf = (float)(Half)hi;
            Assert.Equal(r, PositionTextureBuffer.DecodeIndex(loHalf, hiHalf));
        }
    }

    [Fact]
    public void Instance_buffer_is_identity_transforms_carrying_each_strand_index()
    {
        var b = new PositionTextureBuffer(3000, 16, StrandLook.Default);
        Assert.Equal(3000 * PositionTextureBuffer.InstanceFloats, b.InstanceBuffer.Length);
        for (int r = 0; r < b.InstanceCount; r++)
        {
            var m = b.InstanceBuffer.AsSpan(r * 16, 16);
            var p = new Vector3(0.3f, -1.2f, 2f);
            AssertClose(p, SegmentInstanceBuffer.TransformPoint(m, p), 0f);
            Assert.Equal(r, PositionTextureBuffer.DecodeIndex(m[12], m[13]));
        }
    }

    [Fact]
    public void Fill_allocates_nothing_and_uploads_fewer_bytes_than_segment_instances()
    {
        var rs = SteppedScene().RenderOutput!;
        var tex = new PositionTextureBuffer(rs, StrandLook.Default);
        var seg = new SegmentInstanceBuffer(rs, false, true, StrandLook.Default);
        tex.Fill(rs); seg.Fill(rs);
        long before = GC.GetAllocatedBytesForCurrentThread();
        for (int i = 0; i < 10; i++) tex.Fill(rs);
        Assert.Equal(0, GC.GetAllocatedBytesForCurrentThread() - before);
        // 16 bytes per point against 64 bytes per segment: the texture moves less whenever strands have > 1 segment.
        Assert.True(tex.BytesPerUpload < seg.BytesPerUpload, $"{tex.BytesPerUpload} vs {seg.BytesPerUpload}");
    }

    [Fact]
    public void Bounds_cover_live_points_only()
    {
        var rs = SteppedScene().RenderOutput!;
        var b = new PositionTextureBuffer(rs, StrandLook.Default);
        b.Fill(rs);
        for (int r = 0; r < rs.StrandCount; r++)
            foreach (var p in rs.Strand(r)) Assert.True(b.Bounds.Contains(p));
        Assert.False(b.Bounds.IsEmpty);
    }

    [Fact]
    public void Absurd_sizes_are_refused()
    {
        Assert.Throws<ArgumentOutOfRangeException>(() => new PositionTextureBuffer(10, 1, StrandLook.Default));
        Assert.Throws<ArgumentOutOfRangeException>(() => new PositionTextureBuffer(10, 20000, StrandLook.Default));
        Assert.Throws<ArgumentOutOfRangeException>(() => new PositionTextureBuffer(1024 * 2048, 2, StrandLook.Default));
        Assert.Throws<ArgumentOutOfRangeException>(() => new PositionTextureBuffer(0, 16, StrandLook.Default));
    }

    [Fact]
    public void Ribbon_meshes_index_only_their_own_vertices()
    {
        var strand = StrandRibbonMesh.Strand(16);
        Assert.Equal(32, strand.VertexCount);
        Assert.Equal(15 * 6, strand.Indices.Length);
        Assert.All(strand.Indices, i => Assert.InRange(i, 0, strand.VertexCount - 1));
        // UV.y names the point index, UV.x the side, as the shader expects.
        Assert.Equal(15f, strand.Uvs[31 * 2 + 1]);
        Assert.Equal(0.5f, strand.Uvs[31 * 2]);
        var seg = StrandRibbonMesh.Segment();
        Assert.Equal(8, seg.VertexCount);
        Assert.All(seg.Indices, i => Assert.InRange(i, 0, 7));
        Assert.Throws<ArgumentOutOfRangeException>(() => StrandRibbonMesh.Strand(1));
    }
}
