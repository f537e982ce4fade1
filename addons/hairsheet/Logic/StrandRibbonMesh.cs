namespace HairSheet.Logic;

/// <summary>
/// Static geometry both layouts instance, as plain arrays the Godot side turns into an ArrayMesh.
/// Positions only matter for layout A (the shader places layout B's vertices from the texture).
/// UV.x is the side (−0.5 / +0.5), UV.y the point index along the strand (layout B) or 0/1 along the
/// segment (layout A); TANGENT is +Y so the engine carries the segment direction into the shader.
/// </summary>
public sealed class StrandRibbonMesh
{
    private StrandRibbonMesh(float[] positions, float[] uvs, int[] indices)
    {
        Positions = positions; Uvs = uvs; Indices = indices;
    }

    /// <summary>xyz per vertex.</summary>
    public float[] Positions { get; }
    /// <summary>uv per vertex.</summary>
    public float[] Uvs { get; }
    /// <summary>Triangle list, counter-clockwise seen from +Z.</summary>
    public int[] Indices { get; }
    public int VertexCount => Positions.Length / 3;

    /// <summary>Layout A: a unit segment (0,0,0) → (0,1,0) as two crossed quads, width 1 along X and along Z.</summary>
    public static StrandRibbonMesh Segment()
    {
        float[] pos =
        [
            -0.5f, 0f, 0f,  0.5f, 0f, 0f,  -0.5f, 1f, 0f,  0.5f, 1f, 0f,
            0f, 0f, -0.5f,  0f, 0f, 0.5f,  0f, 1f, -0.5f,  0f, 1f, 0.5f,
        ];
        float[] uv = [0f, 0f, 1f, 0f, 0f, 1f, 1f, 1f, 0f, 0f, 1f, 0f, 0f, 1f, 1f, 1f];
        int[] idx = [0, 1, 2, 2, 1, 3, 4, 5, 6, 6, 5, 7];
        return new StrandRibbonMesh(pos, uv, idx);
    }

    /// <summary>Layout B: a ribbon of <paramref name="points"/> point pairs; vertex 2k+s is side s of point k.</summary>
    public static StrandRibbonMesh Strand(int points)
    {
        if (points < 2 || points > PositionTextureBuffer.MaxTextureWidth)
            throw new ArgumentOutOfRangeException(nameof(points), points, $"A strand ribbon needs 2 … {PositionTextureBuffer.MaxTextureWidth} points.");
        var pos = new float[points * 2 * 3];
        var uv = new float[points * 2 * 2];
        var idx = new int[(points - 1) * 6];
        for (int k = 0; k < points; k++)
            for (int s = 0; s < 2; s++)
            {
                int v = 2 * k + s;
                pos[v * 3] = s - 0.5f; pos[v * 3 + 1] = k; pos[v * 3 + 2] = 0f;
                uv[v * 2] = s - 0.5f; uv[v * 2 + 1] = k;
            }
        for (int k = 0; k + 1 < points; k++)
        {
            int a = 2 * k, o = k * 6;
            idx[o] = a; idx[o + 1] = a + 1; idx[o + 2] = a + 2;
            idx[o + 3] = a + 2; idx[o + 4] = a + 1; idx[o + 5] = a + 3;
        }
        return new StrandRibbonMesh(pos, uv, idx);
    }
}
