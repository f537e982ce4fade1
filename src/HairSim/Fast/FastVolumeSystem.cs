using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.Intrinsics;
using System.Runtime.Intrinsics.X86;

namespace HairSim.Fast;

/// <summary>
/// Hair volume, fast path: the reference <see cref="VolumeSystem"/>'s steps in single precision, in parallel passes
/// (bounds, splat, reduce, node changes, sample and spread), with node data packed so a corner is one 128-bit load.
/// The splat writes into <see cref="Partitions"/> private grids, a fixed number so the sums (and so the results) do not
/// depend on how many threads run; the reduce pass adds them in order and clears them for the next frame. The node pass
/// also finds the largest over-density curvature (a max: the same on any thread count) for the next part's length.
/// </summary>
internal sealed class FastVolumeSystem : IHairSystem, IFrameSplitter
{
    public string Name => VolumeSystem.SystemName;
    public SystemPhase Phase => SystemPhase.FrameStart;

    /// <summary>Frames longer than <see cref="VolumeSettings.MaxStep"/> natural times are stepped in parts (none without the component: a kept pipeline changes nothing).</summary>
    public int PartsOf(HairScene scene, float dt, GroomScale scale) => scene.GetComponent<VolumeSettings>()?.PartsOf(dt, scale) ?? 1;

    /// <summary>Shorter parts while the last pass found the push stiff (<see cref="VolumeSettings.LongestPart"/>).</summary>
    public double LongestPart(HairScene scene, GroomScale scale) =>
        scene.GetComponent<VolumeSettings>()?.LongestPart(_curvature, _cell, scale) ?? double.PositiveInfinity;

    /// <summary>Private splat grids (and splat jobs): fixed, so the bits do not depend on the thread count.</summary>
    public const int Partitions = 4;
    private const int MaxJobs = 1024;
    /// <summary>Grids of fewer nodes are reduced and turned into changes on the stepping thread, without a fork.</summary>
    private const int InlineNodes = 1 << 15;
    /// <summary>Worlds of fewer particles find their sample strands' bounds on the stepping thread, without a fork.</summary>
    private const int InlineBoundsParticles = 1 << 20;

    private readonly VolumeGrid _grid = new();
    private readonly VolumeRestCache _rest = new();
    // (ρ, mx, my, mz) per node; every partition is all zeros between frames (the reduce pass clears what it read).
    private readonly Vector128<float>[][] _splat = new Vector128<float>[Partitions][];
    private float[] _p = [];
    // (ρ, mx, my, mz) summed over the partitions, per node.
    private Vector128<float>[] _sum = [];
    // The velocity change a particle at a node takes, as (D, S): Δv = D − S·v, with D = push + S·(mean velocity) and
    // S the friction share (0 where there is no hair).
    private Vector128<float>[] _change = [];
    private readonly Vector3[] _min = new Vector3[MaxJobs], _max = new Vector3[MaxJobs];
    // The largest over-density curvature each node job found (max: the same whatever the thread count), and over all
    // of them with the cell it was measured on, for the next part's length.
    private readonly float[] _jobCurvature = new float[MaxJobs];
    private float _curvature, _cell;
    // Per particle of the sample strands, packed sample after sample (sample strand s from _sampleAt[s]): D and S
    // interpolated there (zeros where nothing was sampled), so a particle's change is Σ t·(D − S·v) over its two samples.
    // Packed, only the samples' entries take room in the cache, side by side, not spread over particle-indexed arrays.
    private float[] _pushX = [], _pushY = [], _pushZ = [], _share = [];
    private int[] _sampleAt = [];
    private int _every;
    private readonly Action<int> _boundsJob, _splatJob, _reduceJob, _gradientJob, _gatherJob;

    // The frame being run (set before the passes fork).
    private HairWorld _w = null!;
    private FrameContext _ctx = null!;
    private int _nodeJobs, _sheetJobs, _boundsJobs;
    private float _invTarget, _push, _maxPush, _friction;
    private bool _inert;

    public FastVolumeSystem()
    {
        for (int p = 0; p < Partitions; p++) _splat[p] = [];
        _boundsJob = BoundsJob; _splatJob = SplatJob; _reduceJob = ReduceJob; _gradientJob = GradientJob; _gatherJob = GatherJob;
    }

    public VolumeGrid Grid => _grid;

    /// <summary>
    /// Splat and sample eight particles at a time (where AVX2 is there); false takes them one by one, with the same bits
    /// (for tests).
    /// </summary>
    internal bool Lanes { get; set; } = Avx2.IsSupported;

    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var settings = scene.GetComponent<VolumeSettings>() ?? VolumeSystem.InertSettings;
        settings.Validate();
        if (ctx.Teleported) return;
        var w = scene.World;
        if (w.StrandCount == 0) return;
        float cell = settings.CellSize * ctx.Scale.Segment;
        _rest.Update(w, cell);
        float rest = _rest.Density;
        if (!(rest > 0f)) return;
        var dispatcher = ctx.Dispatcher;
        _w = w;
        _ctx = ctx;

        _every = settings.SampleEvery;
        // Four sample-and-spread jobs per thread, so a thread that starts late (or is held up by another process) leaves
        // its share to the others (each sheet is computed alone: the same bits whatever the job count).
        _sheetJobs = Math.Min(Math.Min(MaxJobs, w.SheetCount), dispatcher.ThreadCount == 1 ? 1 : 4 * dispatcher.ThreadCount);
        // The bounds of a head of hair's sample strands take less than a fork costs: on this thread unless the groom is huge.
        _boundsJobs = w.ParticleCount < InlineBoundsParticles ? 1 : _sheetJobs;
        if (_boundsJobs == 1) BoundsJob(0); else dispatcher.Run(_boundsJobs, _boundsJob);
        var min = _min[0]; var max = _max[0];
        for (int j = 1; j < _boundsJobs; j++) { min = Vector3.Min(min, _min[j]); max = Vector3.Max(max, _max[j]); }
        if (!_grid.Fit(min, max, cell)) return;

        int n = _grid.NodeCount;
        if (_p.Length < n)
        {
            // Room to grow: hair that spreads a little after warm-up does not make a step allocate.
            int capacity = Math.Min(VolumeGrid.MaxNodes, n + n / 2);
            for (int p = 0; p < Partitions; p++) _splat[p] = new Vector128<float>[capacity];
            _p = new float[capacity];
            _sum = new Vector128<float>[capacity];
            _change = new Vector128<float>[capacity];
        }
        // A grid of a head of hair holds some thousands of nodes: the node passes are cheaper than a fork, so they run
        // on this thread unless the grid is large (the same bits either way: every node is computed alone).
        _nodeJobs = n < InlineNodes ? 1 : Math.Min(_grid.Nz, dispatcher.ThreadCount);
        _invTarget = (float)(1.0 / (settings.Density * (double)rest));
        double dt = ctx.Dt;
        _push = (float)(settings.Stiffness * BendProfile.StandardGravity * dt);
        _maxPush = (float)(VolumeSettings.MaxPushPerPass * _grid.Cell / dt);
        _friction = (float)(1.0 - Math.Exp(-settings.Friction * dt / ctx.Scale.NaturalTime));
        _inert = settings.IsInert;
        int packed = PackSamples(w);
        if (_share.Length < packed)
        {
            // Room to grow, as for the grid (an edit rarely lengthens the samples).
            int np = packed + packed / 4;
            _pushX = new float[np]; _pushY = new float[np]; _pushZ = new float[np]; _share = new float[np];
        }

        dispatcher.Run(Partitions, _splatJob);
        if (_nodeJobs == 1) { ReduceJob(0); GradientJob(0); }
        else
        {
            dispatcher.Run(_nodeJobs, _reduceJob);
            dispatcher.Run(_nodeJobs, _gradientJob);
        }
        float curvature = 0f;
        for (int j = 0; j < _nodeJobs; j++) curvature = MathF.Max(curvature, _jobCurvature[j]);
        _curvature = curvature; _cell = _grid.Cell;
        dispatcher.Run(_sheetJobs, _gatherJob);
    }

    /// <summary>Where each sample strand's particles start in the packed buffers; how many particles the samples hold.</summary>
    private int PackSamples(HairWorld w)
    {
        if (_sampleAt.Length != w.StrandCount) _sampleAt = new int[w.StrandCount];
        int at = 0;
        for (int q = 0; q < w.SheetCount; q++)
            for (int j = 0, first = w.SheetFirstStrand[q], count = w.SheetStrandCount[q]; j < count; j = VolumeSampling.Next(j, count, _every))
            {
                _sampleAt[first + j] = at;
                at += w.StrandParticleCount[first + j];
            }
        return at;
    }

    private (int Begin, int End) Sheets(int job, int jobs)
    {
        long n = _w.SheetCount;
        return ((int)(n * job / jobs), (int)(n * (job + 1) / jobs));
    }

    // Only the sample strands are ever splatted or sampled, so the grid needs to hold only them.
    private void BoundsJob(int job)
    {
        var w = _w;
        var (sheetBegin, sheetEnd) = Sheets(job, _boundsJobs);
        var inf = Vector256.Create(float.PositiveInfinity);
        Vector256<float> minX = inf, minY = inf, minZ = inf, maxX = -inf, maxY = -inf, maxZ = -inf;
        var min = new Vector3(float.PositiveInfinity); var max = new Vector3(float.NegativeInfinity);
        ref float px = ref w.PosX[0], py = ref w.PosY[0], pz = ref w.PosZ[0];
        for (int q = sheetBegin; q < sheetEnd; q++)
        for (int j = 0, first = w.SheetFirstStrand[q], count = w.SheetStrandCount[q]; j < count; j = VolumeSampling.Next(j, count, _every))
        {
            int s = first + j;
            int i = w.StrandFirst[s], e = i + w.StrandParticleCount[s];
            for (; i + 8 <= e; i += 8)
            {
                var x = Vector256.LoadUnsafe(ref px, (nuint)i); var y = Vector256.LoadUnsafe(ref py, (nuint)i); var z = Vector256.LoadUnsafe(ref pz, (nuint)i);
                minX = Vector256.Min(minX, x); minY = Vector256.Min(minY, y); minZ = Vector256.Min(minZ, z);
                maxX = Vector256.Max(maxX, x); maxY = Vector256.Max(maxY, y); maxZ = Vector256.Max(maxZ, z);
            }
            for (; i < e; i++)
            {
                var p = new Vector3(w.PosX[i], w.PosY[i], w.PosZ[i]);
                min = Vector3.Min(min, p); max = Vector3.Max(max, p);
            }
        }
        for (int l = 0; l < 8; l++)
        {
            min = Vector3.Min(min, new Vector3(minX.GetElement(l), minY.GetElement(l), minZ.GetElement(l)));
            max = Vector3.Max(max, new Vector3(maxX.GetElement(l), maxY.GetElement(l), maxZ.GetElement(l)));
        }
        _min[job] = min; _max[job] = max;
    }

    [SkipLocalsInit]
    private unsafe void SplatJob(int partition)
    {
        var w = _w;
        var (sheetBegin, sheetEnd) = Sheets(partition, Partitions);
        var g = _grid;
        var lanes = new CellLanes(g);
        int sy = g.Nx, sz = g.Nx * g.Ny;
        ref var nodes = ref _splat[partition][0];
        float[] posX = w.PosX, posY = w.PosY, posZ = w.PosZ, velX = w.VelX, velY = w.VelY, velZ = w.VelZ, invMass = w.InvMass;
        int[] strandFirst = w.StrandFirst, strandCount = w.StrandParticleCount;
        int* cell = stackalloc int[CellLanes.Lanes];
        float* corner = stackalloc float[8 * CellLanes.Lanes];
        float* momentum = stackalloc float[3 * CellLanes.Lanes];
        bool lanesOn = Lanes;
        for (int q = sheetBegin; q < sheetEnd; q++)
        {
            int first = w.SheetFirstStrand[q], count = w.SheetStrandCount[q];
            float weight = (float)VolumeSampling.Weight(count, _every);
            for (int j = 0; j < count; j = VolumeSampling.Next(j, count, _every))
            {
                int s = first + j;
                int i = strandFirst[s], e = i + strandCount[s];
                if ((uint)e > (uint)posX.Length || (uint)e > (uint)velX.Length || (uint)e > (uint)invMass.Length
                    || (uint)e > (uint)posY.Length || (uint)e > (uint)posZ.Length || (uint)e > (uint)velY.Length || (uint)e > (uint)velZ.Length || i < 0)
                    throw new InvalidOperationException("Strand outside the particle arrays.");
                FetchAhead(w, s + 2 * _every, roots: true);
                // Eight particles at a time: their cells and weights side by side, then each lane's adds (the same bits
                // as one particle at a time, which the strand's last few take).
                for (; lanesOn && i + CellLanes.Lanes <= e; i += CellLanes.Lanes)
                {
                    var px = Load(posX, i); var py = Load(posY, i); var pz = Load(posZ, i);
                    var vx = Load(velX, i); var vy = Load(velY, i); var vz = Load(velZ, i);
                    if (Vector256.EqualsAny(Load(invMass, i), Vector256<float>.Zero))
                    {
                        // A pinned root takes up room and moves with the head (its velocity buffer reads zero).
                        vx.Store(momentum); vy.Store(momentum + 8); vz.Store(momentum + 16);
                        for (int l = 0; l < CellLanes.Lanes; l++)
                        {
                            if (invMass[i + l] != 0f) continue;
                            var v = VolumeSystem.ParticleVelocity(w, i + l, _ctx);
                            momentum[l] = v.X; momentum[8 + l] = v.Y; momentum[16 + l] = v.Z;
                        }
                        vx = Vector256.Load(momentum); vy = Vector256.Load(momentum + 8); vz = Vector256.Load(momentum + 16);
                    }
                    uint live = CellLanes.Finite(px + py + pz + vx + vy + vz);
                    if (live == 0) continue;
                    lanes.Cells(px, py, pz, cell, corner);
                    var vw = Vector256.Create(weight);
                    (vw * vx).Store(momentum); (vw * vy).Store(momentum + 8); (vw * vz).Store(momentum + 16);
                    for (int l = 0; l < CellLanes.Lanes; l++)
                    {
                        if ((live & (1u << l)) == 0) continue;
                        var value = Vector128.Create(weight, momentum[l], momentum[8 + l], momentum[16 + l]);
                        ref var n0 = ref Unsafe.Add(ref nodes, cell[l]);
                        Add(ref n0, value, corner[l]); Add(ref Unsafe.Add(ref n0, 1), value, corner[8 + l]);
                        ref var n1 = ref Unsafe.Add(ref n0, sy);
                        Add(ref n1, value, corner[16 + l]); Add(ref Unsafe.Add(ref n1, 1), value, corner[24 + l]);
                        ref var n2 = ref Unsafe.Add(ref n0, sz);
                        Add(ref n2, value, corner[32 + l]); Add(ref Unsafe.Add(ref n2, 1), value, corner[40 + l]);
                        ref var n3 = ref Unsafe.Add(ref n2, sy);
                        Add(ref n3, value, corner[48 + l]); Add(ref Unsafe.Add(ref n3, 1), value, corner[56 + l]);
                    }
                }
                for (; i < e; i++) SplatOne(ref nodes, i, weight, sy, sz);
            }
        }
    }

    private void SplatOne(ref Vector128<float> nodes, int i, float weight, int sy, int sz)
    {
        var w = _w;
        var g = _grid;
        float px = w.PosX[i], py = w.PosY[i], pz = w.PosZ[i];
        float vx = w.VelX[i], vy = w.VelY[i], vz = w.VelZ[i];
        if (w.InvMass[i] == 0f)
        {
            var v = VolumeSystem.ParticleVelocity(w, i, _ctx);
            vx = v.X; vy = v.Y; vz = v.Z;
        }
        if (!float.IsFinite(px + py + pz + vx + vy + vz)) return;
        int b = Cell(px, py, pz, g.Origin, g.InvCell, g.Nx - 1.001f, g.Ny - 1.001f, g.Nz - 1.001f, sy, sz, out float fx, out float fy, out float fz);
        var value = Vector128.Create(weight, weight * vx, weight * vy, weight * vz);
        float gx = 1f - fx, gy = 1f - fy, gz = 1f - fz;
        float w00 = gy * gz, w10 = fy * gz, w01 = gy * fz, w11 = fy * fz;
        ref var n0 = ref Unsafe.Add(ref nodes, b);
        Add(ref n0, value, gx * w00); Add(ref Unsafe.Add(ref n0, 1), value, fx * w00);
        ref var n1 = ref Unsafe.Add(ref n0, sy);
        Add(ref n1, value, gx * w10); Add(ref Unsafe.Add(ref n1, 1), value, fx * w10);
        ref var n2 = ref Unsafe.Add(ref n0, sz);
        Add(ref n2, value, gx * w01); Add(ref Unsafe.Add(ref n2, 1), value, fx * w01);
        ref var n3 = ref Unsafe.Add(ref n2, sy);
        Add(ref n3, value, gx * w11); Add(ref Unsafe.Add(ref n3, 1), value, fx * w11);
    }

    /// <summary>
    /// Starts fetching the lines of strand s's positions, velocities and masses: the sample strands lie a few strands
    /// apart, a stride the hardware's prefetchers do not follow across seven arrays, so every strand waited on memory.
    /// With <paramref name="roots"/>, the rest position of its root as well (a pinned root's velocity comes from it).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void FetchAhead(HairWorld w, int s, bool roots)
    {
        if ((uint)s >= (uint)w.StrandCount) return;
        int a = w.StrandFirst[s], b = a + w.StrandParticleCount[s] - 1;
        Prefetcher.Particle(w.PosX, a, b); Prefetcher.Particle(w.PosY, a, b); Prefetcher.Particle(w.PosZ, a, b);
        Prefetcher.Particle(w.VelX, a, b); Prefetcher.Particle(w.VelY, a, b); Prefetcher.Particle(w.VelZ, a, b);
        Prefetcher.Particle(w.InvMass, a, b);
        if (!roots) return;
        Prefetcher.First(w.RestX, a); Prefetcher.First(w.RestY, a); Prefetcher.First(w.RestZ, a);
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Add(ref Vector128<float> node, Vector128<float> value, float weight) => node += value * weight;

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static int Cell(float px, float py, float pz, Vector3 origin, float inv, float hx, float hy, float hz, int sy, int sz,
        out float fx, out float fy, out float fz)
    {
        float ux = Clamp((px - origin.X) * inv, hx), uy = Clamp((py - origin.Y) * inv, hy), uz = Clamp((pz - origin.Z) * inv, hz);
        int ix = (int)ux, iy = (int)uy, iz = (int)uz;
        fx = ux - ix; fy = uy - iy; fz = uz - iz;
        return ix + sy * iy + sz * iz;
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static float Clamp(float u, float hi) => u >= 0f ? (u <= hi ? u : hi) : 0f;

    private (int Begin, int End) NodeRange(int job)
    {
        int slab = _grid.Nx * _grid.Ny;
        return (slab * (int)((long)_grid.Nz * job / _nodeJobs), slab * (int)((long)_grid.Nz * (job + 1) / _nodeJobs));
    }

    private void ReduceJob(int job)
    {
        var (begin, end) = NodeRange(job);
        var s0 = _splat[0]; var s1 = _splat[1]; var s2 = _splat[2]; var s3 = _splat[3];
        float inv = _invTarget;
        for (int k = begin; k < end; k++)
        {
            var sum = ((s0[k] + s1[k]) + s2[k]) + s3[k];
            s0[k] = default; s1[k] = default; s2[k] = default; s3[k] = default;
            _p[k] = MathF.Max(0f, sum.GetElement(0) * inv - 1f);
            _sum[k] = sum;
        }
    }

    private void GradientJob(int job)
    {
        var g = _grid;
        int nx = g.Nx, ny = g.Ny, nz = g.Nz, sy = nx, sz = nx * ny;
        int zBegin = (int)((long)nz * job / _nodeJobs), zEnd = (int)((long)nz * (job + 1) / _nodeJobs);
        var p = _p;
        float half = -0.5f * _push, maxPush = _maxPush, friction = _friction, curvature = 0f;
        // Row by row (no divisions to find a node's x, y, z).
        for (int z = zBegin; z < zEnd; z++)
            for (int y = 0; y < ny; y++)
            {
                int row = z * sz + y * sy;
                for (int x = 0, k = row; x < nx; x++, k++)
                {
                    float px1 = x + 1 < nx ? p[k + 1] : 0f, px0 = x > 0 ? p[k - 1] : 0f;
                    float py1 = y + 1 < ny ? p[k + sy] : 0f, py0 = y > 0 ? p[k - sy] : 0f;
                    float pz1 = z + 1 < nz ? p[k + sz] : 0f, pz0 = z > 0 ? p[k - sz] : 0f;
                    float dx = half * (px1 - px0), dy = half * (py1 - py0), dz = half * (pz1 - pz0);
                    float d2 = dx * dx + dy * dy + dz * dz;
                    if (d2 > maxPush * maxPush) { float c = maxPush / MathF.Sqrt(d2); dx *= c; dy *= c; dz *= c; }
                    var sum = _sum[k]; // (ρ, mx, my, mz)
                    float rho = sum.GetElement(0);
                    if (rho > VolumeSystem.MinDensity)
                    {
                        float pk2 = 2f * p[k];
                        curvature = MathF.Max(curvature, MathF.Max(MathF.Abs(px1 - pk2 + px0), MathF.Max(MathF.Abs(py1 - pk2 + py0), MathF.Abs(pz1 - pk2 + pz0))));
                        float pull = friction / rho;
                        _change[k] = Vector128.Create(dx + pull * sum.GetElement(1), dy + pull * sum.GetElement(2), dz + pull * sum.GetElement(3), friction);
                    }
                    else _change[k] = Vector128.Create(dx, dy, dz, 0f);
                }
            }
        _jobCurvature[job] = curvature;
    }

    private void GatherJob(int job)
    {
        var w = _w;
        var (sheetBegin, sheetEnd) = Sheets(job, _sheetJobs);
        var lanes = new CellLanes(_grid);
        for (int q = sheetBegin; q < sheetEnd; q++)
        {
            int first = w.SheetFirstStrand[q], count = w.SheetStrandCount[q];
            for (int j = 0; j < count; j = VolumeSampling.Next(j, count, _every)) SampleStrand(first + j, in lanes);
            if (_inert) continue;
            // Every strand between two samples a < b takes its share of both (VolumeSampling.Bracket, without a division
            // per strand); a sample takes its own change.
            for (int a = 0, b; a < count; a = b)
            {
                b = VolumeSampling.Next(a, count, _every);
                Apply(first + a, first + a, first + a, 0f);
                if (b == count) break;
                for (int j = a + 1; j < b; j++) Apply(first + j, first + a, first + b, (float)((double)(j - a) / (b - a)));
                if (b == count - 1 && b % _every != 0) { Apply(first + b, first + a, first + b, 1f); break; }
            }
        }
    }

    /// <summary>Strand s takes (1 − t) of sample a's change and t of sample b's, particle by particle (8 at a time where all three strands have them).</summary>
    private void Apply(int s, int a, int b, float t)
    {
        var w = _w;
        float[] velX = w.VelX, velY = w.VelY, velZ = w.VelZ, invMass = w.InvMass;
        int first = w.StrandFirst[s], n = w.StrandParticleCount[s];
        int firstA = _sampleAt[a], lastA = w.StrandParticleCount[a] - 1, firstB = _sampleAt[b], lastB = w.StrandParticleCount[b] - 1;
        int whole = Math.Min(n, Math.Min(lastA, lastB) + 1);
        float ta = 1f - t;
        int k = 0;
        if (Vector256.IsHardwareAccelerated)
        {
            var vta = Vector256.Create(ta); var vtb = Vector256.Create(t);
            for (; k + 8 <= whole; k += 8)
            {
                int i = first + k, ia = firstA + k, ib = firstB + k;
                var vx = Load(velX, i); var vy = Load(velY, i); var vz = Load(velZ, i);
                var fa = vta * Load(_share, ia); var fb = vtb * Load(_share, ib);
                var free = Vector256.GreaterThan(Load(invMass, i), Vector256<float>.Zero);
                var dx = vta * Load(_pushX, ia) + vtb * Load(_pushX, ib) - (fa + fb) * vx;
                var dy = vta * Load(_pushY, ia) + vtb * Load(_pushY, ib) - (fa + fb) * vy;
                var dz = vta * Load(_pushZ, ia) + vtb * Load(_pushZ, ib) - (fa + fb) * vz;
                (vx + (dx & free)).StoreUnsafe(ref velX[0], (nuint)i);
                (vy + (dy & free)).StoreUnsafe(ref velY[0], (nuint)i);
                (vz + (dz & free)).StoreUnsafe(ref velZ[0], (nuint)i);
            }
        }
        for (; k < n; k++)
        {
            int i = first + k;
            if (invMass[i] == 0f) continue;
            int ia = firstA + Math.Min(k, lastA), ib = firstB + Math.Min(k, lastB);
            float vx = velX[i], vy = velY[i], vz = velZ[i];
            float fab = ta * _share[ia] + t * _share[ib];
            velX[i] = vx + (ta * _pushX[ia] + t * _pushX[ib] - fab * vx);
            velY[i] = vy + (ta * _pushY[ia] + t * _pushY[ib] - fab * vy);
            velZ[i] = vz + (ta * _pushZ[ia] + t * _pushZ[ib] - fab * vz);
        }
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static Vector256<float> Load(float[] a, int i) => Vector256.LoadUnsafe(ref a[0], (nuint)i);

    /// <summary>D and S (see <see cref="_change"/>) at every particle of sample strand s, into the packed buffers (eight at a time, then one by one: the same bits).</summary>
    [SkipLocalsInit]
    private unsafe void SampleStrand(int s, in CellLanes lanes)
    {
        var w = _w;
        var g = _grid;
        int sy = g.Nx, sz = g.Nx * g.Ny;
        ref var change = ref _change[0];
        float[] posX = w.PosX, posY = w.PosY, posZ = w.PosZ, velX = w.VelX, velY = w.VelY, velZ = w.VelZ, invMass = w.InvMass;
        float[] pushX = _pushX, pushY = _pushY, pushZ = _pushZ, share = _share;
        int* cell = stackalloc int[CellLanes.Lanes];
        int i = w.StrandFirst[s], e = i + w.StrandParticleCount[s];
        // Particle i's values go to packed entry i + o.
        int o = _sampleAt[s] - i, end = e + o;
        if ((uint)e > (uint)posX.Length || (uint)e > (uint)velX.Length || (uint)e > (uint)invMass.Length || (uint)e > (uint)posY.Length
            || (uint)e > (uint)posZ.Length || (uint)e > (uint)velY.Length || (uint)e > (uint)velZ.Length || (uint)end > (uint)share.Length
            || (uint)end > (uint)pushX.Length || (uint)end > (uint)pushY.Length || (uint)end > (uint)pushZ.Length || i < 0 || i + o < 0)
            throw new InvalidOperationException("Strand outside the particle arrays.");
        FetchAhead(w, s + 2 * _every, roots: false);
        // Eight particles at a time where AVX2 is there: their cells and weights side by side, and each corner's nodes
        // turned into eight-lane channels (the same sums in the same order as one particle at a time, so the same bits).
        for (; Lanes && i + CellLanes.Lanes <= e; i += CellLanes.Lanes)
        {
            var px = Load(posX, i); var py = Load(posY, i); var pz = Load(posZ, i);
            var dead = Vector256.Equals(Load(invMass, i), Vector256<float>.Zero)
                | CellLanes.NonFinite(px + py + pz + Load(velX, i) + Load(velY, i) + Load(velZ, i));
            lanes.Cells(px, py, pz, cell, out var fx, out var fy, out var fz);
            var one = Vector256<float>.One;
            var gx = one - fx; var gy = one - fy; var gz = one - fz;
            var w00 = gy * gz; var w10 = fy * gz; var w01 = gy * fz; var w11 = fy * fz;
            CellLanes.Corner(ref change, cell, 0, out var x0, out var y0, out var z0, out var s0);
            CellLanes.Corner(ref change, cell, 1, out var x1, out var y1, out var z1, out var s1);
            var c0 = gx * w00; var c1 = fx * w00;
            var ax = x0 * c0 + x1 * c1; var ay = y0 * c0 + y1 * c1; var az = z0 * c0 + z1 * c1; var aS = s0 * c0 + s1 * c1;
            CellLanes.Corner(ref change, cell, sy, out x0, out y0, out z0, out s0);
            CellLanes.Corner(ref change, cell, sy + 1, out x1, out y1, out z1, out s1);
            c0 = gx * w10; c1 = fx * w10;
            ax += x0 * c0 + x1 * c1; ay += y0 * c0 + y1 * c1; az += z0 * c0 + z1 * c1; aS += s0 * c0 + s1 * c1;
            CellLanes.Corner(ref change, cell, sz, out x0, out y0, out z0, out s0);
            CellLanes.Corner(ref change, cell, sz + 1, out x1, out y1, out z1, out s1);
            c0 = gx * w01; c1 = fx * w01;
            var bx = x0 * c0 + x1 * c1; var by = y0 * c0 + y1 * c1; var bz = z0 * c0 + z1 * c1; var bS = s0 * c0 + s1 * c1;
            CellLanes.Corner(ref change, cell, sz + sy, out x0, out y0, out z0, out s0);
            CellLanes.Corner(ref change, cell, sz + sy + 1, out x1, out y1, out z1, out s1);
            c0 = gx * w11; c1 = fx * w11;
            bx += x0 * c0 + x1 * c1; by += y0 * c0 + y1 * c1; bz += z0 * c0 + z1 * c1; bS += s0 * c0 + s1 * c1;
            Vector256.AndNot(ax + bx, dead).StoreUnsafe(ref pushX[0], (nuint)(i + o));
            Vector256.AndNot(ay + by, dead).StoreUnsafe(ref pushY[0], (nuint)(i + o));
            Vector256.AndNot(az + bz, dead).StoreUnsafe(ref pushZ[0], (nuint)(i + o));
            Vector256.AndNot(aS + bS, dead).StoreUnsafe(ref share[0], (nuint)(i + o));
        }
        float hx = g.Nx - 1.001f, hy = g.Ny - 1.001f, hz = g.Nz - 1.001f;
        for (; i < e; i++)
        {
            float px = posX[i], py = posY[i], pz = posZ[i];
            if (invMass[i] == 0f || !float.IsFinite(px + py + pz + velX[i] + velY[i] + velZ[i]))
            {
                pushX[i + o] = pushY[i + o] = pushZ[i + o] = share[i + o] = 0f;
                continue;
            }
            int b = Cell(px, py, pz, g.Origin, g.InvCell, hx, hy, hz, sy, sz, out float fx, out float fy, out float fz);
            float gx = 1f - fx, gy = 1f - fy, gz = 1f - fz;
            float w00 = gy * gz, w10 = fy * gz, w01 = gy * fz, w11 = fy * fz;
            ref var n0 = ref Unsafe.Add(ref change, b);
            ref var n1 = ref Unsafe.Add(ref n0, sy);
            ref var n2 = ref Unsafe.Add(ref n0, sz);
            ref var n3 = ref Unsafe.Add(ref n2, sy);
            var acc = (n0 * (gx * w00) + Unsafe.Add(ref n0, 1) * (fx * w00))
                    + (n1 * (gx * w10) + Unsafe.Add(ref n1, 1) * (fx * w10))
                    + ((n2 * (gx * w01) + Unsafe.Add(ref n2, 1) * (fx * w01))
                    + (n3 * (gx * w11) + Unsafe.Add(ref n3, 1) * (fx * w11)));
            pushX[i + o] = acc.GetElement(0); pushY[i + o] = acc.GetElement(1); pushZ[i + o] = acc.GetElement(2); share[i + o] = acc.GetElement(3);
        }
    }

    /// <summary>
    /// Eight particles' grid cells and trilinear corner weights, side by side, with <see cref="Cell"/>'s operations lane by
    /// lane (so the same bits): the scalar version spent most of its time on the clamps, conversions and weights.
    /// </summary>
    private readonly struct CellLanes(VolumeGrid g)
    {
        public const int Lanes = 8;
        private readonly Vector256<float> _ox = Vector256.Create(g.Origin.X), _oy = Vector256.Create(g.Origin.Y), _oz = Vector256.Create(g.Origin.Z);
        private readonly Vector256<float> _inv = Vector256.Create(g.InvCell);
        private readonly Vector256<float> _hx = Vector256.Create(g.Nx - 1.001f), _hy = Vector256.Create(g.Ny - 1.001f), _hz = Vector256.Create(g.Nz - 1.001f);
        private readonly Vector256<int> _sy = Vector256.Create(g.Nx), _sz = Vector256.Create(g.Nx * g.Ny);

        /// <summary>Lanes whose sum is finite, as bits.</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public static uint Finite(Vector256<float> sum) => ~NonFinite(sum).ExtractMostSignificantBits() & 0xFFu;

        /// <summary>Lanes whose sum is not finite, as a mask.</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public static Vector256<float> NonFinite(Vector256<float> sum)
        {
            var exponent = Vector256.Create(0x7F800000);
            return Vector256.Equals(sum.AsInt32() & exponent, exponent).AsSingle();
        }

        /// <summary>Each lane's first node into <paramref name="cell"/>, and its place in the cell.</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public unsafe void Cells(Vector256<float> px, Vector256<float> py, Vector256<float> pz, int* cell,
            out Vector256<float> fx, out Vector256<float> fy, out Vector256<float> fz)
        {
            var ux = Clamp((px - _ox) * _inv, _hx); var uy = Clamp((py - _oy) * _inv, _hy); var uz = Clamp((pz - _oz) * _inv, _hz);
            // The clamped values lie in [0, N − 1): truncation is C#'s (int) conversion there.
            var ix = Vector256.ConvertToInt32(ux); var iy = Vector256.ConvertToInt32(uy); var iz = Vector256.ConvertToInt32(uz);
            fx = ux - Vector256.ConvertToSingle(ix); fy = uy - Vector256.ConvertToSingle(iy); fz = uz - Vector256.ConvertToSingle(iz);
            (ix + _sy * iy + _sz * iz).Store(cell);
        }

        /// <summary>Each lane's first node into <paramref name="cell"/>, corner c's weight (c = x + 2y + 4z) into corner[8c + lane].</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public unsafe void Cells(Vector256<float> px, Vector256<float> py, Vector256<float> pz, int* cell, float* corner)
        {
            Cells(px, py, pz, cell, out var fx, out var fy, out var fz);
            var one = Vector256<float>.One;
            var gx = one - fx; var gy = one - fy; var gz = one - fz;
            var w00 = gy * gz; var w10 = fy * gz; var w01 = gy * fz; var w11 = fy * fz;
            (gx * w00).Store(corner); (fx * w00).Store(corner + 8);
            (gx * w10).Store(corner + 16); (fx * w10).Store(corner + 24);
            (gx * w01).Store(corner + 32); (fx * w01).Store(corner + 40);
            (gx * w11).Store(corner + 48); (fx * w11).Store(corner + 56);
        }

        /// <summary>
        /// The four floats of node cell[l] + o of every lane l, as eight-lane vectors: lanes j and j + 4 share one 256-bit
        /// value, and a 4×4 transpose within each half puts lanes 0–3 and 4–7 in order.
        /// </summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public static unsafe void Corner(ref Vector128<float> nodes, int* cell, int o,
            out Vector256<float> x, out Vector256<float> y, out Vector256<float> z, out Vector256<float> w)
        {
            var p0 = Vector256.Create(Unsafe.Add(ref nodes, cell[0] + o), Unsafe.Add(ref nodes, cell[4] + o));
            var p1 = Vector256.Create(Unsafe.Add(ref nodes, cell[1] + o), Unsafe.Add(ref nodes, cell[5] + o));
            var p2 = Vector256.Create(Unsafe.Add(ref nodes, cell[2] + o), Unsafe.Add(ref nodes, cell[6] + o));
            var p3 = Vector256.Create(Unsafe.Add(ref nodes, cell[3] + o), Unsafe.Add(ref nodes, cell[7] + o));
            var t0 = Avx.UnpackLow(p0, p1); var t1 = Avx.UnpackHigh(p0, p1);
            var t2 = Avx.UnpackLow(p2, p3); var t3 = Avx.UnpackHigh(p2, p3);
            x = Avx.Shuffle(t0, t2, 0x44); y = Avx.Shuffle(t0, t2, 0xEE);
            z = Avx.Shuffle(t1, t3, 0x44); w = Avx.Shuffle(t1, t3, 0xEE);
        }

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        private static Vector256<float> Clamp(Vector256<float> u, Vector256<float> hi) =>
            Vector256.ConditionalSelect(Vector256.GreaterThanOrEqual(u, Vector256<float>.Zero),
                Vector256.ConditionalSelect(Vector256.LessThanOrEqual(u, hi), u, hi), Vector256<float>.Zero);
    }
}
