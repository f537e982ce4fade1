using System.Numerics;
using HairSim.Editing;

namespace HairSim.Cli.Studio;

// The JSON the page and the server exchange (System.Text.Json, camelCase names).

/// <summary>
/// The browser's camera when a stroke was drawn: three.js's view matrix (camera.matrixWorldInverse.elements) and
/// projection matrix (camera.projectionMatrix.elements), both column-major, and the canvas size in CSS pixels.
/// A column-major column-vector matrix read row by row is the same matrix in System.Numerics' row-vector
/// convention, so the sixteen numbers map to M11 … M44 in order.
/// </summary>
public sealed class CameraRequest
{
    public float[]? View { get; set; }
    public float[]? Projection { get; set; }
    public float Width { get; set; }
    public float Height { get; set; }

    public StrokeCamera ToStrokeCamera() =>
        StrokeCamera.Perspective(Matrix(View, "view"), Matrix(Projection, "projection"), new Vector2(Width, Height));

    private static Matrix4x4 Matrix(float[]? e, string name)
    {
        if (e is not { Length: 16 }) throw new ArgumentException($"The camera's {name} matrix must have 16 numbers.");
        foreach (float v in e) if (!float.IsFinite(v)) throw new ArgumentException($"The camera's {name} matrix has a non-finite number.");
        return new Matrix4x4(e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7], e[8], e[9], e[10], e[11], e[12], e[13], e[14], e[15]);
    }
}

/// <summary>A stroke on the canvas: points as x0, y0, x1, y1, … in CSS pixels from the top-left.</summary>
public sealed class StrokeRequest
{
    public float[]? Points { get; set; }
    public CameraRequest? Camera { get; set; }
    /// <summary>Cut only: true cuts only hair in front of the head; false cuts through it.</summary>
    public bool VisibleOnly { get; set; } = true;

    public Stroke ToStroke()
    {
        var camera = Camera?.ToStrokeCamera() ?? throw new ArgumentException("A stroke needs the camera it was drawn with.");
        return new Stroke(ParsePoints(Points, 2), camera);
    }

    internal static Vector2[] ParsePoints(float[]? flat, int min)
    {
        if (flat == null || flat.Length < 2 * min) throw new ArgumentException($"A stroke needs at least {min} point{(min > 1 ? "s" : "")}.");
        if (flat.Length % 2 != 0) throw new ArgumentException("Stroke points come in x, y pairs.");
        if (flat.Length / 2 > StudioSession.MaxStrokePoints) throw new ArgumentException($"A stroke may have at most {StudioSession.MaxStrokePoints:N0} points.");
        var pts = new Vector2[flat.Length / 2];
        for (int i = 0; i < pts.Length; i++)
        {
            pts[i] = new Vector2(flat[2 * i], flat[2 * i + 1]);
            if (!float.IsFinite(pts[i].X + pts[i].Y)) throw new ArgumentException("A stroke point is not a finite number.");
        }
        return pts;
    }
}

public sealed class SelectRequest
{
    /// <summary>rectangle (two corners), lasso (a polygon) or brush (a path with a radius).</summary>
    public string Shape { get; set; } = "rectangle";
    /// <summary>replace, add or subtract.</summary>
    public string Mode { get; set; } = "replace";
    public float[]? Points { get; set; }
    public float Radius { get; set; } = 30f;
    public bool RootsOnly { get; set; } = true;
    public bool VisibleOnly { get; set; } = true;
    public CameraRequest? Camera { get; set; }
}

/// <summary>Live settings; null leaves a value as it is. Gravity is in g (1 = Earth), the rest as SimulationSettings documents them.</summary>
public sealed class SettingsRequest
{
    public float? Sag { get; set; }
    public float? BendDamping { get; set; }
    public float? Damping { get; set; }
    public float? Gravity { get; set; }
    public int? Substeps { get; set; }
    public float? StaticFriction { get; set; }
    public float? KineticFriction { get; set; }
    public string? Path { get; set; }
    /// <summary>Hair volume on or off (docs/volume.md); its stiffness, friction and target density as VolumeSettings documents them.</summary>
    public bool? Volume { get; set; }
    public float? VolumeStiffness { get; set; }
    public float? VolumeFriction { get; set; }
    public float? VolumeDensity { get; set; }
}

/// <summary>A paint stroke on a head mesh's scalp: a rectangle, lasso or brush (as selections are drawn) that adds or erases.</summary>
public sealed class ScalpPaintRequest
{
    /// <summary>rectangle (two corners), lasso (a polygon) or brush (a path with a radius).</summary>
    public string Shape { get; set; } = "brush";
    /// <summary>add (paint scalp) or erase.</summary>
    public string Mode { get; set; } = "add";
    public float[]? Points { get; set; }
    public float Radius { get; set; } = 30f;
    public CameraRequest? Camera { get; set; }
}

/// <summary>The whole scalp at once: none, all, or colours (the mesh's vertex-colour scalp).</summary>
public sealed class ScalpFillRequest
{
    public string? To { get; set; }
}

public sealed class HeadRequest
{
    public float[]? Position { get; set; }
    public float Yaw { get; set; }
    public float Pitch { get; set; }
    public float Roll { get; set; }
    public bool Shake { get; set; }
}

public sealed class GroomRequest
{
    public string? Name { get; set; }
    public int? StrandsPerSheet { get; set; }
}

public sealed record GroomChoice(string Name, string Description);
public sealed record MetricsState(double LengthRatio, double MaxEdgeStretch, double MaxPenetrationMm, int ParticlesInside, int NonFinite);
public sealed record ColliderState(string Kind, float[] Center, float[] End, float[] Radii, float[] Rotation);
/// <summary>
/// A head mesh's painted scalp: triangles in the mesh and painted, the painted area, a revision that changes with the
/// mask (the page fetches api/scalp then), the paint strokes to undo and redo, the strands a grow would make now, and
/// whether a grow is running.
/// </summary>
public sealed record ScalpState(int Triangles, int Painted, double AreaCm2, int Revision, int UndoCount, int RedoCount, int GrowStrands, bool Growing);

/// <summary>Everything the page shows besides the strands themselves.</summary>
public sealed record StudioState(
    string Groom, GroomChoice[] Grooms, bool CanRegrow, bool HasMesh,
    int Strands, int Particles, int LiveParticles, int CutStrands, double TotalRestLength, int EditStamp,
    int Revision, long Frame, double SimTime, double StepMs, double StepMsWorst, double SimHz, bool Paused, bool Shake,
    int UndoCount, int RedoCount, int[] Selection,
    MetricsState Metrics, SettingsRequest Settings, HeadRequest Head, ColliderState[] Colliders, ScalpState? Scalp, string Message);
