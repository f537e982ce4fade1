using System.Numerics;

namespace HairSim.Measurement;

/// <summary>Head trajectories the cases and the stability map drive the roots with.</summary>
public static class HeadMotion
{
    /// <summary>A head shaking "no" (±40° at 1.5 Hz) while bobbing 3 cm at 2 Hz, as a game character would.</summary>
    public static RigidTransform Shake(float t)
    {
        float yaw = 0.7f * MathF.Sin(2 * MathF.PI * 1.5f * t);
        return new RigidTransform(new Vector3(0, 0.03f * MathF.Sin(2 * MathF.PI * 2f * t), 0),
            Quaternion.CreateFromAxisAngle(Vector3.UnitY, yaw));
    }

    /// <summary>Spinning about the vertical axis at <paramref name="turnsPerSecond"/>.</summary>
    public static RigidTransform Spin(float t, float turnsPerSecond) =>
        new(Vector3.Zero, Quaternion.CreateFromAxisAngle(Vector3.UnitY, 2 * MathF.PI * turnsPerSecond * t));

    /// <summary>The head sweeping ±8 cm sideways and nodding ±30° at 1 Hz: hair is pressed into the scalp and slides.</summary>
    public static RigidTransform Sweep(float t)
    {
        float phase = 2 * MathF.PI * t;
        return new RigidTransform(new Vector3(0.08f * MathF.Sin(phase), 0, 0),
            Quaternion.CreateFromAxisAngle(Vector3.UnitX, 0.5f * MathF.Sin(phase)));
    }
}
