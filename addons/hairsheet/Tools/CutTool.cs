using System.Collections.Generic;
using System.Numerics;
using HairSheet.Logic;
using HairSim;

namespace HairSheet;

/// <summary>Cut (SPEC A.5, Algorithm 2): every strand the stroke crosses ends where it crosses.</summary>
public sealed class CutTool : IHairStrokeTool
{
    public string Name => "Cut";
    public string Hint => "Cut: draw a line across the strands to cut.";
    public IReadOnlyList<Vector2> PendingArea => [];

    public HairEdit? Complete(HairScene scene, IReadOnlyList<Vector2> stroke, in CameraMatrices camera) =>
        HairEditAdapter.Cut(scene, stroke, camera);

    public void Reset() { }
}
