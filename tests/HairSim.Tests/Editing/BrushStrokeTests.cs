using System.Numerics;
using HairSim.Editing;
using Xunit;

namespace HairSim.Tests.Editing;

/// <summary>
/// <see cref="SelectionArea.BrushStroke"/>, the dabs the studio's brush and the Godot scalp brushes paint and select
/// with: the union covers the whole path, even between points far apart, with no dab per pixel; bad strokes refused.
/// </summary>
public class BrushStrokeTests
{
    [Fact]
    public void The_dabs_cover_every_point_of_the_path_and_nothing_beyond_the_radius()
    {
        const float Radius = 10f;
        // A fast stroke (points 60 px apart) with a slow part (points 1 px apart).
        var stroke = new List<Vector2> { new(100, 100), new(160, 100), new(220, 130) };
        for (int i = 1; i <= 20; i++) stroke.Add(new Vector2(220 + i, 130));
        var dabs = SelectionArea.BrushStroke(stroke, Radius);
        bool Covered(Vector2 p) => dabs.Any(d => d.Contains(p));
        for (int i = 1; i < stroke.Count; i++)
            for (float t = 0f; t <= 1f; t += 0.01f)
                Assert.True(Covered(Vector2.Lerp(stroke[i - 1], stroke[i], t)), $"a gap in segment {i} at {t:F2}");
        Assert.False(Covered(new Vector2(130, 100 + Radius + 1f)), "a dab reaches past its radius");
        // No dab per point on the slow part: at most one per half radius of path, plus the first.
        float length = 0f;
        for (int i = 1; i < stroke.Count; i++) length += Vector2.Distance(stroke[i - 1], stroke[i]);
        Assert.InRange(dabs.Count, 2, (int)MathF.Ceiling(length / (0.5f * Radius)) + stroke.Count);
        Assert.Single(SelectionArea.BrushStroke([new Vector2(5, 5)], Radius));
    }

    [Fact]
    public void Bad_strokes_are_refused()
    {
        Assert.Throws<ArgumentException>(() => SelectionArea.BrushStroke([], 10f));
        Assert.ThrowsAny<ArgumentException>(() => SelectionArea.BrushStroke([new Vector2(1, 1)], 0f));
        Assert.ThrowsAny<ArgumentException>(() => SelectionArea.BrushStroke([new Vector2(1, 1)], float.NaN));
        Assert.Throws<ArgumentException>(() => SelectionArea.BrushStroke([new Vector2(1, 1), new Vector2(float.PositiveInfinity, 1)], 10f));
        var e = Assert.Throws<ArgumentException>(() => SelectionArea.BrushStroke([new Vector2(0, 0), new Vector2(1e7f, 0)], 1f));
        Assert.Contains("too long", e.Message);
    }
}
