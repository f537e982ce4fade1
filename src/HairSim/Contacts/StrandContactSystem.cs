namespace HairSim;

/// <summary>What a strand-contact pass found (<see cref="StrandContactSystem.LastPass"/>).</summary>
public readonly record struct ContactPass(int Candidates, int Pushed, int Crossed, bool Overloaded = false);

/// <summary>
/// Strand contacts between sheets (<see cref="StrandContactSettings"/>), once per pass after the substeps, on the
/// stepping thread:
/// 1. the segments of every live strand, each boxed over where it was at the pass's start and where it is now (so a
///    segment that moved far is still found), widened by half the contact distance D;
/// 2. a grid of cells the size of the mean box, each box filed in every cell it overlaps: the candidate pairs are the
///    overlapping boxes of segments of different sheets, each taken once, in a fixed order;
/// 3. Gauss–Seidel sweeps over the candidates (position-based, Müller et al. 2007): at the closest points of the two
///    segments, a pair closer than its contact distance (D, or less where the two lie closer at rest, as sheets do at
///    the roots) is pushed apart along the line between them, shared by inverse mass and by where the points lie on
///    their segments; a pair that passed through each other during the pass (edge–edge test, see <see cref="Crossed"/>)
///    goes back to the side it came from, which is what keeps a fast layer from tunnelling through a slow one. After
///    each sweep the strands it moved get their rest lengths back and are put out of the colliders; a last sweep has
///    the final say;
/// 4. each pair pushed loses the velocity with which it approaches (<see cref="StrandContactSettings.Restitution"/>).
/// Friction (<see cref="StrandContactSettings.Friction"/>) holds touching strands against sliding past each other, in
/// positions and velocities (Coulomb: up to μ × the push).
/// Pinned particles do not move. Skipped on teleport frames (the hair is carried rigidly). The same code serves both
/// solver paths; it is sequential, so its result does not depend on the thread count.
/// </summary>
public sealed class StrandContactSystem : IHairSystem, IPassStartListener, IStrandResetListener
{
    public const string SystemName = "StrandContact";
    public string Name => SystemName;
    public SystemPhase Phase => SystemPhase.PassEnd;

    /// <summary>At most this many grid cells: hair spread wider than this at the needed cell size gets larger cells.</summary>
    public const int MaxCells = 1 << 20;

    // Positions at the start of the pass.
    private float[] _x0 = [], _y0 = [], _z0 = [];
    // Per segment: its first particle, its sheet, its strand and its box (low corner, high corner).
    private int[] _segFirst = [], _segSheet = [], _segStrand = [];
    private float[] _box = [];
    // Strands the last sweep moved, whose segments are brought back to their rest lengths after it; and strands moved
    // at all in this pass (only their pairs can have been moved into a crossing by putting lengths right).
    private bool[] _moved = [], _touched = [];
    private int[] _cellStart = [], _entries = [];
    private int[] _pairs = [], _active = [];
    // Per candidate pair (first sweep): its contact distance, D or the pair's distance at rest if that is less.
    private double[] _pairD = [];
    private int _activeCount;

    /// <summary>At most this many sweeps that only put back crossed pairs end a pass (each but the last followed by the lengths put right).</summary>
    internal const int FinalRounds = 4;

    /// <summary>Pairs within this many contact distances after the first sweep are swept again (see <see cref="Sweep"/>).</summary>
    internal const double NearShare = 3;
    private int _segments, _pairCount;

    /// <summary>
    /// The last pass: candidate segment pairs, pairs pushed apart in the first sweep and, of those, pairs that had
    /// crossed during the pass; Overloaded when the hair held more than <see cref="StrandContactSettings.PairsPerSegment"/>
    /// × <see cref="PassBudget"/> candidates per segment in motion and the pass was skipped.
    /// </summary>
    public ContactPass LastPass { get; private set; }

    // The edit stamp and thickness the groom was last checked against the pair budget for.
    private int _checkedStamp = -1;
    private float _checkedThickness = float.NaN;

    /// <summary>A pass may hold this many times the pairs per segment the groom was checked against, since moving hair's boxes are longer.</summary>
    public const int PassBudget = 4;

    /// <summary>
    /// Keeps the positions the pass starts from. At a frame's first pass, before anything moves, the groom is checked
    /// against the pair budget after an edit or a change of thickness: a groom packed denser than contacts can handle
    /// is refused with a message, the world unchanged.
    /// </summary>
    public void PassStarting(HairScene scene, FrameContext ctx, bool firstOfFrame)
    {
        var w = scene.World;
        int n = w.ParticleCount;
        if (_x0.Length != n) { _x0 = new float[n]; _y0 = new float[n]; _z0 = new float[n]; }
        w.PosX.AsSpan().CopyTo(_x0); w.PosY.AsSpan().CopyTo(_y0); w.PosZ.AsSpan().CopyTo(_z0);
        var settings = scene.GetComponent<StrandContactSettings>();
        if (settings == null || !firstOfFrame) return;
        settings.Validate();
        if (_checkedStamp == w.EditStamp && _checkedThickness == settings.Thickness) return;
        // The same broad phase as the pass, on the positions as they are (boxes of zero travel).
        double d = settings.Thickness * ctx.Scale.Segment;
        bool fits = !(d > 0) || !double.IsFinite(d) || !CollectSegments(w, (float)d, out float cell, out var lo, out var hi)
            || !BuildGrid(cell, lo, hi) || FindPairs(StrandContactSettings.PairsPerSegment, store: false);
        if (!fits)
            throw new InvalidOperationException(
                $"Strand contacts: the hair holds more than {StrandContactSettings.PairsPerSegment} candidate segment pairs per segment "
                + $"at a Thickness of {settings.Thickness} segments ({_segments} segments). Contacts are made for hair of few layers "
                + "(a few sheets over one another); for a full head of hair use VolumeSettings instead.");
        _checkedStamp = w.EditStamp; _checkedThickness = settings.Thickness;
    }

    /// <summary>A strand put back at rest in this pass starts its pass there: it crossed nothing.</summary>
    public void StrandReset(HairWorld world, int strand)
    {
        int first = world.StrandFirst[strand], n = world.StrandCapacity[strand];
        if (first + n > _x0.Length) return;
        world.PosX.AsSpan(first, n).CopyTo(_x0.AsSpan(first, n));
        world.PosY.AsSpan(first, n).CopyTo(_y0.AsSpan(first, n));
        world.PosZ.AsSpan(first, n).CopyTo(_z0.AsSpan(first, n));
    }

    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        // Without the component (a pipeline that keeps every system): the segments' boxes and grid, and nothing moved.
        var own = scene.GetComponent<StrandContactSettings>();
        bool inert = own == null;
        var settings = own ?? InertSettings;
        settings.Validate();
        LastPass = default;
        var w = scene.World;
        if (ctx.Teleported || _x0.Length != w.ParticleCount) return;
        double d = settings.Thickness * ctx.Scale.Segment;
        if (!(d > 0) || !double.IsFinite(d)) return;
        if (!CollectSegments(w, (float)d, out float cell, out var lo, out var hi)) return;
        if (!BuildGrid(cell, lo, hi)) return;
        if (inert) return;
        // Moving hair's boxes are longer than resting hair's: the pass allows a few times the budget the groom was checked against.
        if (!FindPairs(StrandContactSettings.PairsPerSegment * PassBudget))
        {
            LastPass = new ContactPass(_pairCount, 0, 0, Overloaded: true);
            return;
        }
        if (_moved.Length < w.StrandCount) { _moved = new bool[w.StrandCount]; _touched = new bool[w.StrandCount]; }
        bool lengths = ctx.Settings.Length != LengthMode.None;
        int pushed = 0, crossed = 0;
        // Each sweep is followed by lengths and colliders put right, which can move a strand into another. Sweeps that
        // only put back pairs that crossed then have the final say, so no pass ends with a crossing, and lengths stay
        // exact unless the last of them still had a crossing to undo.
        for (int it = 0; it < settings.Iterations; it++)
        {
            var (p, c) = Sweep(w, d, settings.Friction, settings.Restitution, first: it == 0, crossingsOnly: false);
            if (it == 0) { pushed = p; crossed = c; }
            if (p == 0) break;
            Settle(scene, ctx, lengths);
        }
        for (int round = 0; round < FinalRounds; round++)
        {
            if (Sweep(w, d, settings.Friction, settings.Restitution, first: false, crossingsOnly: true).Pushed == 0) break;
            Settle(scene, ctx, lengths && round < FinalRounds - 1);
        }
        Array.Clear(_touched, 0, w.StrandCount);
        LastPass = new ContactPass(_pairCount, pushed, crossed);
    }

    private bool CollectSegments(HairWorld w, float d, out float cell, out (float X, float Y, float Z) lo, out (float X, float Y, float Z) hi)
    {
        int capacity = w.ParticleCount;
        if (_segFirst.Length < capacity)
        {
            _segFirst = new int[capacity]; _segSheet = new int[capacity]; _segStrand = new int[capacity];
            _box = new float[6 * capacity];
        }
        float half = 0.5f * d;
        double extents = 0;
        float lx = float.MaxValue, ly = float.MaxValue, lz = float.MaxValue, hx = float.MinValue, hy = float.MinValue, hz = float.MinValue;
        int m = 0;
        for (int s = 0; s < w.StrandCount; s++)
        {
            int first = w.StrandFirst[s], last = first + w.StrandParticleCount[s] - 1;
            for (int i = first; i < last; i++)
            {
                float ax = Min4(w.PosX[i], w.PosX[i + 1], _x0[i], _x0[i + 1]) - half, bx = Max4(w.PosX[i], w.PosX[i + 1], _x0[i], _x0[i + 1]) + half;
                float ay = Min4(w.PosY[i], w.PosY[i + 1], _y0[i], _y0[i + 1]) - half, by = Max4(w.PosY[i], w.PosY[i + 1], _y0[i], _y0[i + 1]) + half;
                float az = Min4(w.PosZ[i], w.PosZ[i + 1], _z0[i], _z0[i + 1]) - half, bz = Max4(w.PosZ[i], w.PosZ[i + 1], _z0[i], _z0[i + 1]) + half;
                if (!float.IsFinite(ax + bx + ay + by + az + bz)) continue; // contained by the pipeline; never spread
                int b = 6 * m;
                _box[b] = ax; _box[b + 1] = ay; _box[b + 2] = az; _box[b + 3] = bx; _box[b + 4] = by; _box[b + 5] = bz;
                _segFirst[m] = i; _segSheet[m] = w.StrandSheet[s]; _segStrand[m] = s;
                extents += MathF.Max(bx - ax, MathF.Max(by - ay, bz - az));
                lx = MathF.Min(lx, ax); ly = MathF.Min(ly, ay); lz = MathF.Min(lz, az);
                hx = MathF.Max(hx, bx); hy = MathF.Max(hy, by); hz = MathF.Max(hz, bz);
                m++;
            }
        }
        _segments = m;
        // Cells of the mean box: most boxes then lie in one to eight cells, and one box that moved far (a whipping tip)
        // lies in many cells rather than making every cell large.
        cell = m > 0 ? MathF.Max(d, (float)(extents / m)) : d;
        lo = (lx, ly, lz); hi = (hx, hy, hz);
        return m > 1;
    }

    private int _nx, _ny, _nz;
    private float _inv, _ox, _oy, _oz;

    private bool BuildGrid(float cell, (float X, float Y, float Z) lo, (float X, float Y, float Z) hi)
    {
        for (int grow = 0; ; grow++)
        {
            long nx = (long)((hi.X - lo.X) / cell) + 1, ny = (long)((hi.Y - lo.Y) / cell) + 1, nz = (long)((hi.Z - lo.Z) / cell) + 1;
            if (nx * ny * nz <= MaxCells) { _nx = (int)nx; _ny = (int)ny; _nz = (int)nz; break; }
            if (grow > 64) return false;
            cell *= 1.25f;
        }
        _inv = 1f / cell; _ox = lo.X; _oy = lo.Y; _oz = lo.Z;
        int cells = _nx * _ny * _nz;
        if (_cellStart.Length < cells + 1) _cellStart = new int[Math.Max(cells + 1, 2 * _cellStart.Length)];
        Array.Clear(_cellStart, 0, cells + 1);
        // Every box is filed in every cell it overlaps: count, sum, then fill (in segment order within a cell).
        long entries = 0;
        for (int m = 0; m < _segments; m++)
        {
            CellRange(m, out int x0, out int y0, out int z0, out int x1, out int y1, out int z1);
            for (int z = z0; z <= z1; z++) for (int y = y0; y <= y1; y++) for (int x = x0; x <= x1; x++) _cellStart[x + _nx * (y + _ny * z) + 1]++;
            entries += (long)(x1 - x0 + 1) * (y1 - y0 + 1) * (z1 - z0 + 1);
        }
        if (entries > int.MaxValue / 2) return false;
        for (int c = 0; c < cells; c++) _cellStart[c + 1] += _cellStart[c];
        if (_entries.Length < entries) _entries = new int[Math.Max(entries, 2L * _entries.Length)];
        for (int m = 0; m < _segments; m++)
        {
            CellRange(m, out int x0, out int y0, out int z0, out int x1, out int y1, out int z1);
            for (int z = z0; z <= z1; z++) for (int y = y0; y <= y1; y++) for (int x = x0; x <= x1; x++) _entries[_cellStart[x + _nx * (y + _ny * z)]++] = m;
        }
        for (int c = cells; c > 0; c--) _cellStart[c] = _cellStart[c - 1];
        _cellStart[0] = 0;
        return true;
    }

    private int Cell(float v, float origin, int n) => Math.Clamp((int)((v - origin) * _inv), 0, n - 1);

    private void CellRange(int m, out int x0, out int y0, out int z0, out int x1, out int y1, out int z1)
    {
        int b = 6 * m;
        x0 = Cell(_box[b], _ox, _nx); y0 = Cell(_box[b + 1], _oy, _ny); z0 = Cell(_box[b + 2], _oz, _nz);
        x1 = Cell(_box[b + 3], _ox, _nx); y1 = Cell(_box[b + 4], _oy, _ny); z1 = Cell(_box[b + 5], _oz, _nz);
    }

    /// <summary>What a pipeline that keeps every system runs when the scene has no contacts: the boxes and the grid, no pairs, no pushes.</summary>
    internal static readonly StrandContactSettings InertSettings = new();

    /// <summary>
    /// The candidate pairs into <see cref="_pairs"/> in a fixed order (segment, its cells, world order): boxes of
    /// segments of different sheets that overlap, each pair taken once, in the cell that holds the low corner of the
    /// two boxes' overlap. False (stopped early) past <paramref name="perSegment"/> pairs per segment. Without
    /// <paramref name="store"/> the pairs are only counted (the groom's check).
    /// </summary>
    private bool FindPairs(int perSegment, bool store = true)
    {
        long budget = Math.Min(StrandContactSettings.MaxPairs, Math.Max(4096L, (long)perSegment * _segments));
        int count = 0;
        for (int a = 0; a < _segments; a++)
        {
            CellRange(a, out int x0, out int y0, out int z0, out int x1, out int y1, out int z1);
            int sheet = _segSheet[a], ba = 6 * a;
            for (int z = z0; z <= z1; z++)
                for (int y = y0; y <= y1; y++)
                    for (int x = x0; x <= x1; x++)
                    {
                        int c = x + _nx * (y + _ny * z);
                        for (int k = _cellStart[c], to = _cellStart[c + 1]; k < to; k++)
                        {
                            int b = _entries[k];
                            if (b <= a || _segSheet[b] == sheet) continue;
                            int bb = 6 * b;
                            if (_box[ba] > _box[bb + 3] || _box[bb] > _box[ba + 3] || _box[ba + 1] > _box[bb + 4] || _box[bb + 1] > _box[ba + 4]
                                || _box[ba + 2] > _box[bb + 5] || _box[bb + 2] > _box[ba + 5]) continue;
                            // Taken only in the cell of the overlap's low corner, so a pair sharing several cells counts once.
                            if (Cell(MathF.Max(_box[ba], _box[bb]), _ox, _nx) != x || Cell(MathF.Max(_box[ba + 1], _box[bb + 1]), _oy, _ny) != y
                                || Cell(MathF.Max(_box[ba + 2], _box[bb + 2]), _oz, _nz) != z) continue;
                            if (count >= budget) { _pairCount = count; return false; }
                            if (!store) { count++; continue; }
                            if (2 * count + 2 > _pairs.Length) Array.Resize(ref _pairs, (int)Math.Min(2 * budget, Math.Max(2048, 2L * _pairs.Length)));
                            _pairs[2 * count] = a; _pairs[2 * count + 1] = b;
                            count++;
                        }
                    }
        }
        _pairCount = count;
        return true;
    }

    /// <summary>
    /// One Gauss–Seidel sweep: the pairs pushed, and of those, the ones that had crossed. The first sweep goes over every
    /// candidate and keeps the pairs within <see cref="NearShare"/> × their contact distance (or crossed) for the later
    /// sweeps: the pushes of a pass move hair by about D, so pairs farther apart are left as they are.
    /// </summary>
    private (int Pushed, int Crossed) Sweep(HairWorld w, double d, double mu, double restitution, bool first, bool crossingsOnly)
    {
        // The sweeps that only undo crossings go over every candidate of a strand moved in this pass: putting lengths
        // right may have moved a pair that was far apart at the first sweep into a crossing.
        bool all = first || crossingsOnly;
        int pushed = 0, crossings = 0, kept = 0, count = all ? _pairCount : _activeCount;
        if (first && _active.Length < _pairCount) { _active = new int[Math.Max(_pairCount, 2 * _active.Length)]; _pairD = new double[_active.Length]; }
        var px = w.PosX; var py = w.PosY; var pz = w.PosZ; var im = w.InvMass;
        for (int q = 0; q < count; q++)
        {
            int k = all ? q : _active[q];
            int a = _pairs[2 * k], b = _pairs[2 * k + 1];
            int i = _segFirst[a], j = _segFirst[b];
            double wi = im[i], wi1 = im[i + 1], wj = im[j], wj1 = im[j + 1];
            if (wi + wi1 + wj + wj1 == 0) continue;
            if (crossingsOnly && !_touched[_segStrand[a]] && !_touched[_segStrand[b]]) continue;
            var p0 = (px[i], py[i], pz[i]); var p1 = (px[i + 1], py[i + 1], pz[i + 1]);
            var q0 = (px[j], py[j], pz[j]); var q1 = (px[j + 1], py[j + 1], pz[j + 1]);
            Gap(p0, p1, q0, q1, out double s, out double t, out double nx, out double ny, out double nz);
            double n2 = nx * nx + ny * ny + nz * nz;
            double dx = 0, dy = 0, dz = 0, dist;
            // Two segments can only have met during the pass if they are now no farther apart than their particles
            // travelled (the distance between two segments changes by at most that much).
            double travel = Travel(w, i, j);
            bool crossed = n2 <= travel * travel && Crossed(a, b, w, d, out dx, out dy, out dz);
            if (crossingsOnly && !crossed) continue;
            double dp;
            if (first)
            {
                bool near = n2 < NearShare * NearShare * d * d;
                // Strands closer than D at rest (sheets that meet at the roots) are kept only as far apart as they grew.
                dp = near ? Math.Min(d, RestDistance(w, i, j)) : d;
                _pairD[k] = dp;
                if (crossed || near && n2 < NearShare * NearShare * dp * dp) _active[kept++] = k;
            }
            else dp = _pairD[k];
            if (crossed) dist = nx * dx + ny * dy + nz * dz;
            else if (n2 < dp * dp && n2 > 1e-12 * d * d)
            {
                double inv = 1 / Math.Sqrt(n2);
                dx = nx * inv; dy = ny * inv; dz = nz * inv; dist = n2 * inv;
            }
            else continue; // apart, or the same point: no side to push towards (the next pass sees them apart or moving)
            double ca = 1 - s, cb = 1 - t;
            double denom = ca * ca * wi + s * s * wi1 + cb * cb * wj + t * t * wj1;
            if (!(denom > 1e-12)) continue;
            double depth = dp - dist;
            // Friction in position-based form (Macklin et al. 2014, §6.1, as the head collision has it): the closest
            // points' sliding past each other since the pass's start, up to μ × the depth pushed out, is taken back.
            double tx = 0, ty = 0, tz = 0;
            if (mu > 0)
            {
                double rx = nx - (Lerp(_x0[j], _x0[j + 1], t) - Lerp(_x0[i], _x0[i + 1], s));
                double ry = ny - (Lerp(_y0[j], _y0[j + 1], t) - Lerp(_y0[i], _y0[i + 1], s));
                double rz = nz - (Lerp(_z0[j], _z0[j + 1], t) - Lerp(_z0[i], _z0[i + 1], s));
                double along = rx * dx + ry * dy + rz * dz;
                rx -= along * dx; ry -= along * dy; rz -= along * dz;
                double slid = Math.Sqrt(rx * rx + ry * ry + rz * rz);
                double take = slid <= mu * depth ? 1 : mu * depth / slid;
                tx = -take * rx; ty = -take * ry; tz = -take * rz;
            }
            double lambda = 1 / denom;
            double ex = (dx * depth + tx) * lambda, ey = (dy * depth + ty) * lambda, ez = (dz * depth + tz) * lambda;
            if (!double.IsFinite(ex + ey + ez)) continue;
            Move(w, i, -ca * wi, ex, ey, ez); Move(w, i + 1, -s * wi1, ex, ey, ez);
            Move(w, j, cb * wj, ex, ey, ez); Move(w, j + 1, t * wj1, ex, ey, ez);
            StopApproach(w, i, j, s, t, ca, cb, denom, dx, dy, dz, restitution, mu);
            _moved[_segStrand[a]] = _moved[_segStrand[b]] = true;
            pushed++;
            if (crossed) crossings++;
        }
        if (first) _activeCount = kept;
        return (pushed, crossings);
    }

    /// <summary>
    /// The strands a sweep moved get their segments back to rest length, root to tip along their current directions
    /// (follow-the-leader, positions only), and are put back out of the colliders (as the collision pass does, inward
    /// velocity removed). Without the first the next substep's length pass would turn the stretch a push left into
    /// velocity (Δx / h: the shorter the substep, the harder the kick); without the second a layer resting on the head
    /// would be pushed into it and thrown back out by the next substep, over and over.
    /// </summary>
    private void Settle(HairScene scene, FrameContext ctx, bool lengths)
    {
        var w = scene.World;
        var px = w.PosX; var py = w.PosY; var pz = w.PosZ; var im = w.InvMass; var rest = w.RestLength;
        int last = ctx.Substeps - 1;
        var colliders = ctx.CollidersAt(last);
        var meshes = scene.MeshColliderArray;
        float slide = ctx.Settings.ContactSlide;
        for (int s = 0; s < w.StrandCount; s++)
        {
            if (!_moved[s]) continue;
            _moved[s] = false;
            _touched[s] = true;
            int first = w.StrandFirst[s], end = first + w.StrandParticleCount[s];
            if (lengths)
                for (int i = first + 1; i < end; i++)
                {
                    if (im[i] == 0f) continue;
                    double ux = px[i] - px[i - 1], uy = py[i] - py[i - 1], uz = pz[i] - pz[i - 1];
                    double len = Math.Sqrt(ux * ux + uy * uy + uz * uz);
                    if (!(len > 0)) continue;
                    double f = rest[i] / len;
                    px[i] = (float)(px[i - 1] + ux * f); py[i] = (float)(py[i - 1] + uy * f); pz[i] = (float)(pz[i - 1] + uz * f);
                }
            for (int i = first; i < end; i++)
            {
                if (im[i] == 0f) continue;
                for (int c = 0; c < colliders.Length; c++)
                {
                    if (!colliders[c].Resolve(w.GetPosition(i), out var surface, out var normal, out _)) continue;
                    w.PutPosition(i, surface);
                    float vn = w.VelX[i] * normal.X + w.VelY[i] * normal.Y + w.VelZ[i] * normal.Z;
                    if (vn < 0f) w.PutVelocity(i, (w.GetVelocity(i) - vn * normal) * slide);
                }
            }
            for (int m = 0; m < meshes.Length; m++)
                Meshes.MeshCollideSystem.Collide(w, meshes[m], new Meshes.MeshCollideSystem.Pose(ctx.MeshPoseAt(last, m, meshes)), slide, s, s + 1);
            ctx.StrandMoved(w, s);
        }
    }

    /// <summary>
    /// A pair just pushed apart along the unit n loses the velocity with which its closest points approach each other
    /// (restitution keeps a share), and Coulomb friction takes up to μ × that change off the velocity with which they
    /// slide past each other. Without this a pair pushed apart at the end of every pass would keep falling into each
    /// other (the push moves positions only).
    /// </summary>
    private static void StopApproach(HairWorld w, int i, int j, double s, double t, double ca, double cb, double denom,
        double nx, double ny, double nz, double restitution, double mu)
    {
        var vx = w.VelX; var vy = w.VelY; var vz = w.VelZ; var im = w.InvMass;
        double rx = Lerp(vx[j], vx[j + 1], t) - Lerp(vx[i], vx[i + 1], s);
        double ry = Lerp(vy[j], vy[j + 1], t) - Lerp(vy[i], vy[i + 1], s);
        double rz = Lerp(vz[j], vz[j + 1], t) - Lerp(vz[i], vz[i + 1], s);
        double approach = rx * nx + ry * ny + rz * nz;
        if (!(approach < 0)) return;
        double change = -(1 + restitution) * approach;
        double ux = rx - approach * nx, uy = ry - approach * ny, uz = rz - approach * nz;
        double slide = Math.Sqrt(ux * ux + uy * uy + uz * uz);
        double cut = slide > 0 ? Math.Min(1, mu * change / slide) : 0;
        double gx = (change * nx - cut * ux) / denom, gy = (change * ny - cut * uy) / denom, gz = (change * nz - cut * uz) / denom;
        if (!double.IsFinite(gx + gy + gz)) return;
        Kick(w, i, -ca * im[i], gx, gy, gz); Kick(w, i + 1, -s * im[i + 1], gx, gy, gz);
        Kick(w, j, cb * im[j], gx, gy, gz); Kick(w, j + 1, t * im[j + 1], gx, gy, gz);
    }

    /// <summary>
    /// Whether segments a and b passed through each other an odd number of times during the pass (continuous edge–edge
    /// test, Provot 1997 / Bridson et al. 2002): each of the four particles moving in a straight line from where the
    /// pass started to where it is now, the segments are coplanar where the triple product
    /// f(τ) = (q₀ − p₀)·((p₁ − p₀) × (q₁ − q₀)), a cubic in τ, is zero, and they pass through each other where they also
    /// meet there. If so, the unit normal of both segments now (d₁ × d₂), pointing to the side of a that b came from:
    /// the side it is not on now.
    /// </summary>
    private bool Crossed(int a, int b, HairWorld w, double d, out double ux, out double uy, out double uz)
    {
        ux = uy = uz = 0;
        int i = _segFirst[a], j = _segFirst[b];
        // Start (capitals) and travel (V) of p0, the two segment vectors and q0 − p0.
        double p0x = _x0[i], p0y = _y0[i], p0z = _z0[i];
        double Ax = _x0[i + 1] - p0x, Ay = _y0[i + 1] - p0y, Az = _z0[i + 1] - p0z;
        double Bx = _x0[j + 1] - _x0[j], By = _y0[j + 1] - _y0[j], Bz = _z0[j + 1] - _z0[j];
        double Rx = _x0[j] - p0x, Ry = _y0[j] - p0y, Rz = _z0[j] - p0z;
        double ax = w.PosX[i + 1] - w.PosX[i], ay = w.PosY[i + 1] - w.PosY[i], az = w.PosZ[i + 1] - w.PosZ[i];
        double bx = w.PosX[j + 1] - w.PosX[j], by = w.PosY[j + 1] - w.PosY[j], bz = w.PosZ[j + 1] - w.PosZ[j];
        double rx = w.PosX[j] - w.PosX[i], ry = w.PosY[j] - w.PosY[i], rz = w.PosZ[j] - w.PosZ[i];
        double Vax = ax - Ax, Vay = ay - Ay, Vaz = az - Az, Vbx = bx - Bx, Vby = by - By, Vbz = bz - Bz, Vrx = rx - Rx, Vry = ry - Ry, Vrz = rz - Rz;
        // f(τ) = c0 + c1 τ + c2 τ² + c3 τ³.
        Cross(Ax, Ay, Az, Bx, By, Bz, out double k0x, out double k0y, out double k0z);
        Cross(Ax, Ay, Az, Vbx, Vby, Vbz, out double e1x, out double e1y, out double e1z);
        Cross(Vax, Vay, Vaz, Bx, By, Bz, out double e2x, out double e2y, out double e2z);
        Cross(Vax, Vay, Vaz, Vbx, Vby, Vbz, out double k2x, out double k2y, out double k2z);
        double k1x = e1x + e2x, k1y = e1y + e2y, k1z = e1z + e2z;
        double c0 = Rx * k0x + Ry * k0y + Rz * k0z;
        double c1 = Vrx * k0x + Vry * k0y + Vrz * k0z + Rx * k1x + Ry * k1y + Rz * k1z;
        double c2 = Vrx * k1x + Vry * k1y + Vrz * k1z + Rx * k2x + Ry * k2y + Rz * k2z;
        double c3 = Vrx * k2x + Vry * k2y + Vrz * k2z;
        int crossings = 0;
        double fPrev = c0, tPrev = 0;
        for (int n = 1; n <= CcdSamples; n++)
        {
            double tau = (double)n / CcdSamples;
            double f = c0 + tau * (c1 + tau * (c2 + tau * c3));
            if (fPrev == 0 || fPrev * f < 0)
            {
                // Bisect to the root, then see whether the segments meet there.
                double lo = tPrev, hi = tau, flo = fPrev;
                for (int it = 0; it < 40 && flo != 0; it++)
                {
                    double mid = 0.5 * (lo + hi), fm = c0 + mid * (c1 + mid * (c2 + mid * c3));
                    if (fm == 0 || fm * flo < 0) hi = mid; else { lo = mid; flo = fm; }
                }
                if (MeetAt(i, j, w, flo == 0 ? lo : 0.5 * (lo + hi), d)) crossings++;
            }
            fPrev = f; tPrev = tau;
        }
        if ((crossings & 1) == 0) return false;
        double now = c0 + c1 + c2 + c3;
        Cross(ax, ay, az, bx, by, bz, out double cx, out double cy, out double cz);
        double c2n = cx * cx + cy * cy + cz * cz;
        if (!(c2n > 0) || now == 0) return false;
        double inv = (now > 0 ? -1 : 1) / Math.Sqrt(c2n);
        ux = cx * inv; uy = cy * inv; uz = cz * inv;
        return true;
    }

    /// <summary>Samples of the pass the coplanarity cubic is checked at for a change of sign (a cubic has at most three roots).</summary>
    private const int CcdSamples = 8;

    /// <summary>Whether segments i and j, at τ of the way from the pass's start to now, meet (closer than a thousandth of D).</summary>
    private bool MeetAt(int i, int j, HairWorld w, double tau, double d)
    {
        var p0 = Between(w, i, tau); var p1 = Between(w, i + 1, tau); var q0 = Between(w, j, tau); var q1 = Between(w, j + 1, tau);
        Gap(p0, p1, q0, q1, out _, out _, out double x, out double y, out double z);
        return x * x + y * y + z * z < 1e-6 * d * d;
    }

    private (double X, double Y, double Z) Between(HairWorld w, int k, double tau) =>
        (Lerp(_x0[k], w.PosX[k], tau), Lerp(_y0[k], w.PosY[k], tau), Lerp(_z0[k], w.PosZ[k], tau));

    private static void Cross(double ax, double ay, double az, double bx, double by, double bz, out double cx, out double cy, out double cz)
    {
        cx = ay * bz - az * by; cy = az * bx - ax * bz; cz = ax * by - ay * bx;
    }

    /// <summary>
    /// A bound on how much the distance between segments i and j changed since the pass's start: measured from particle
    /// i's own travel (the distance does not change when both move alike), the farthest any of the other three moved.
    /// </summary>
    private double Travel(HairWorld w, int i, int j)
    {
        double ox = w.PosX[i] - _x0[i], oy = w.PosY[i] - _y0[i], oz = w.PosZ[i] - _z0[i];
        return Moved(w, i + 1, ox, oy, oz) + Math.Max(Moved(w, j, ox, oy, oz), Moved(w, j + 1, ox, oy, oz));
    }

    private double Moved(HairWorld w, int k, double ox, double oy, double oz)
    {
        double x = w.PosX[k] - _x0[k] - ox, y = w.PosY[k] - _y0[k] - oy, z = w.PosZ[k] - _z0[k] - oz;
        return Math.Sqrt(x * x + y * y + z * z);
    }

    /// <summary>The distance between segments i and j (their first particles) in the rest pose.</summary>
    private static double RestDistance(HairWorld w, int i, int j)
    {
        var p0 = (w.RestX[i], w.RestY[i], w.RestZ[i]); var p1 = (w.RestX[i + 1], w.RestY[i + 1], w.RestZ[i + 1]);
        var q0 = (w.RestX[j], w.RestY[j], w.RestZ[j]); var q1 = (w.RestX[j + 1], w.RestY[j + 1], w.RestZ[j + 1]);
        Gap(p0, p1, q0, q1, out _, out _, out double x, out double y, out double z);
        return Math.Sqrt(x * x + y * y + z * z);
    }

    private static void Move(HairWorld w, int i, double f, double dx, double dy, double dz)
    {
        if (f == 0) return;
        w.PosX[i] = (float)(w.PosX[i] + f * dx); w.PosY[i] = (float)(w.PosY[i] + f * dy); w.PosZ[i] = (float)(w.PosZ[i] + f * dz);
    }

    private static void Kick(HairWorld w, int i, double f, double dx, double dy, double dz)
    {
        if (f == 0) return;
        w.VelX[i] = (float)(w.VelX[i] + f * dx); w.VelY[i] = (float)(w.VelY[i] + f * dy); w.VelZ[i] = (float)(w.VelZ[i] + f * dz);
    }

    private static double Lerp(double a, double b, double u) => a + u * (b - a);
    private static float Min4(float a, float b, float c, float d) => MathF.Min(MathF.Min(a, b), MathF.Min(c, d));
    private static float Max4(float a, float b, float c, float d) => MathF.Max(MathF.Max(a, b), MathF.Max(c, d));

    /// <summary>The closest points of segments p0p1 and q0q1 (parameters s, t) and the vector from the first to the second.</summary>
    private static void Gap((double X, double Y, double Z) p0, (double X, double Y, double Z) p1, (double X, double Y, double Z) q0, (double X, double Y, double Z) q1,
        out double s, out double t, out double x, out double y, out double z)
    {
        ClosestPoints(p0, p1, q0, q1, out s, out t);
        x = Lerp(q0.X, q1.X, t) - Lerp(p0.X, p1.X, s);
        y = Lerp(q0.Y, q1.Y, t) - Lerp(p0.Y, p1.Y, s);
        z = Lerp(q0.Z, q1.Z, t) - Lerp(p0.Z, p1.Z, s);
    }

    /// <summary>
    /// The parameters (0 … 1) of the closest points of segments p0p1 and q0q1 (Ericson, Real-Time Collision Detection,
    /// §5.1.9), with degenerate (zero-length) and parallel segments handled.
    /// </summary>
    internal static void ClosestPoints((double X, double Y, double Z) p0, (double X, double Y, double Z) p1,
        (double X, double Y, double Z) q0, (double X, double Y, double Z) q1, out double s, out double t)
    {
        double d1x = p1.X - p0.X, d1y = p1.Y - p0.Y, d1z = p1.Z - p0.Z;
        double d2x = q1.X - q0.X, d2y = q1.Y - q0.Y, d2z = q1.Z - q0.Z;
        double rx = p0.X - q0.X, ry = p0.Y - q0.Y, rz = p0.Z - q0.Z;
        double a = d1x * d1x + d1y * d1y + d1z * d1z, e = d2x * d2x + d2y * d2y + d2z * d2z, f = d2x * rx + d2y * ry + d2z * rz;
        const double eps = 1e-30;
        if (a <= eps && e <= eps) { s = t = 0; return; }
        if (a <= eps) { s = 0; t = Math.Clamp(f / e, 0, 1); return; }
        double c = d1x * rx + d1y * ry + d1z * rz;
        if (e <= eps) { t = 0; s = Math.Clamp(-c / a, 0, 1); return; }
        double b = d1x * d2x + d1y * d2y + d1z * d2z, denom = a * e - b * b;
        s = denom > 1e-12 * a * e ? Math.Clamp((b * f - c * e) / denom, 0, 1) : 0.5; // parallel: the middle
        t = (b * s + f) / e;
        if (t < 0) { t = 0; s = Math.Clamp(-c / a, 0, 1); }
        else if (t > 1) { t = 1; s = Math.Clamp((b - c) / a, 0, 1); }
    }
}
