using System.Numerics;

namespace HairSim.Measurement;

/// <summary>
/// How much volume the hair keeps on the head: the outer layer's mean height above the scalp. Directions from the
/// head's centre (head space, upper half: the scalp) are binned by azimuth and elevation; in each bin the farthest
/// particle's height above the head ellipsoid is the outer layer there; the figure is the mean over occupied bins.
/// <c>minElevation</c> (radians above the head's equator) keeps to the crown, where gravity presses hair onto the head.
/// Hair that collapses into a thin shell (strands passing through one another) shows as a small figure.
/// </summary>
public static class HairVolume
{
    public static double OuterLayerThickness(HairWorld w, Vector3 headCenter, Vector3 headRadii, float minElevation = 0f, int azimuthBins = 24, int elevationBins = 8)
    {
        var outer = new double[azimuthBins * elevationBins];
        Array.Fill(outer, double.NaN);
        float meanRadius = (headRadii.X + headRadii.Y + headRadii.Z) / 3f;
        for (int s = 0; s < w.StrandCount; s++)
        {
            int first = w.StrandFirst[s], n = w.StrandParticleCount[s];
            for (int i = first; i < first + n; i++)
            {
                var u = (w.Head.InverseTransformPoint(w.GetPosition(i)) - headCenter) / headRadii;
                float r = u.Length();
                if (!(r > 1e-6f)) continue;
                var dir = u / r;
                if (dir.Y < MathF.Sin(minElevation)) continue;
                int a = Math.Clamp((int)((MathF.Atan2(dir.X, dir.Z) + MathF.PI) / (2 * MathF.PI) * azimuthBins), 0, azimuthBins - 1);
                int e = Math.Clamp((int)(MathF.Asin(Math.Clamp(dir.Y, 0f, 1f)) / (MathF.PI / 2) * elevationBins), 0, elevationBins - 1);
                double height = (r - 1f) * meanRadius;
                ref double o = ref outer[e * azimuthBins + a];
                if (double.IsNaN(o) || height > o) o = height;
            }
        }
        double sum = 0; int count = 0;
        foreach (double o in outer) if (!double.IsNaN(o)) { sum += o; count++; }
        return count > 0 ? sum / count : 0;
    }
}
