namespace HairSheet.Logic;

/// <summary>How render strands reach the GPU through a MultiMesh (docs/godot.md compares the two).</summary>
public enum StrandRenderLayout
{
    /// <summary>One instance per strand segment: a 3×4 transform (+ colour, + custom data) per segment, every frame.</summary>
    SegmentInstances,
    /// <summary>One ribbon mesh per render strand; the vertex shader reads particle positions from an RGBAF texture.</summary>
    PositionTexture,
}

/// <summary>Root-to-tip look shared by both layouts: width taper and colour gradient.</summary>
public readonly record struct StrandLook(float RootWidth, float TipWidth)
{
    public static StrandLook Default => new(0.0012f, 0.0002f);

    /// <summary>Width at t ∈ [0, 1] along the strand's full (uncut) length, so a cut end stays blunt like real cut hair.</summary>
    public float WidthAt(float t) => RootWidth + (TipWidth - RootWidth) * t;

    public void Validate()
    {
        if (!float.IsFinite(RootWidth) || RootWidth <= 0f || RootWidth > 0.05f)
            throw new ArgumentOutOfRangeException(nameof(RootWidth), RootWidth, "Root width must be in (0, 0.05] m.");
        if (!float.IsFinite(TipWidth) || TipWidth < 0f || TipWidth > RootWidth)
            throw new ArgumentOutOfRangeException(nameof(TipWidth), TipWidth, "Tip width must be in 0 … root width.");
    }
}
