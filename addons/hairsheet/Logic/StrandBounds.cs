using System.Numerics;

namespace HairSheet.Logic;

/// <summary>An axis-aligned box around render strands; becomes the MultiMesh's CustomAabb.</summary>
public readonly record struct StrandBounds(Vector3 Min, Vector3 Max)
{
    /// <summary>The empty box: Include() of any point makes it that point.</summary>
    public static StrandBounds Empty => new(new Vector3(float.PositiveInfinity), new Vector3(float.NegativeInfinity));

    public bool IsEmpty => Min.X > Max.X || Min.Y > Max.Y || Min.Z > Max.Z;
    public Vector3 Size => IsEmpty ? Vector3.Zero : Max - Min;

    public StrandBounds Include(Vector3 p) => new(Vector3.Min(Min, p), Vector3.Max(Max, p));

    /// <summary>Grown by margin on every side (strand width, so ribbons at the edge are not culled).</summary>
    public StrandBounds Grow(float margin) => IsEmpty ? this : new(Min - new Vector3(margin), Max + new Vector3(margin));

    public bool Contains(Vector3 p) =>
        p.X >= Min.X && p.Y >= Min.Y && p.Z >= Min.Z && p.X <= Max.X && p.Y <= Max.Y && p.Z <= Max.Z;
}
