using System.Numerics;

namespace HairSim.Editing;

public enum CameraProjection { Perspective, Orthographic }

/// <summary>
/// The camera that saw a stroke: view and projection matrices (System.Numerics row-vector convention,
/// clip = (p, 1) · View · Projection; the camera looks down its −Z, as in Godot and System.Numerics) and
/// the viewport size in pixels. Screen pixels have their origin at the top-left and y pointing down.
/// Both NDC depth conventions ([0, 1] and [−1, 1]) work: un-projection only uses depths 0 and 0.5.
/// </summary>
public sealed class StrokeCamera
{
    public const float MaxViewportPixels = 100_000f;

    private readonly Matrix4x4 _viewProjection, _inverseViewProjection;

    private StrokeCamera(Matrix4x4 view, Matrix4x4 projection, Vector2 viewportSize, CameraProjection kind)
    {
        CheckFinite(view, nameof(view));
        CheckFinite(projection, nameof(projection));
        if (!float.IsFinite(viewportSize.X) || !float.IsFinite(viewportSize.Y) || viewportSize.X < 1f || viewportSize.Y < 1f ||
            viewportSize.X > MaxViewportPixels || viewportSize.Y > MaxViewportPixels)
            throw new ArgumentOutOfRangeException(nameof(viewportSize), viewportSize, $"Viewport size must be 1 … {MaxViewportPixels} pixels each way.");
        if (kind == CameraProjection.Perspective && MathF.Abs(projection.M34) < 1e-6f)
            throw new ArgumentException("A perspective projection needs a non-zero M34 (w = −z_view); this matrix looks orthographic.", nameof(projection));
        if (kind == CameraProjection.Orthographic && (projection.M14 != 0f || projection.M24 != 0f || projection.M34 != 0f || projection.M44 == 0f))
            throw new ArgumentException("An orthographic projection has M14 = M24 = M34 = 0 and M44 ≠ 0.", nameof(projection));
        if (!Matrix4x4.Invert(view, out var inverseView) || !IsFinite(inverseView))
            throw new ArgumentException("The view matrix is singular.", nameof(view));
        var vp = view * projection;
        if (!Matrix4x4.Invert(vp, out var inv) || !IsFinite(inv) || MathF.Abs(vp.GetDeterminant()) < 1e-30f)
            throw new ArgumentException("The camera is singular (view × projection cannot be inverted).", nameof(projection));
        View = view; Projection = projection; ViewportSize = viewportSize; Kind = kind;
        _viewProjection = vp; _inverseViewProjection = inv;
        Position = inverseView.Translation;
        var f = -new Vector3(inverseView.M31, inverseView.M32, inverseView.M33);
        if (f.LengthSquared() < 1e-20f) throw new ArgumentException("The view matrix has no forward axis.", nameof(view));
        Forward = Vector3.Normalize(f);
    }

    public Matrix4x4 View { get; }
    public Matrix4x4 Projection { get; }
    public Vector2 ViewportSize { get; }
    public CameraProjection Kind { get; }
    /// <summary>Camera position in world space.</summary>
    public Vector3 Position { get; }
    /// <summary>World-space unit view direction.</summary>
    public Vector3 Forward { get; }
    public Matrix4x4 ViewProjection => _viewProjection;

    public static StrokeCamera Perspective(Matrix4x4 view, Matrix4x4 projection, Vector2 viewportSize) =>
        new(view, projection, viewportSize, CameraProjection.Perspective);

    public static StrokeCamera Orthographic(Matrix4x4 view, Matrix4x4 projection, Vector2 viewportSize) =>
        new(view, projection, viewportSize, CameraProjection.Orthographic);

    /// <summary>A perspective camera at eye looking at target (vertical field of view in radians).</summary>
    public static StrokeCamera LookAtPerspective(Vector3 eye, Vector3 target, Vector3 up, float fovY, Vector2 viewportSize, float near = 0.01f, float far = 100f)
    {
        if (!float.IsFinite(fovY) || fovY <= 0.01f || fovY >= 3.1f) throw new ArgumentOutOfRangeException(nameof(fovY), fovY, "Field of view must be in (0.01, 3.1) radians.");
        if (!float.IsFinite(viewportSize.X) || !float.IsFinite(viewportSize.Y) || viewportSize.X < 1f || viewportSize.Y < 1f)
            throw new ArgumentOutOfRangeException(nameof(viewportSize), viewportSize, "Viewport size must be at least 1 pixel each way.");
        return Perspective(LookAt(eye, target, up), Matrix4x4.CreatePerspectiveFieldOfView(fovY, viewportSize.X / viewportSize.Y, near, far), viewportSize);
    }

    /// <summary>An orthographic camera at eye looking at target, showing viewHeight metres vertically.</summary>
    public static StrokeCamera LookAtOrthographic(Vector3 eye, Vector3 target, Vector3 up, float viewHeight, Vector2 viewportSize, float near = 0.01f, float far = 100f)
    {
        if (!float.IsFinite(viewHeight) || viewHeight <= 0f) throw new ArgumentOutOfRangeException(nameof(viewHeight), viewHeight, "View height must be positive.");
        if (!float.IsFinite(viewportSize.X) || !float.IsFinite(viewportSize.Y) || viewportSize.X < 1f || viewportSize.Y < 1f)
            throw new ArgumentOutOfRangeException(nameof(viewportSize), viewportSize, "Viewport size must be at least 1 pixel each way.");
        return Orthographic(LookAt(eye, target, up), Matrix4x4.CreateOrthographic(viewHeight * viewportSize.X / viewportSize.Y, viewHeight, near, far), viewportSize);
    }

    private static Matrix4x4 LookAt(Vector3 eye, Vector3 target, Vector3 up)
    {
        var d = target - eye;
        if (!float.IsFinite(d.X + d.Y + d.Z + up.X + up.Y + up.Z) || d.LengthSquared() < 1e-12f || Vector3.Cross(d, up).LengthSquared() < 1e-12f * d.LengthSquared() * up.LengthSquared())
            throw new ArgumentException("Eye, target and up must be finite, distinct and not collinear.");
        return Matrix4x4.CreateLookAt(eye, target, up);
    }

    /// <summary>Screen position (pixels) and view depth (metres along <see cref="Forward"/>); false behind the camera.</summary>
    public bool Project(Vector3 world, out Vector2 screen, out float depth)
    {
        var m = _viewProjection;
        float cx = world.X * m.M11 + world.Y * m.M21 + world.Z * m.M31 + m.M41;
        float cy = world.X * m.M12 + world.Y * m.M22 + world.Z * m.M32 + m.M42;
        float cw = world.X * m.M14 + world.Y * m.M24 + world.Z * m.M34 + m.M44;
        depth = Vector3.Dot(world - Position, Forward);
        if (!(cw > 1e-9f)) { screen = default; return false; }
        screen = new Vector2((cx / cw + 1f) * 0.5f * ViewportSize.X, (1f - cy / cw) * 0.5f * ViewportSize.Y);
        return true;
    }

    /// <summary>The world-space ray through a screen point: origin on the camera (plane) and unit direction.</summary>
    public (Vector3 Origin, Vector3 Direction) ScreenRay(Vector2 screen)
    {
        float nx = 2f * screen.X / ViewportSize.X - 1f, ny = 1f - 2f * screen.Y / ViewportSize.Y;
        var a = Unproject(nx, ny, 0f);
        var b = Unproject(nx, ny, 0.5f);
        if (Kind == CameraProjection.Perspective)
        {
            var d = b - a;
            return (Position, Vector3.Normalize(Vector3.Dot(d, Forward) < 0 ? -d : d));
        }
        return (a - Forward * Vector3.Dot(a - Position, Forward), Forward);
    }

    private Vector3 Unproject(float nx, float ny, float nz)
    {
        var p = Vector4.Transform(new Vector4(nx, ny, nz, 1f), _inverseViewProjection);
        return new Vector3(p.X, p.Y, p.Z) / p.W;
    }

    /// <summary>Is a screen point inside the viewport (edges included)?</summary>
    public bool InViewport(Vector2 p) => p.X >= 0f && p.Y >= 0f && p.X <= ViewportSize.X && p.Y <= ViewportSize.Y;

    private static void CheckFinite(Matrix4x4 m, string name)
    {
        if (!IsFinite(m)) throw new ArgumentException($"The {name} matrix has non-finite entries.", name);
    }

    private static bool IsFinite(Matrix4x4 m) =>
        float.IsFinite(m.M11 + m.M12 + m.M13 + m.M14 + m.M21 + m.M22 + m.M23 + m.M24 +
                       m.M31 + m.M32 + m.M33 + m.M34 + m.M41 + m.M42 + m.M43 + m.M44) &&
        float.IsFinite(m.M11) && float.IsFinite(m.M22) && float.IsFinite(m.M33) && float.IsFinite(m.M44);
}
