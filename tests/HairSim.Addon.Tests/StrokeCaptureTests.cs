using System.Numerics;
using HairSheet.Logic;

namespace HairSheet.Addon.Tests;

public class StrokeCaptureTests
{
    private static PointerSample S(PointerPhase ph, float x, float y, int id = StrokeCapture.MousePointer) => new(ph, id, new Vector2(x, y));

    [Fact]
    public void A_drag_becomes_a_polyline_with_minimum_spacing_and_the_release_point_last()
    {
        var c = new StrokeCapture(minSpacing: 5f, minLength: 8f);
        Assert.Equal(StrokeEvent.Started, c.Handle(S(PointerPhase.Down, 0, 0)));
        Assert.Equal(StrokeEvent.Skipped, c.Handle(S(PointerPhase.Move, 2, 0)));    // too close
        Assert.Equal(StrokeEvent.Extended, c.Handle(S(PointerPhase.Move, 6, 0)));
        Assert.Equal(StrokeEvent.Skipped, c.Handle(S(PointerPhase.Move, 6, 0)));    // duplicate
        Assert.Equal(StrokeEvent.Extended, c.Handle(S(PointerPhase.Move, 12, 0)));
        Assert.Equal(StrokeEvent.Skipped, c.Handle(S(PointerPhase.Move, 14, 0)));
        Assert.Equal(StrokeEvent.Completed, c.Handle(S(PointerPhase.Up, 15, 0)));
        Assert.Equal(new[] { new Vector2(0, 0), new Vector2(6, 0), new Vector2(12, 0), new Vector2(15, 0) }, c.Completed);
        Assert.False(c.IsDrawing);
        Assert.Empty(c.Points);
        for (int i = 1; i < c.Completed.Count - 1; i++)
            Assert.True(Vector2.Distance(c.Completed[i - 1], c.Completed[i]) >= 5f);
    }

    [Fact]
    public void A_click_or_tap_is_too_short_and_keeps_the_previous_stroke()
    {
        var c = new StrokeCapture(4f, 8f);
        c.Handle(S(PointerPhase.Down, 0, 0)); c.Handle(S(PointerPhase.Move, 50, 0)); c.Handle(S(PointerPhase.Up, 60, 0));
        var previous = c.Completed.ToArray();
        c.Handle(S(PointerPhase.Down, 100, 100));
        Assert.Equal(StrokeEvent.TooShort, c.Handle(S(PointerPhase.Up, 103, 100)));
        Assert.Equal(previous, c.Completed);
        c.Handle(S(PointerPhase.Down, 100, 100));
        Assert.Equal(StrokeEvent.TooShort, c.Handle(S(PointerPhase.Up, 100, 100)));
    }

    [Fact]
    public void A_second_finger_cancels_and_other_fingers_are_ignored()
    {
        var c = new StrokeCapture(1f, 1f);
        Assert.Equal(StrokeEvent.Started, c.Handle(S(PointerPhase.Down, 0, 0, id: 0)));
        Assert.Equal(StrokeEvent.Ignored, c.Handle(S(PointerPhase.Move, 40, 0, id: 1)));
        Assert.Equal(StrokeEvent.Extended, c.Handle(S(PointerPhase.Move, 10, 0, id: 0)));
        Assert.Equal(StrokeEvent.Cancelled, c.Handle(S(PointerPhase.Down, 50, 50, id: 1)));
        Assert.False(c.IsDrawing);
        Assert.Equal(StrokeEvent.Ignored, c.Handle(S(PointerPhase.Up, 20, 0, id: 0)));
        Assert.Empty(c.Completed);
    }

    [Fact]
    public void Cancel_and_non_finite_input_leave_no_stroke()
    {
        var c = new StrokeCapture(1f, 1f);
        Assert.Equal(StrokeEvent.Ignored, c.Handle(S(PointerPhase.Down, float.NaN, 0)));
        Assert.False(c.IsDrawing);
        c.Handle(S(PointerPhase.Down, 0, 0));
        Assert.Equal(StrokeEvent.Ignored, c.Handle(S(PointerPhase.Move, float.PositiveInfinity, 0)));
        c.Handle(S(PointerPhase.Move, 10, 0));
        Assert.Equal(StrokeEvent.Cancelled, c.Handle(S(PointerPhase.Cancel, 0, 0)));
        Assert.Empty(c.Points);
        Assert.Empty(c.Completed);
    }

    [Fact]
    public void Mouse_and_touch_give_the_same_stroke()
    {
        var path = new[] { new Vector2(10, 10), new Vector2(13, 11), new Vector2(30, 15), new Vector2(31, 15), new Vector2(60, 40) };
        IReadOnlyList<Vector2> Run(int id)
        {
            var c = new StrokeCapture(4f, 8f);
            c.Handle(new PointerSample(PointerPhase.Down, id, path[0]));
            for (int i = 1; i < path.Length - 1; i++) c.Handle(new PointerSample(PointerPhase.Move, id, path[i]));
            Assert.Equal(StrokeEvent.Completed, c.Handle(new PointerSample(PointerPhase.Up, id, path[^1])));
            return c.Completed;
        }
        Assert.Equal(Run(StrokeCapture.MousePointer), Run(3));
    }

    [Fact]
    public void The_point_limit_caps_a_runaway_stroke()
    {
        var c = new StrokeCapture(1f, 1f, maxPoints: 10);
        c.Handle(S(PointerPhase.Down, 0, 0));
        for (int i = 1; i < 100; i++) c.Handle(S(PointerPhase.Move, i * 2, 0));
        Assert.Equal(10, c.Points.Count);
        c.Handle(S(PointerPhase.Up, 500, 0));
        Assert.Equal(10, c.Completed.Count);
        Assert.Equal(new Vector2(500, 0), c.Completed[^1]);
    }

    [Fact]
    public void Fit_takes_an_area_then_a_shape_stroke()
    {
        var g = new FitGesture();
        var loop = new[] { new Vector2(0, 0), new Vector2(100, 0), new Vector2(100, 80), new Vector2(0, 80) };
        Assert.Equal(8000f, FitGesture.PolygonArea(loop), 3);
        Assert.False(g.Accept(loop, out _, out _));
        Assert.Equal(FitGesture.Phase.DrawShape, g.Current);
        var shape = new[] { new Vector2(50, 0), new Vector2(60, 120) };
        Assert.True(g.Accept(shape, out var area, out var got));
        Assert.Equal(loop, area);
        Assert.Equal(shape, got);
        Assert.Equal(FitGesture.Phase.SelectArea, g.Current);
    }

    [Fact]
    public void Fit_refuses_a_selection_without_area()
    {
        var g = new FitGesture();
        var line = new[] { new Vector2(0, 0), new Vector2(50, 50), new Vector2(100, 100) };
        Assert.Throws<ArgumentException>(() => g.Accept(line, out _, out _));
        Assert.Equal(FitGesture.Phase.SelectArea, g.Current);
        Assert.Empty(g.Area);
    }
}
