using HairSim.Editing;

namespace HairSheet.Logic;

/// <summary>HairSim's stroke camera for Godot camera matrices: a projection with no perspective divide (last column 0, 0, 0, 1) is orthographic.</summary>
public static class StrokeCameras
{
    public static StrokeCamera From(in CameraMatrices camera) =>
        camera.Projection.M34 == 0f && camera.Projection.M44 == 1f
            ? StrokeCamera.Orthographic(camera.View, camera.Projection, camera.Viewport)
            : StrokeCamera.Perspective(camera.View, camera.Projection, camera.Viewport);
}
