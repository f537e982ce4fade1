using System.Numerics;
using HairSim;
using HairSim.Editing;

namespace HairSim.Tests.Editing;

/// <summary>Small scenes with known geometry for editing tests.</summary>
internal static class EditScenes
{
    public const float Segment = 0.02f;

    /// <summary>
    /// A curtain of straight strands hanging down (−Y) from roots at y = 0, z = <paramref name="z"/>, x spread over
    /// [−0.05, 0.05]; each strand has <paramref name="particles"/> particles, <see cref="Segment"/> apart, root pinned.
    /// </summary>
    public static HairScene Curtain(int sheets = 2, int strandsPerSheet = 5, int particles = 11, float z = 0f, SimulationSettings? settings = null)
    {
        var w = new HairWorld(sheets, strandsPerSheet, particles);
        int n = sheets * strandsPerSheet;
        var pts = new Vector3[particles];
        for (int s = 0; s < n; s++)
        {
            float x = -0.05f + 0.1f * s / Math.Max(1, n - 1);
            for (int k = 0; k < particles; k++) pts[k] = new Vector3(x, -Segment * k, z);
            w.SetStrand(s, pts, pinned: 1, straightRestShape: true);
        }
        return new HairScene(w, settings);
    }

    /// <summary>Front orthographic camera: 1000 px per metre, screen centre at world (0, −0.1), looking along −Z.</summary>
    public static StrokeCamera Front() =>
        StrokeCamera.LookAtOrthographic(new Vector3(0, -0.1f, 1f), new Vector3(0, -0.1f, 0), Vector3.UnitY, 0.5f, new Vector2(500, 500));

    /// <summary>Screen y of world height y for <see cref="Front"/>.</summary>
    public static float ScreenY(float worldY) => 250f - (worldY + 0.1f) * 1000f;
    public static float ScreenX(float worldX) => 250f + worldX * 1000f;

    public static Stroke Horizontal(StrokeCamera cam, float worldY, float x0 = -0.1f, float x1 = 0.1f) =>
        new([new Vector2(ScreenX(x0), ScreenY(worldY)), new Vector2(ScreenX(x1), ScreenY(worldY))], cam);

    /// <summary>Are all buffers of strand s equal bit for bit in a and b (and its live count)?</summary>
    public static bool StrandBitEquals(HairWorld a, HairWorld b, int s)
    {
        if (a.StrandParticleCount[s] != b.StrandParticleCount[s]) return false;
        float[][] ba = a.Buffers(), bb = b.Buffers();
        int first = a.StrandFirst[s], cap = a.StrandCapacity[s];
        for (int k = 0; k < ba.Length; k++)
            for (int i = first; i < first + cap; i++)
                if (BitConverter.SingleToInt32Bits(ba[k][i]) != BitConverter.SingleToInt32Bits(bb[k][i])) return false;
        return true;
    }

    /// <summary>Distance in pixels from p to a screen polyline.</summary>
    public static float DistanceToPolyline(Vector2 p, ReadOnlySpan<Vector2> line)
    {
        float best = float.MaxValue;
        for (int k = 0; k + 1 < line.Length; k++)
        {
            var a = line[k]; var d = line[k + 1] - a;
            float t = Math.Clamp(Vector2.Dot(p - a, d) / d.LengthSquared(), 0f, 1f);
            best = MathF.Min(best, Vector2.Distance(p, a + t * d));
        }
        return best;
    }

    public static float StrandRestLength(HairWorld w, int s)
    {
        float sum = 0;
        for (int k = 1; k < w.StrandParticleCount[s]; k++) sum += w.RestLength[w.StrandFirst[s] + k];
        return sum;
    }
}
