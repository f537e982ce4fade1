using System.Numerics;

namespace HairSheet.Logic;

/// <summary>
/// The demo's orbit camera: yaw/pitch/distance around a target. Produces a Godot-style camera basis
/// (X right, Y up, Z back: the camera looks along −Z at the target) and the eye position.
/// </summary>
public sealed class OrbitCamera
{
    private float _pitch, _distance = 0.6f;

    public Vector3 Target { get; set; }
    /// <summary>Radians about +Y; 0 puts the eye on +Z of the target (in front of a head facing +Z).</summary>
    public float Yaw { get; set; }
    /// <summary>Radians above the horizon, clamped to ±PitchLimit so the basis never degenerates at the poles.</summary>
    public float Pitch { get => _pitch; set => _pitch = Math.Clamp(value, -PitchLimit, PitchLimit); }
    public float Distance { get => _distance; set => _distance = Math.Clamp(value, MinDistance, MaxDistance); }
    public float PitchLimit { get; init; } = 1.45f;
    public float MinDistance { get; init; } = 0.15f;
    public float MaxDistance { get; init; } = 5f;

    /// <summary>Drag in pixels → rotation; dragging right turns the view to the right around the target.</summary>
    public void Orbit(Vector2 dragPixels, float radiansPerPixel = 0.008f)
    {
        if (!float.IsFinite(dragPixels.X) || !float.IsFinite(dragPixels.Y)) return;
        Yaw -= dragPixels.X * radiansPerPixel;
        Pitch += dragPixels.Y * radiansPerPixel;
        Yaw = MathF.IEEERemainder(Yaw, 2f * MathF.PI);
    }

    /// <summary>Wheel steps: positive zooms in (each step 10 % closer).</summary>
    public void Zoom(float steps)
    {
        if (!float.IsFinite(steps)) return;
        Distance = Distance * MathF.Pow(0.9f, steps);
    }

    public Vector3 Eye => Target + Distance * new Vector3(MathF.Cos(Pitch) * MathF.Sin(Yaw), MathF.Sin(Pitch), MathF.Cos(Pitch) * MathF.Cos(Yaw));

    /// <summary>Columns of the camera basis (Godot's Basis.X, .Y, .Z).</summary>
    public (Vector3 X, Vector3 Y, Vector3 Z) Basis
    {
        get
        {
            var z = Vector3.Normalize(Eye - Target);
            var x = Vector3.Normalize(Vector3.Cross(Vector3.UnitY, z));
            return (x, Vector3.Cross(z, x), z);
        }
    }
}
