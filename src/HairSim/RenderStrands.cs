using System.Numerics;

namespace HairSim;

/// <summary>What to draw: how many interpolated strands between neighbouring simulated strands of a sheet.</summary>
public sealed class RenderSettings
{
    public const int MaxStrandsPerGap = 64;
    /// <summary>Interpolated render strands between two simulated strands of a sheet (0 = draw only simulated ones).</summary>
    public int StrandsPerGap { get; set; } = 1;

    public void Validate()
    {
        if (StrandsPerGap < 0 || StrandsPerGap > MaxStrandsPerGap)
            throw new ArgumentOutOfRangeException(nameof(StrandsPerGap), StrandsPerGap, $"Render strands per gap must be in 0 … {MaxStrandsPerGap}.");
    }

    /// <summary>Render strands a sheet of n simulated strands produces.</summary>
    public int RenderStrandsFor(int simulatedStrands) => simulatedStrands + (simulatedStrands - 1) * StrandsPerGap;
}

/// <summary>
/// Render polylines: strand r's points are Points[r·Stride … r·Stride + Counts[r]). Sheet q's render strands
/// start at SheetFirst[q]. Allocated once when the pipeline is built; the interpolation system refills it.
/// </summary>
public sealed class RenderStrands
{
    public RenderStrands(HairWorld world, RenderSettings settings)
    {
        settings.Validate();
        Stride = world.MaxStrandCapacity;
        SheetFirst = new int[world.SheetCount];
        int total = 0;
        for (int q = 0; q < world.SheetCount; q++)
        {
            SheetFirst[q] = total;
            total += settings.RenderStrandsFor(world.SheetStrandCount[q]);
        }
        long points = (long)total * Stride;
        if (points > HairWorld.MaxParticles * 8L)
            throw new ArgumentOutOfRangeException(nameof(settings), points, "Render density too high: too many render points.");
        StrandCount = total;
        StrandsPerGap = settings.StrandsPerGap;
        Points = new Vector3[points];
        Counts = new int[total];
    }

    public int Stride { get; }
    public int StrandCount { get; }
    public int StrandsPerGap { get; }
    public Vector3[] Points { get; }
    public int[] Counts { get; }
    public int[] SheetFirst { get; }
    /// <summary>Number of points across all render strands (sum of Counts), computed on demand.</summary>
    public int TotalPoints
    {
        get
        {
            int sum = 0;
            foreach (int c in Counts) sum += c;
            return sum;
        }
    }

    public ReadOnlySpan<Vector3> Strand(int r) => Points.AsSpan(r * Stride, Counts[r]);
}
