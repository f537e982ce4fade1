using System.Numerics;

namespace HairSheet.Logic;

/// <summary>Which viewport axis a Godot camera's fov / size refers to (Camera3D.KeepAspect).</summary>
public enum KeepAspect { Width, Height }

/// <summary>View and projection matrices (System.Numerics, row-vector convention) plus the viewport size in pixels.</summary>
public readonly record struct CameraMatrices(Matrix4x4 View, Matrix4x4 Projection, Vector2 Viewport);

/// <summary>
/// Turns Godot-style camera data (global transform as basis columns + origin, lens, viewport size) into the
/// view/projection pair HairSim's stroke code consumes. A Godot camera looks along its basis −Z with +Y up;
/// System.Numerics' right-handed projections look along −Z too, so no axis flip is needed. Screen pixels run
/// right and down from the viewport's top-left corner, as Godot's input events report them.
/// </summary>
public static class StrokeCameraMath
{
    /// <summary>View matrix: the inverse of the camera's world transform. The basis may be scaled; it is orthonormalised first.</summary>
    public static Matrix4x4 View(Vector3 basisX, Vector3 basisY, Vector3 basisZ, Vector3 origin)
    {
        Finite(origin, nameof(origin));
        var (x, y, z) = Orthonormalize(basisX, basisY, basisZ);
        var world = new Matrix4x4(
            x.X, x.Y, x.Z, 0f,
            y.X, y.Y, y.Z, 0f,
            z.X, z.Y, z.Z, 0f,
            origin.X, origin.Y, origin.Z, 1f);
        // Rigid inverse: transpose the rotation, rotate the negated origin.
        Matrix4x4.Invert(world, out var view);
        return view;
    }

    /// <summary>Godot perspective camera: fov in degrees along the KeepAspect axis, near/far planes.</summary>
    public static Matrix4x4 Perspective(float fovDegrees, float near, float far, Vector2 viewport, KeepAspect keep = KeepAspect.Height)
    {
        CheckViewport(viewport);
        if (!float.IsFinite(fovDegrees) || fovDegrees <= 0.01f || fovDegrees >= 179f)
            throw new ArgumentOutOfRangeException(nameof(fovDegrees), fovDegrees, "Camera fov must be in (0.01, 179) degrees.");
        CheckDepth(near, far);
        float aspect = viewport.X / viewport.Y;
        float half = fovDegrees * MathF.PI / 360f;
        float fovY = keep == KeepAspect.Height ? 2f * half : 2f * MathF.Atan(MathF.Tan(half) / aspect);
        return Matrix4x4.CreatePerspectiveFieldOfView(fovY, aspect, near, far);
    }

    /// <summary>Godot orthogonal camera: size is the full extent along the KeepAspect axis, in metres.</summary>
    public static Matrix4x4 Orthographic(float size, float near, float far, Vector2 viewport, KeepAspect keep = KeepAspect.Height)
    {
        CheckViewport(viewport);
        if (!float.IsFinite(size) || size <= 0f) throw new ArgumentOutOfRangeException(nameof(size), size, "Orthographic size must be positive.");
        if (!float.IsFinite(near) || !float.IsFinite(far) || far <= near)
            throw new ArgumentOutOfRangeException(nameof(far), far, "Far plane must lie beyond the near plane.");
        float aspect = viewport.X / viewport.Y;
        float h = keep == KeepAspect.Height ? size : size / aspect;
        return Matrix4x4.CreateOrthographic(h * aspect, h, near, far);
    }

    /// <summary>
    /// From Godot's Projection (Camera3D.GetCameraProjection()), given as its four columns. Godot multiplies
    /// column vectors (clip = P·v); System.Numerics multiplies row vectors (clip = v·M), so M = Pᵀ: column i
    /// of P becomes row i of M. Godot's clip depth is OpenGL's [−1, 1]; screen x and y are unaffected.
    /// </summary>
    public static Matrix4x4 FromGodotProjection(Vector4 c0, Vector4 c1, Vector4 c2, Vector4 c3)
    {
        var m = new Matrix4x4(c0.X, c0.Y, c0.Z, c0.W, c1.X, c1.Y, c1.Z, c1.W, c2.X, c2.Y, c2.Z, c2.W, c3.X, c3.Y, c3.Z, c3.W);
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++)
                if (!float.IsFinite(m[i, j])) throw new ArgumentException("Projection has non-finite entries.", nameof(c0));
        return m;
    }

    /// <summary>Pixel position of a world point and whether it is in front of the camera.</summary>
    public static bool WorldToScreen(in CameraMatrices cam, Vector3 world, out Vector2 pixel)
    {
        var clip = Vector4.Transform(new Vector4(world, 1f), cam.View * cam.Projection);
        if (clip.W <= 1e-12f) { pixel = default; return false; }
        float nx = clip.X / clip.W, ny = clip.Y / clip.W;
        pixel = new Vector2((nx * 0.5f + 0.5f) * cam.Viewport.X, (0.5f - ny * 0.5f) * cam.Viewport.Y);
        return true;
    }

    /// <summary>World-space ray through a pixel (origin on the near plane, unit direction).</summary>
    public static (Vector3 Origin, Vector3 Direction) ScreenRay(in CameraMatrices cam, Vector2 pixel)
    {
        if (!Matrix4x4.Invert(cam.View * cam.Projection, out var inv))
            throw new ArgumentException("Camera matrices are singular.", nameof(cam));
        float nx = pixel.X / cam.Viewport.X * 2f - 1f, ny = 1f - pixel.Y / cam.Viewport.Y * 2f;
        var a = Vector4.Transform(new Vector4(nx, ny, 0f, 1f), inv);
        var b = Vector4.Transform(new Vector4(nx, ny, 0.5f, 1f), inv);
        var pa = new Vector3(a.X, a.Y, a.Z) / a.W;
        var pb = new Vector3(b.X, b.Y, b.Z) / b.W;
        return (pa, Vector3.Normalize(pb - pa));
    }

    private static (Vector3, Vector3, Vector3) Orthonormalize(Vector3 bx, Vector3 by, Vector3 bz)
    {
        Finite(bx, nameof(bx)); Finite(by, nameof(by)); Finite(bz, nameof(bz));
        if (bz.LengthSquared() < 1e-20f || by.LengthSquared() < 1e-20f)
            throw new ArgumentException("Camera basis is degenerate (zero axis).");
        var z = Vector3.Normalize(bz);
        var x = Vector3.Cross(by, z);
        if (x.LengthSquared() < 1e-20f) throw new ArgumentException("Camera basis is degenerate (Y parallel to Z).");
        x = Vector3.Normalize(x);
        if (Vector3.Dot(x, bx) < 0f) throw new ArgumentException("Camera basis is mirrored (left-handed); Godot cameras are right-handed.");
        return (x, Vector3.Cross(z, x), z);
    }

    private static void CheckViewport(Vector2 v)
    {
        if (!float.IsFinite(v.X) || !float.IsFinite(v.Y) || v.X < 1f || v.Y < 1f)
            throw new ArgumentOutOfRangeException(nameof(v), v, "Viewport size must be at least 1 × 1 pixels.");
    }

    private static void CheckDepth(float near, float far)
    {
        if (!float.IsFinite(near) || near <= 0f) throw new ArgumentOutOfRangeException(nameof(near), near, "Near plane must be positive.");
        if (!float.IsFinite(far) || far <= near) throw new ArgumentOutOfRangeException(nameof(far), far, "Far plane must lie beyond the near plane.");
    }

    private static void Finite(Vector3 v, string name)
    {
        if (!float.IsFinite(v.X) || !float.IsFinite(v.Y) || !float.IsFinite(v.Z)) throw new ArgumentException($"{name} must be finite.", name);
    }
}
