using System.Numerics;

namespace HairSim.Tests.Core;

/// <summary>Small hand-made worlds for core tests.</summary>
internal static class TestWorlds
{
    /// <summary>One strand of n particles laid along a direction from a root, edges of length l0, root pinned.</summary>
    public static HairWorld Strand(int n, float l0, Vector3 root, Vector3 direction, int pinned = 1)
    {
        var w = new HairWorld(1, 1, n);
        var pts = new Vector3[n];
        var d = Vector3.Normalize(direction);
        for (int k = 0; k < n; k++) pts[k] = root + d * (l0 * k);
        w.SetStrand(0, pts, pinned, straightRestShape: true);
        return w;
    }

    /// <summary>
    /// Reference-path settings for the core systems' tests, on the source's scheme (triple shape matching, follow-the-
    /// leader): the tests of the default bend model (BendModel.RestShape) build their own settings.
    /// </summary>
    public static SimulationSettings Settings(Action<SimulationSettings>? change = null)
    {
        var s = new SimulationSettings { Path = SolverPath.Reference, Bend = BendModel.SourceTriples };
        change?.Invoke(s);
        return s;
    }

    public static GroomSettings SmallGroom() => new()
    {
        SheetCount = 12, StrandsPerSheet = 5, ParticlesPerStrand = 10, StrandLength = 0.2f,
    };

    public static void SetPositions(HairWorld w, int strand, params Vector3[] pts)
    {
        for (int k = 0; k < pts.Length; k++) w.SetPosition(w.StrandFirst[strand] + k, pts[k]);
    }
}
