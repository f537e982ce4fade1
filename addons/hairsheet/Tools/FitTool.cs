using System.Collections.Generic;
using System.Numerics;
using HairSheet.Logic;
using HairSim;

namespace HairSheet;

/// <summary>
/// Fit (SPEC A.5, Algorithm 3): first stroke encloses the strands to shape, second stroke is the shape;
/// the library fits the selection's key curve to it and the strands follow with their offsets kept.
/// </summary>
public sealed class FitTool : IHairStrokeTool
{
    private readonly FitGesture _gesture = new();

    public string Name => "Fit";
    public string Hint => _gesture.Current == FitGesture.Phase.SelectArea
        ? "Fit: draw a loop around the strands to shape."
        : "Fit: now draw the shape the selected strands should follow.";
    public IReadOnlyList<Vector2> PendingArea => _gesture.Area;

    public HairEdit? Complete(HairScene scene, IReadOnlyList<Vector2> stroke, in CameraMatrices camera)
    {
        if (!_gesture.Accept(stroke, out var area, out var shape)) return null;
        return HairEditAdapter.Fit(scene, area, shape, camera);
    }

    public void Reset() => _gesture.Reset();
}
