using System.Numerics;

namespace HairSim;

/// <summary>
/// Render strands between a sheet's simulated strands, along the Catmull-Rom curves through the particles
/// with the same index (SPEC A.1). Interpolated strands take the length between their neighbours', so
/// they follow a cut. This is the reference (double precision inside, like every reference system);
/// <see cref="Fast.FastInterpolateSystem"/> is the fast path's twin.
/// </summary>
public sealed class InterpolateSystem : IHairSystem
{
    public const string SystemName = "Interpolate";
    public string Name => SystemName;
    public SystemPhase Phase => SystemPhase.FrameEnd;

    private readonly RenderStrands _out;

    public InterpolateSystem(HairScene scene)
    {
        _out = new RenderStrands(scene.World, scene.Render!);
        scene.RenderOutput = _out;
    }

    public RenderStrands Output => _out;

    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var w = scene.World;
        int g = _out.StrandsPerGap, stride = _out.Stride;
        var pts = _out.Points;
        for (int q = begin; q < end; q++)
        {
            int s0 = w.SheetFirstStrand[q], ns = w.SheetStrandCount[q];
            int r = _out.SheetFirst[q];
            for (int j = 0; j < ns; j++)
            {
                // The simulated strand itself.
                int sj = s0 + j, nj = w.StrandParticleCount[sj];
                for (int k = 0; k < nj; k++) pts[r * stride + k] = w.GetPosition(w.StrandFirst[sj] + k);
                _out.Counts[r++] = nj;
                if (j == ns - 1) break;
                int sn = sj + 1, nn = w.StrandParticleCount[sn];
                for (int m = 1; m <= g; m++)
                {
                    float t = m / (float)(g + 1);
                    int count = (int)MathF.Round(nj + (nn - nj) * t, MidpointRounding.AwayFromZero);
                    for (int k = 0; k < count; k++)
                    {
                        var p1 = At(w, sj, k); var p2 = At(w, sn, k);
                        var p0 = j > 0 ? At(w, sj - 1, k) : CatmullRom.Mirror(p1, p2);
                        var p3 = j + 2 < ns ? At(w, sn + 1, k) : CatmullRom.Mirror(p2, p1);
                        pts[r * stride + k] = CatmullRom.Evaluate(p0, p1, p2, p3, t);
                    }
                    _out.Counts[r++] = count;
                }
            }
        }
    }

    /// <summary>Particle k of strand s, clamped to its live tip.</summary>
    internal static Vector3 At(HairWorld w, int s, int k) => w.GetPosition(w.StrandFirst[s] + Math.Min(k, w.StrandParticleCount[s] - 1));
}
