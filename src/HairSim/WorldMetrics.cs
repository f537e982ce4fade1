using System.Numerics;

namespace HairSim;

/// <summary>Error figures of a scene's current state: stretch, penetration, non-finite values.</summary>
public readonly record struct WorldMetrics(
    double LengthRatio,
    double MaxEdgeStretch,
    double MaxPenetration,
    int ParticlesInside,
    int NonFinite)
{
    /// <summary>Measures against the scene's colliders (and its mesh colliders' distance fields) placed at the world's current head pose.</summary>
    public static WorldMetrics Measure(HairScene scene)
    {
        var w = scene.World;
        var colliders = new Collider[scene.Colliders.Count];
        for (int c = 0; c < colliders.Length; c++) colliders[c] = scene.Colliders[c].ToWorld(w.Head);
        var meshes = scene.MeshColliderArray;
        var meshPoses = Array.ConvertAll(meshes, m => m.PoseFor(w.Head));
        double length = 0, rest = 0, maxStretch = 0, maxPen = 0;
        int inside = 0;
        for (int s = 0; s < w.StrandCount; s++)
        {
            int first = w.StrandFirst[s], n = w.StrandParticleCount[s];
            for (int k = 0; k < n; k++)
            {
                int i = first + k;
                var p = w.GetPosition(i);
                if (k > 0)
                {
                    double l = Vector3.Distance(p, w.GetPosition(i - 1));
                    length += l;
                    rest += w.RestLength[i];
                    if (w.RestLength[i] > 0) maxStretch = Math.Max(maxStretch, Math.Abs(l / w.RestLength[i] - 1));
                }
                if (w.InvMass[i] == 0f) continue;
                for (int m = 0; m < meshes.Length; m++)
                {
                    float dm = -meshes[m].Field.Distance(meshPoses[m].InverseTransformPoint(p));
                    if (dm > 1e-6f + 5e-7f * p.Length()) { inside++; maxPen = Math.Max(maxPen, dm); }
                }
                foreach (var c in colliders)
                {
                    // "Inside" beyond float resolution at this distance from the origin (a few ulps).
                    float d = c.Penetration(p);
                    if (d > 1e-6f + 5e-7f * p.Length()) { inside++; maxPen = Math.Max(maxPen, d); }
                }
            }
        }
        return new WorldMetrics(rest > 0 ? length / rest : 1, maxStretch, maxPen, inside, w.CountNonFinite());
    }
}
