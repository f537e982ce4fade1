using System.Numerics;

namespace HairSim;

/// <summary>
/// Hair volume (<see cref="VolumeSettings"/>), once per pass before the substeps (a frame longer than
/// <see cref="VolumeSettings.MaxStep"/> is stepped in parts, and cut finer while the last pass found the push stiff:
/// <see cref="VolumeSettings.LongestPart"/>), reference implementation (scalar, double precision, one thread):
/// 1. fit a grid to the live particles (cells of <see cref="VolumeSettings.CellSize"/> mean segments);
/// 2. splat the free particles of every <see cref="VolumeSettings.SampleEvery"/>-th strand of a sheet (weight: the
///    strands each stands for) to their cell's eight nodes (trilinear): density ρ and momentum m;
/// 3. at each node, the over-density P = max(0, ρ / ρ₀ − 1) (ρ₀ a multiple of the rest pose's median density), its
///    gradient by central differences, and the change a particle there takes: Δv = D − S·v, with D the push
///    −Stiffness·1 g·∇P·dt (at most half a cell per pass) plus S·m/ρ, and S = 1 − e^(−Friction·dt/T₀), T₀ = √(L / 1 g);
///    and the largest curvature of P over the nodes with hair, which sets how long the next part may be;
/// 4. D and S interpolated at the sample strands' particles, and every strand takes the changes of the two samples
///    around it, blended by its place in the sheet.
/// The substeps that follow carry the changed velocities through the strand constraints. Skipped on teleport frames.
/// </summary>
public sealed class VolumeSystem : IHairSystem, IFrameSplitter
{
    public const string SystemName = "Volume";
    public string Name => SystemName;
    public SystemPhase Phase => SystemPhase.FrameStart;

    /// <summary>Frames longer than <see cref="VolumeSettings.MaxStep"/> natural times are stepped in parts (none without the component: a kept pipeline changes nothing).</summary>
    public int PartsOf(HairScene scene, float dt, GroomScale scale) => scene.GetComponent<VolumeSettings>()?.PartsOf(dt, scale) ?? 1;

    /// <summary>Shorter parts while the last pass found the push stiff (<see cref="VolumeSettings.LongestPart"/>).</summary>
    public double LongestPart(HairScene scene, GroomScale scale) =>
        scene.GetComponent<VolumeSettings>()?.LongestPart(_curvature, _cell, scale) ?? double.PositiveInfinity;

    // The largest over-density curvature (second difference of P along an axis, per cell²) at a node holding hair in the
    // last pass, and the cell it was measured on.
    private double _curvature, _cell;

    /// <summary>What a pipeline that keeps every system runs when the scene has no volume: all the work, no change.</summary>
    internal static readonly VolumeSettings InertSettings = VolumeSettings.Inert;

    private readonly VolumeGrid _grid = new();
    private readonly VolumeRestCache _rest = new();
    private double[] _rho = [], _mx = [], _my = [], _mz = [], _p = [], _dx = [], _dy = [], _dz = [], _s = [];

    /// <summary>Below this density (weighted particles per node) a node has no hair to take a mean velocity from.</summary>
    internal const float MinDensity = 1e-6f;

    public VolumeGrid Grid => _grid;

    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var settings = scene.GetComponent<VolumeSettings>() ?? InertSettings;
        settings.Validate();
        if (ctx.Teleported) return;
        var w = scene.World;
        float cell = settings.CellSize * ctx.Scale.Segment;
        _rest.Update(w, cell);
        float rest = _rest.Density;
        if (!(rest > 0f)) return;
        if (!FitToSamples(w, _grid, cell, settings.SampleEvery)) return;
        int n = _grid.NodeCount;
        if (_rho.Length < n)
        {
            _rho = new double[n]; _mx = new double[n]; _my = new double[n]; _mz = new double[n];
            _p = new double[n]; _dx = new double[n]; _dy = new double[n]; _dz = new double[n]; _s = new double[n];
        }
        Array.Clear(_rho, 0, n); Array.Clear(_mx, 0, n); Array.Clear(_my, 0, n); Array.Clear(_mz, 0, n);
        int sy = _grid.Nx, sz = _grid.Nx * _grid.Ny;

        for (int q = 0; q < w.SheetCount; q++)
        {
            int first = w.SheetFirstStrand[q], count = w.SheetStrandCount[q], every = settings.SampleEvery;
            double weight = VolumeSampling.Weight(count, every);
            for (int j = 0; j < count; j++)
            {
                if (!VolumeSampling.IsSample(j, count, every)) continue;
                int s = first + j;
                for (int i = w.StrandFirst[s], e = i + w.StrandParticleCount[s]; i < e; i++)
                {
                    int b = _grid.Locate(w.PosX[i], w.PosY[i], w.PosZ[i], out float fx, out float fy, out float fz);
                    var v = ParticleVelocity(w, i, ctx);
                    if (b < 0 || !float.IsFinite(v.X + v.Y + v.Z)) continue;
                    for (int c = 0; c < 8; c++)
                    {
                        int node = b + (c & 1) + ((c & 2) != 0 ? sy : 0) + ((c & 4) != 0 ? sz : 0);
                        double wt = weight * VolumeGrid.Weight(c, fx, fy, fz);
                        _rho[node] += wt; _mx[node] += wt * v.X; _my[node] += wt * v.Y; _mz[node] += wt * v.Z;
                    }
                }
            }
        }

        double invTarget = 1.0 / (settings.Density * (double)rest);
        for (int k = 0; k < n; k++) _p[k] = Math.Max(0.0, _rho[k] * invTarget - 1.0);
        double dt = ctx.Dt;
        double push = settings.Stiffness * BendProfile.StandardGravity * dt;
        double maxPush = VolumeSettings.MaxPushPerPass * _grid.Cell / dt;
        double f = 1.0 - Math.Exp(-settings.Friction * dt / ctx.Scale.NaturalTime);
        // At each node, the change a particle there takes: Δv = D − S·v, with D = push + S·(mean velocity), S the friction share.
        double curvature = 0;
        for (int z = 0; z < _grid.Nz; z++)
            for (int y = 0; y < _grid.Ny; y++)
                for (int x = 0; x < _grid.Nx; x++)
                {
                    int k = x + sy * y + sz * z;
                    var d = new Vec3d(-push * 0.5 * (P(x + 1, y, z) - P(x - 1, y, z)), -push * 0.5 * (P(x, y + 1, z) - P(x, y - 1, z)),
                        -push * 0.5 * (P(x, y, z + 1) - P(x, y, z - 1)));
                    if (d.Length > maxPush) d *= maxPush / d.Length;
                    double share = 0;
                    if (_rho[k] > MinDensity)
                    {
                        share = f; d += f / _rho[k] * new Vec3d(_mx[k], _my[k], _mz[k]);
                        double p2 = 2 * _p[k];
                        curvature = Math.Max(curvature, Math.Max(Math.Abs(P(x + 1, y, z) - p2 + P(x - 1, y, z)),
                            Math.Max(Math.Abs(P(x, y + 1, z) - p2 + P(x, y - 1, z)), Math.Abs(P(x, y, z + 1) - p2 + P(x, y, z - 1)))));
                    }
                    _dx[k] = d.X; _dy[k] = d.Y; _dz[k] = d.Z; _s[k] = share;
                }
        _curvature = curvature; _cell = _grid.Cell;

        bool inert = settings.IsInert;
        for (int q = 0; q < w.SheetCount; q++)
        {
            int first = w.SheetFirstStrand[q], count = w.SheetStrandCount[q], every = settings.SampleEvery;
            for (int j = 0; j < count; j++)
            {
                var (a, b, t) = VolumeSampling.Bracket(j, count, every);
                int s = first + j, sa = first + a, sb = first + b;
                for (int k = 0; k < w.StrandParticleCount[s]; k++)
                {
                    int i = w.StrandFirst[s] + k;
                    if (w.InvMass[i] == 0f || !float.IsFinite(w.VelX[i] + w.VelY[i] + w.VelZ[i])) continue;
                    // Each sample gives a push and (where it found hair) a friction pull f·(target − v); a sample with
                    // nothing to give (a pinned or broken particle) gives zero, so strands near it are pushed less.
                    Evaluate(w, sa, k, out var dA, out double sA);
                    Evaluate(w, sb, k, out var dB, out double sB);
                    var v = new Vec3d(w.VelX[i], w.VelY[i], w.VelZ[i]);
                    var dv = (1.0 - t) * (dA - sA * v) + t * (dB - sB * v);
                    if (inert) continue;
                    w.VelX[i] = (float)(w.VelX[i] + dv.X); w.VelY[i] = (float)(w.VelY[i] + dv.Y); w.VelZ[i] = (float)(w.VelZ[i] + dv.Z);
                }
            }
        }

        // D and S at particle k of sample strand s (its last particle if s is shorter); zeros where there is no free,
        // finite particle to sample.
        void Evaluate(HairWorld w, int s, int k, out Vec3d d, out double share)
        {
            d = default; share = 0;
            int n = w.StrandParticleCount[s];
            int i = w.StrandFirst[s] + Math.Min(k, n - 1);
            if (w.InvMass[i] == 0f || !float.IsFinite(w.VelX[i] + w.VelY[i] + w.VelZ[i])) return;
            int b = _grid.Locate(w.PosX[i], w.PosY[i], w.PosZ[i], out float fx, out float fy, out float fz);
            if (b < 0) return;
            for (int c = 0; c < 8; c++)
            {
                int node = b + (c & 1) + ((c & 2) != 0 ? sy : 0) + ((c & 4) != 0 ? sz : 0);
                double wt = VolumeGrid.Weight(c, fx, fy, fz);
                d += wt * new Vec3d(_dx[node], _dy[node], _dz[node]);
                share += wt * _s[node];
            }
        }

        double P(int x, int y, int z) =>
            (uint)x < (uint)_grid.Nx && (uint)y < (uint)_grid.Ny && (uint)z < (uint)_grid.Nz ? _p[x + sy * y + sz * z] : 0.0;
    }

    /// <summary>
    /// A particle's velocity for the grid: a free particle's own; a pinned root's is the head's motion there over this
    /// frame (its buffer reads zero): roots are hair too, they take up room and move with the head.
    /// </summary>
    internal static Vector3 ParticleVelocity(HairWorld w, int i, FrameContext ctx)
    {
        if (w.InvMass[i] != 0f) return new Vector3(w.VelX[i], w.VelY[i], w.VelZ[i]);
        var end = ctx.HeadEnd.TransformPoint(new Vector3(w.RestX[i], w.RestY[i], w.RestZ[i]));
        return (end - new Vector3(w.PosX[i], w.PosY[i], w.PosZ[i])) / ctx.Dt;
    }

    /// <summary>
    /// Fits the grid to the bounds of the sample strands' live particles (pinned roots included: they lie inside the hair
    /// anyway): only the samples are ever splatted or sampled.
    /// </summary>
    internal static bool FitToSamples(HairWorld w, VolumeGrid grid, float cell, int every)
    {
        var min = new Vector3(float.MaxValue); var max = new Vector3(float.MinValue);
        for (int q = 0; q < w.SheetCount; q++)
            for (int j = 0, first = w.SheetFirstStrand[q], count = w.SheetStrandCount[q]; j < count; j++)
            {
                if (!VolumeSampling.IsSample(j, count, every)) continue;
                int s = first + j;
                for (int i = w.StrandFirst[s], e = i + w.StrandParticleCount[s]; i < e; i++)
                {
                    var p = new Vector3(w.PosX[i], w.PosY[i], w.PosZ[i]);
                    if (!float.IsFinite(p.X + p.Y + p.Z)) continue;
                    min = Vector3.Min(min, p); max = Vector3.Max(max, p);
                }
            }
        return grid.Fit(min, max, cell);
    }
}

/// <summary>Which strands of a sheet fill the grid (<see cref="VolumeSettings.SampleEvery"/>), and how the others take their pushes.</summary>
public static class VolumeSampling
{
    /// <summary>Strand j of a sheet of n is a sample: every <paramref name="every"/>-th, and the last.</summary>
    public static bool IsSample(int j, int n, int every) => j % every == 0 || j == n - 1;

    /// <summary>The sample after sample j of a sheet of n (n after the last): stepping with it visits exactly the strands <see cref="IsSample"/> names, without a division per strand.</summary>
    public static int Next(int j, int n, int every) => j >= n - 1 ? n : Math.Min(j + every, n - 1);

    /// <summary>How many strands each sample of a sheet of n stands for (n over the number of samples).</summary>
    public static double Weight(int n, int every)
    {
        int samples = (n - 1) / every + 1 + ((n - 1) % every != 0 ? 1 : 0);
        return (double)n / samples;
    }

    /// <summary>The samples around strand j (A ≤ j ≤ B) and j's place between them (0 at A, 1 at B).</summary>
    public static (int A, int B, double T) Bracket(int j, int n, int every)
    {
        int a = j / every * every;
        if (a == j) return (a, a, 0.0);
        int b = Math.Min(a + every, n - 1);
        return (a, b, (double)(j - a) / (b - a));
    }
}

/// <summary>A double-precision vector for the reference path.</summary>
internal readonly record struct Vec3d(double X, double Y, double Z)
{
    public double Length => Math.Sqrt(X * X + Y * Y + Z * Z);
    public static Vec3d operator +(Vec3d a, Vec3d b) => new(a.X + b.X, a.Y + b.Y, a.Z + b.Z);
    public static Vec3d operator -(Vec3d a, Vec3d b) => new(a.X - b.X, a.Y - b.Y, a.Z - b.Z);
    public static Vec3d operator *(double k, Vec3d a) => new(k * a.X, k * a.Y, k * a.Z);
    public static Vec3d operator *(Vec3d a, double k) => new(k * a.X, k * a.Y, k * a.Z);
}

/// <summary>
/// The rest pose's density (<see cref="VolumeGrid.RestDensity"/>), recomputed only after an edit or a change of cell size.
/// </summary>
internal sealed class VolumeRestCache
{
    private HairWorld? _world;
    private int _stamp;
    private float _cell;

    public float Density { get; private set; }

    public void Update(HairWorld w, float cell)
    {
        if (ReferenceEquals(w, _world) && w.EditStamp == _stamp && cell == _cell) return;
        Density = VolumeGrid.RestDensity(w, cell);
        _world = w; _stamp = w.EditStamp; _cell = cell;
    }
}
