using System.Collections.Generic;
using System.Numerics;
using HairSheet.Logic;
using HairSim;

namespace HairSheet;

/// <summary>
/// A stroke tool shared by the editor plugin and the run-time HairStrokeTool node: completed screen strokes
/// plus the camera in, an edit out. Projection, cutting and fitting are the library's (via HairEditAdapter).
/// </summary>
public interface IHairStrokeTool
{
    string Name { get; }
    /// <summary>What the user should draw next.</summary>
    string Hint { get; }
    /// <summary>An edit to apply, or null when the tool needs another stroke first. Bad strokes throw ArgumentException.</summary>
    HairEdit? Complete(HairScene scene, IReadOnlyList<Vector2> stroke, in CameraMatrices camera);
    /// <summary>The area drawn so far by a multi-stroke tool (for overlays); empty otherwise.</summary>
    IReadOnlyList<Vector2> PendingArea { get; }
    void Reset();
}
