using System.Numerics;

namespace HairSim.IO;

/// <summary>Polylines to export: strand r is Points[Start(r) … Start(r) + Counts[r]).</summary>
public sealed class StrandCurves
{
    public StrandCurves(Vector3[] points, int[] counts)
    {
        ArgumentNullException.ThrowIfNull(points);
        ArgumentNullException.ThrowIfNull(counts);
        long sum = 0;
        foreach (int c in counts)
        {
            if (c < 2) throw new ArgumentException("Every exported strand needs at least 2 points.", nameof(counts));
            sum += c;
        }
        if (sum != points.Length) throw new ArgumentException($"Counts add up to {sum} points, {points.Length} were given.", nameof(points));
        Points = points; Counts = counts;
    }

    public Vector3[] Points { get; }
    public int[] Counts { get; }
    public int StrandCount => Counts.Length;

    /// <summary>The live particles of every simulated strand, world positions.</summary>
    public static StrandCurves FromWorld(HairWorld w)
    {
        var counts = new int[w.StrandCount];
        int total = 0;
        for (int s = 0; s < counts.Length; s++) total += counts[s] = w.StrandParticleCount[s];
        var pts = new Vector3[total];
        int o = 0;
        for (int s = 0; s < counts.Length; s++)
            for (int k = 0; k < counts[s]; k++) pts[o++] = w.GetPosition(w.StrandFirst[s] + k);
        return new StrandCurves(pts, counts);
    }

    /// <summary>The render strands (simulated plus interpolated) of the last simulated frame.</summary>
    public static StrandCurves FromRender(RenderStrands r)
    {
        ArgumentNullException.ThrowIfNull(r);
        var counts = new int[r.StrandCount];
        int total = 0;
        for (int s = 0; s < counts.Length; s++) total += counts[s] = r.Counts[s];
        var pts = new Vector3[total];
        int o = 0;
        for (int s = 0; s < counts.Length; s++) { r.Strand(s).CopyTo(pts.AsSpan(o)); o += counts[s]; }
        return new StrandCurves(pts, counts);
    }
}
