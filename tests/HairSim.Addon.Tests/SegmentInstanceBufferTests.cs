using System.Numerics;
using HairSheet.Logic;
using HairSim;
using static HairSheet.Addon.Tests.TestScenes;

namespace HairSheet.Addon.Tests;

public class SegmentInstanceBufferTests
{
    [Theory]
    [InlineData(false, false, 12)]
    [InlineData(true, false, 16)]
    [InlineData(false, true, 16)]
    [InlineData(true, true, 20)]
    public void Every_instance_maps_the_unit_segment_onto_its_render_segment(bool colors, bool custom, int floats)
    {
        var scene = SteppedScene();
        var rs = scene.RenderOutput!;
        var b = new SegmentInstanceBuffer(rs, colors, custom, StrandLook.Default);
        Assert.Equal(floats, b.FloatsPerInstance);
        int n = b.Fill(rs);
        int i = 0;
        for (int r = 0; r < rs.StrandCount; r++)
        {
            var pts = rs.Strand(r);
            for (int k = 0; k + 1 < pts.Length; k++, i++)
            {
                var m = b.Buffer.AsSpan(i * floats, 12);
                AssertClose(pts[k], SegmentInstanceBuffer.TransformPoint(m, Vector3.Zero));
                AssertClose(pts[k + 1], SegmentInstanceBuffer.TransformPoint(m, Vector3.UnitY));
            }
        }
        Assert.Equal(i, n);
        Assert.Equal(n, b.VisibleInstances);
    }

    [Fact]
    public void Counts_follow_cuts_while_the_buffer_is_reused()
    {
        var scene = SteppedScene();
        var rs = scene.RenderOutput!;
        var b = new SegmentInstanceBuffer(rs, false, true, StrandLook.Default);
        Assert.Equal(rs.StrandCount * (rs.Stride - 1), b.MaxInstances);
        Assert.Equal(b.MaxInstances * b.FloatsPerInstance, b.Buffer.Length);
        var buffer = b.Buffer;
        Assert.Equal(b.MaxInstances, b.Fill(rs));

        // A cut lowers the live point count of some render strands: fewer visible instances, same array.
        rs.Counts[0] = 3;
        rs.Counts[5] = 2;
        int expected = 0;
        foreach (int c in rs.Counts) expected += c - 1;
        Assert.Equal(expected, b.Fill(rs));
        Assert.True(b.VisibleInstances < b.MaxInstances);
        Assert.Same(buffer, b.Buffer);
        Assert.Equal((long)expected * b.FloatsPerInstance * 4, b.VisibleBytes);
        Assert.Equal((long)b.MaxInstances * b.FloatsPerInstance * 4, b.BytesPerUpload);
    }

    [Fact]
    public void Width_axes_are_perpendicular_to_the_segment_and_taper_to_the_tip()
    {
        var rs = SteppedScene().RenderOutput!;
        var look = new StrandLook(0.002f, 0.0004f);
        var b = new SegmentInstanceBuffer(rs, false, true, look);
        b.Fill(rs);
        int perStrand = rs.Stride - 1;
        for (int k = 0; k < perStrand; k++)
        {
            var m = b.Buffer.AsSpan(k * 16, 16);
            var bx = new Vector3(m[0], m[4], m[8]);
            var by = new Vector3(m[1], m[5], m[9]);
            var bz = new Vector3(m[2], m[6], m[10]);
            float t0 = k / (float)(rs.Stride - 1), t1 = (k + 1) / (float)(rs.Stride - 1);
            Assert.Equal(look.WidthAt(0.5f * (t0 + t1)), bx.Length(), 6);
            Assert.Equal(look.WidthAt(0.5f * (t0 + t1)), bz.Length(), 6);
            Assert.True(MathF.Abs(Vector3.Dot(Vector3.Normalize(bx), Vector3.Normalize(by))) < 1e-4f);
            Assert.True(MathF.Abs(Vector3.Dot(Vector3.Normalize(bz), Vector3.Normalize(by))) < 1e-4f);
            Assert.True(MathF.Abs(Vector3.Dot(Vector3.Normalize(bx), Vector3.Normalize(bz))) < 1e-4f);
            // Custom data: where along the full strand the segment runs (root-to-tip colour in the shader).
            Assert.Equal(t0, m[12], 6);
            Assert.Equal(t1, m[13], 6);
            Assert.InRange(m[14], 0f, 1f);
        }
        Assert.True(look.WidthAt(1f) < look.WidthAt(0f));
    }

    [Fact]
    public void Colours_come_before_custom_data_and_run_root_to_tip()
    {
        var rs = SteppedScene().RenderOutput!;
        var b = new SegmentInstanceBuffer(rs, true, true, StrandLook.Default)
        {
            RootColor = new Vector4(1, 0, 0, 1),
            TipColor = new Vector4(0, 0, 1, 1),
        };
        b.Fill(rs);
        var first = b.Buffer.AsSpan(0, 20);
        var last = b.Buffer.AsSpan((rs.Stride - 2) * 20, 20);
        Assert.True(first[12] > first[14]);   // near the root: red
        Assert.True(last[14] > last[12]);     // near the tip: blue
        Assert.Equal(0f, first[16], 6);       // custom data t0 after the colour
    }

    [Fact]
    public void Zero_length_segment_gives_an_invisible_instance_not_NaN()
    {
        Span<float> m = stackalloc float[12];
        SegmentInstanceBuffer.WriteSegment(m, new Vector3(1, 2, 3), new Vector3(1, 2, 3), 0.001f);
        foreach (float f in m) Assert.True(float.IsFinite(f));
        AssertClose(new Vector3(1, 2, 3), SegmentInstanceBuffer.TransformPoint(m, new Vector3(0.5f, 1f, -0.5f)));
    }

    [Fact]
    public void Orthonormal_frame_is_right_handed_for_every_direction()
    {
        var rng = new SplitMix64(7);
        for (int i = 0; i < 1000; i++)
        {
            var n = Vector3.Normalize(new Vector3(rng.NextFloat() - 0.5f, rng.NextFloat() - 0.5f, rng.NextFloat() - 0.5f));
            if (i == 0) n = -Vector3.UnitZ;
            if (i == 1) n = Vector3.UnitZ;
            SegmentInstanceBuffer.Orthonormal(n, out var u, out var v);
            Assert.Equal(1f, u.Length(), 4);
            Assert.Equal(1f, v.Length(), 4);
            Assert.True(MathF.Abs(Vector3.Dot(u, n)) < 1e-4f && MathF.Abs(Vector3.Dot(v, n)) < 1e-4f && MathF.Abs(Vector3.Dot(u, v)) < 1e-4f);
            AssertClose(n, Vector3.Cross(u, v), 1e-4f);
        }
    }

    [Fact]
    public void Bounds_contain_every_live_point_with_the_width_as_margin()
    {
        var rs = SteppedScene().RenderOutput!;
        var b = new SegmentInstanceBuffer(rs, false, false, StrandLook.Default);
        b.Fill(rs);
        var min = new Vector3(float.MaxValue); var max = new Vector3(float.MinValue);
        for (int r = 0; r < rs.StrandCount; r++)
            foreach (var p in rs.Strand(r)) { Assert.True(b.Bounds.Contains(p)); min = Vector3.Min(min, p); max = Vector3.Max(max, p); }
        AssertClose(min - new Vector3(StrandLook.Default.RootWidth), b.Bounds.Min);
        AssertClose(max + new Vector3(StrandLook.Default.RootWidth), b.Bounds.Max);
    }

    [Fact]
    public void Fill_allocates_nothing()
    {
        var rs = SteppedScene().RenderOutput!;
        var b = new SegmentInstanceBuffer(rs, true, true, StrandLook.Default);
        b.Fill(rs);
        long before = GC.GetAllocatedBytesForCurrentThread();
        for (int i = 0; i < 10; i++) b.Fill(rs);
        Assert.Equal(0, GC.GetAllocatedBytesForCurrentThread() - before);
    }

    [Fact]
    public void Render_strands_of_another_layout_are_refused()
    {
        var rs = SteppedScene(strandsPerGap: 1).RenderOutput!;
        var other = SteppedScene(strandsPerGap: 2).RenderOutput!;
        var b = new SegmentInstanceBuffer(rs, false, false, StrandLook.Default);
        Assert.Throws<ArgumentException>(() => b.Fill(other));
        Assert.Throws<ArgumentOutOfRangeException>(() => new SegmentInstanceBuffer(0, 16, false, false, StrandLook.Default));
        Assert.Throws<ArgumentOutOfRangeException>(() => new SegmentInstanceBuffer(10, 16, false, false, new StrandLook(0.001f, 0.002f)));
    }
}
