using System.Numerics;

namespace HairSim;

/// <summary>
/// Every particle of every strand, as flat struct-of-arrays buffers; strands and sheets are index ranges.
/// Strand s owns particles [StrandFirst[s], StrandFirst[s] + StrandCapacity[s]); the first
/// StrandParticleCount[s] of them are live (a cut lowers the count, an undo or regrow raises it again).
/// Arrays never change size after construction, so the simulation allocates nothing per step.
/// Positions and velocities are the simulation's to write. Whoever writes the other arrays (masses, rest pose, rest
/// shape, live counts) directly calls <see cref="MarkEdited"/> before the next step: systems may keep what they derive
/// from them (which particles are pinned, and where) until the stamp changes. Edit commands and loaders do this.
/// </summary>
public sealed class HairWorld
{
    /// <summary>Upper bound on particles in one world (≈ 1.3 GB of particle data); larger requests are refused before allocating.</summary>
    public const int MaxParticles = 16 * 1024 * 1024;
    public const int MaxParticlesPerStrand = 4096;
    /// <summary>
    /// Largest coordinate (m), velocity component (m/s) or size the public setters accept: a million kilometres, where
    /// float's spacing is already over 100 m, so nothing larger is hair (it is uninitialised memory or a unit mix-up), and
    /// every squared distance the solver forms stays finite in float.
    /// </summary>
    public const float MaxCoordinate = 1e9f;
    public const int MaxStrandsPerSheet = 4096;

    // ---- particles ----
    public readonly float[] PosX, PosY, PosZ;
    public readonly float[] VelX, VelY, VelZ;
    /// <summary>0 for a pinned particle (roots): it follows the head instead of the solver.</summary>
    public readonly float[] InvMass;
    /// <summary>Rest distance from the previous particle of the strand (0 at the root).</summary>
    public readonly float[] RestLength;
    /// <summary>Rest pose in head space: pins follow it, reset returns to it, fit writes it.</summary>
    public readonly float[] RestX, RestY, RestZ;
    /// <summary>
    /// Rest shape of the triple centred at each particle, in the triple's own frame (see <see cref="RestShape"/>):
    /// axial offsets of previous, middle and next particle from the triple's centroid, and the bend height.
    /// </summary>
    public readonly float[] ShapePrev, ShapeMid, ShapeNext, ShapeBend;

    // ---- strands ----
    public readonly int[] StrandFirst;
    public readonly int[] StrandCapacity;
    public readonly int[] StrandParticleCount;
    public readonly int[] StrandSheet;

    // ---- sheets ----
    public readonly int[] SheetFirstStrand;
    public readonly int[] SheetStrandCount;

    /// <summary>Current head pose; roots and colliders follow it.</summary>
    public RigidTransform Head { get; internal set; } = RigidTransform.Identity;

    /// <summary>Bumped by every edit that changes topology or rest data, so renderers and caches can notice.</summary>
    public int EditStamp { get; private set; }

    public int ParticleCount => PosX.Length;
    public int StrandCount => StrandFirst.Length;
    public int SheetCount => SheetFirstStrand.Length;
    public int MaxStrandCapacity { get; }

    /// <summary>A world of sheetCount sheets × strandsPerSheet strands × particlesPerStrand particles.</summary>
    public HairWorld(int sheetCount, int strandsPerSheet, int particlesPerStrand)
        : this(Uniform(Check(sheetCount, strandsPerSheet, particlesPerStrand), strandsPerSheet), Uniform(sheetCount * strandsPerSheet, particlesPerStrand))
    { }

    /// <summary>General layout: strands per sheet, then particle capacity per strand (in sheet order).</summary>
    public HairWorld(ReadOnlySpan<int> strandsPerSheet, ReadOnlySpan<int> particlesPerStrand)
    {
        if (strandsPerSheet.Length == 0) throw new ArgumentException("A hair world needs at least one sheet.", nameof(strandsPerSheet));
        long strands = 0;
        foreach (int n in strandsPerSheet)
        {
            if (n < 1 || n > MaxStrandsPerSheet)
                throw new ArgumentOutOfRangeException(nameof(strandsPerSheet), n, $"Strands per sheet must be in 1 … {MaxStrandsPerSheet}.");
            strands += n;
        }
        if (strands != particlesPerStrand.Length)
            throw new ArgumentException($"Sheets hold {strands} strands but {particlesPerStrand.Length} strand capacities were given.", nameof(particlesPerStrand));
        long particles = 0;
        int maxCap = 0;
        foreach (int p in particlesPerStrand)
        {
            if (p < 2 || p > MaxParticlesPerStrand)
                throw new ArgumentOutOfRangeException(nameof(particlesPerStrand), p, $"Particles per strand must be in 2 … {MaxParticlesPerStrand} (a root and a tip at least).");
            particles += p;
            maxCap = Math.Max(maxCap, p);
        }
        if (particles > MaxParticles)
            throw new ArgumentOutOfRangeException(nameof(particlesPerStrand), particles, $"{particles:N0} particles exceed the limit of {MaxParticles:N0} per world.");

        int np = (int)particles, ns = (int)strands;
        PosX = new float[np]; PosY = new float[np]; PosZ = new float[np];
        VelX = new float[np]; VelY = new float[np]; VelZ = new float[np];
        InvMass = new float[np]; RestLength = new float[np];
        RestX = new float[np]; RestY = new float[np]; RestZ = new float[np];
        ShapePrev = new float[np]; ShapeMid = new float[np]; ShapeNext = new float[np]; ShapeBend = new float[np];
        StrandFirst = new int[ns]; StrandCapacity = new int[ns]; StrandParticleCount = new int[ns]; StrandSheet = new int[ns];
        SheetFirstStrand = new int[strandsPerSheet.Length]; SheetStrandCount = new int[strandsPerSheet.Length];
        MaxStrandCapacity = maxCap;

        int s = 0, first = 0;
        for (int q = 0; q < strandsPerSheet.Length; q++)
        {
            SheetFirstStrand[q] = s;
            SheetStrandCount[q] = strandsPerSheet[q];
            for (int k = 0; k < strandsPerSheet[q]; k++, s++)
            {
                StrandFirst[s] = first;
                StrandCapacity[s] = particlesPerStrand[s];
                StrandParticleCount[s] = particlesPerStrand[s];
                StrandSheet[s] = q;
                first += particlesPerStrand[s];
            }
        }
        Array.Fill(InvMass, 1f);
    }

    private static int Check(int sheets, int strandsPerSheet, int particlesPerStrand)
    {
        if (sheets < 1) throw new ArgumentOutOfRangeException(nameof(sheets), sheets, "Sheet count must be at least 1.");
        if (strandsPerSheet < 1 || strandsPerSheet > MaxStrandsPerSheet)
            throw new ArgumentOutOfRangeException(nameof(strandsPerSheet), strandsPerSheet, $"Strands per sheet must be in 1 … {MaxStrandsPerSheet}.");
        if (particlesPerStrand < 2 || particlesPerStrand > MaxParticlesPerStrand)
            throw new ArgumentOutOfRangeException(nameof(particlesPerStrand), particlesPerStrand, $"Particles per strand must be in 2 … {MaxParticlesPerStrand}.");
        long total = (long)sheets * strandsPerSheet * particlesPerStrand;
        if (total > MaxParticles)
            throw new ArgumentOutOfRangeException(nameof(sheets), total, $"{total:N0} particles exceed the limit of {MaxParticles:N0} per world.");
        return sheets;
    }

    private static int[] Uniform(int count, int value)
    {
        var a = new int[count];
        Array.Fill(a, value);
        return a;
    }

    // ---- access helpers (not for hot loops) ----
    public Vector3 GetPosition(int i) => new(PosX[i], PosY[i], PosZ[i]);
    /// <summary>Sets a particle's position; a non-finite one is refused and nothing changes.</summary>
    public void SetPosition(int i, Vector3 p)
    {
        CheckParticle(i);
        if (!InRange(p)) throw new ArgumentException($"Position of particle {i} must be finite and within ±{MaxCoordinate:G} m, got {p}.", nameof(p));
        PutPosition(i, p);
    }

    /// <summary>Finite, each component within ±<see cref="MaxCoordinate"/>.</summary>
    public static bool InRange(Vector3 v) =>
        MathF.Abs(v.X) <= MaxCoordinate && MathF.Abs(v.Y) <= MaxCoordinate && MathF.Abs(v.Z) <= MaxCoordinate; // false for NaN

    private void CheckParticle(int i)
    {
        if ((uint)i >= (uint)ParticleCount) throw new ArgumentOutOfRangeException(nameof(i), i, $"Particle index must be in 0 … {ParticleCount - 1}.");
    }

    /// <summary>The systems' own write (their results are checked by the step, not per particle).</summary>
    internal void PutPosition(int i, Vector3 p) { PosX[i] = p.X; PosY[i] = p.Y; PosZ[i] = p.Z; }
    public Vector3 GetVelocity(int i) => new(VelX[i], VelY[i], VelZ[i]);
    /// <summary>Sets a particle's velocity; a non-finite one is refused and nothing changes.</summary>
    public void SetVelocity(int i, Vector3 v)
    {
        CheckParticle(i);
        if (!InRange(v)) throw new ArgumentException($"Velocity of particle {i} must be finite and within ±{MaxCoordinate:G} m/s, got {v}.", nameof(v));
        PutVelocity(i, v);
    }

    internal void PutVelocity(int i, Vector3 v) { VelX[i] = v.X; VelY[i] = v.Y; VelZ[i] = v.Z; }
    public Vector3 GetRest(int i) => new(RestX[i], RestY[i], RestZ[i]);
    public int SkeletonStrand(int sheet) => SheetFirstStrand[sheet] + SheetStrandCount[sheet] / 2;
    public int RootIndex(int strand) => StrandFirst[strand];
    public int TipIndex(int strand) => StrandFirst[strand] + StrandParticleCount[strand] - 1;

    /// <summary>Copies the live particles of a strand (world positions).</summary>
    public Vector3[] GetStrandPositions(int strand)
    {
        var pts = new Vector3[StrandParticleCount[strand]];
        for (int k = 0; k < pts.Length; k++) pts[k] = GetPosition(StrandFirst[strand] + k);
        return pts;
    }

    /// <summary>
    /// Sets a strand's rest pose (head space), rest lengths and rest shape from points, pins its first
    /// <paramref name="pinned"/> particles and places it at rest under the current head pose.
    /// The points may have fewer entries than the strand's capacity (a shorter strand). <paramref name="pinned"/> = 0
    /// makes a free strand (a clipping, a loose hair): nothing holds it to the head, it falls and collides as a whole,
    /// its segments keep their lengths and bend against each other (docs/robustness.md).
    /// </summary>
    public void SetStrand(int strand, ReadOnlySpan<Vector3> restHeadSpace, int pinned = 1, bool straightRestShape = false)
    {
        if ((uint)strand >= (uint)StrandCount) throw new ArgumentOutOfRangeException(nameof(strand));
        int cap = StrandCapacity[strand];
        if (restHeadSpace.Length < 2 || restHeadSpace.Length > cap)
            throw new ArgumentException($"A strand needs 2 … {cap} points, got {restHeadSpace.Length}.", nameof(restHeadSpace));
        if (pinned < 0 || pinned > restHeadSpace.Length)
            throw new ArgumentOutOfRangeException(nameof(pinned), pinned, $"Pinned particles must be in 0 (a free strand) … {restHeadSpace.Length} (every point).");
        double chord = 0;
        for (int k = 0; k < restHeadSpace.Length; k++)
        {
            var p = restHeadSpace[k];
            if (!InRange(p))
                throw new ArgumentException($"Point {k} of strand {strand} must be finite and within ±{MaxCoordinate:G} m, got {p}.", nameof(restHeadSpace));
            if (k > 0) chord += Vector3.Distance(p, restHeadSpace[k - 1]);
        }
        // Coincident: a segment shorter than a millionth of the strand's mean segment (scale-free), or exactly zero.
        double tiny = 1e-6 * chord / (restHeadSpace.Length - 1);
        for (int k = 1; k < restHeadSpace.Length; k++)
        {
            double d = Vector3.Distance(restHeadSpace[k], restHeadSpace[k - 1]);
            if (d <= tiny || d == 0)
                throw new ArgumentException($"Points {k - 1} and {k} of strand {strand} coincide: zero-length segments are not allowed.", nameof(restHeadSpace));
        }

        int first = StrandFirst[strand];
        int n = restHeadSpace.Length;
        StrandParticleCount[strand] = n;
        var head = Head;
        for (int k = 0; k < cap; k++)
        {
            int i = first + k;
            var p = restHeadSpace[Math.Min(k, n - 1)];
            RestX[i] = p.X; RestY[i] = p.Y; RestZ[i] = p.Z;
            RestLength[i] = k == 0 || k >= n ? 0f : Vector3.Distance(p, restHeadSpace[k - 1]);
            InvMass[i] = k < pinned ? 0f : 1f;
            PutPosition(i, head.TransformPoint(p));
            VelX[i] = VelY[i] = VelZ[i] = 0f;
        }
        if (straightRestShape) RestShape.SetStraight(this, strand);
        else RestShape.SetFromRestPose(this, strand);
        MarkEdited();
    }

    /// <summary>
    /// As <see cref="SetStrand(int, ReadOnlySpan{Vector3}, int, bool)"/>, but the strand starts away from its rest shape:
    /// <paramref name="startWorld"/> (world space, one point per rest point) is where its free particles are now, and the
    /// bend model brings it towards the rest shape from there. Pinned points start where the head puts their rest.
    /// Every point is checked before anything changes.
    /// </summary>
    public void SetStrand(int strand, ReadOnlySpan<Vector3> restHeadSpace, ReadOnlySpan<Vector3> startWorld, int pinned = 1, bool straightRestShape = false)
    {
        if (startWorld.Length != restHeadSpace.Length)
            throw new ArgumentException($"The start pose has {startWorld.Length} points but the rest shape {restHeadSpace.Length}: give one start point per rest point.", nameof(startWorld));
        for (int k = 0; k < startWorld.Length; k++)
        {
            var p = startWorld[k];
            if (!InRange(p))
                throw new ArgumentException($"Start point {k} of strand {strand} must be finite and within ±{MaxCoordinate:G} m, got {p}.", nameof(startWorld));
        }
        SetStrand(strand, restHeadSpace, pinned, straightRestShape);
        int first = StrandFirst[strand];
        for (int k = pinned; k < startWorld.Length; k++) PutPosition(first + k, startWorld[k]);
    }

    /// <summary>Puts every live particle back at its rest pose under the current head, at rest.</summary>
    public void ResetToRest()
    {
        var head = Head;
        for (int i = 0; i < ParticleCount; i++)
        {
            PutPosition(i, head.TransformPoint(GetRest(i)));
            VelX[i] = VelY[i] = VelZ[i] = 0f;
        }
    }

    /// <summary>Moves the head without simulating: every particle is carried rigidly (used at load and for teleports).</summary>
    public void PlaceHead(RigidTransform head)
    {
        CheckHead(head, nameof(head));
        var delta = RigidTransform.Delta(Head, head);
        for (int i = 0; i < ParticleCount; i++)
        {
            PutPosition(i, delta.TransformPoint(GetPosition(i)));
            PutVelocity(i, delta.TransformDirection(GetVelocity(i)));
        }
        Head = head;
    }

    /// <summary>Refuses a head pose the solver cannot use: a non-finite or zero rotation (a default value) or a position beyond <see cref="MaxCoordinate"/>.</summary>
    internal static void CheckHead(in RigidTransform head, string name)
    {
        var p = head.Position; var q = head.Rotation;
        if (!InRange(p) || !float.IsFinite(q.X) || !float.IsFinite(q.Y) || !float.IsFinite(q.Z) || !float.IsFinite(q.W) || q.LengthSquared() < 1e-12f)
            throw new ArgumentException($"The head pose must have a finite position within ±{MaxCoordinate:G} m and a non-zero rotation, got {p}, {q}.", name);
    }

    // Which strands are free (no live particle pinned), derived from the masses and live counts: kept until the next edit.
    private readonly object _freeGate = new();
    private bool[]? _free;
    private int _freeCount, _freeStamp = int.MinValue;

    /// <summary>Strands with no pinned live particle (free strands: clippings, loose hair).</summary>
    public int FreeStrandCount { get { EnsureFreeStrands(); return _freeCount; } }

    /// <summary>Whether strand s has no pinned live particle: it is held by nothing, so the solver shares its corrections out over the whole strand.</summary>
    public bool IsFreeStrand(int s) { EnsureFreeStrands(); return _freeCount > 0 && _free![s]; }

    /// <summary>Recomputes the free strands after an edit (the pipeline calls it before a frame's jobs, so jobs only read).</summary>
    internal void EnsureFreeStrands()
    {
        if (Volatile.Read(ref _freeStamp) == EditStamp) return;
        lock (_freeGate)
        {
            int stamp = EditStamp;
            if (_freeStamp == stamp) return;
            _free ??= new bool[StrandCount];
            int count = 0;
            for (int s = 0; s < StrandCount; s++)
            {
                bool free = true;
                for (int i = StrandFirst[s], end = i + StrandParticleCount[s]; i < end && free; i++) free = InvMass[i] != 0f;
                _free[s] = free;
                if (free) count++;
            }
            _freeCount = count;
            Volatile.Write(ref _freeStamp, stamp);
        }
    }

    /// <summary>Says that masses, rest pose, rest shape or live counts were written: caches derived from them are rebuilt.</summary>
    public void MarkEdited() => EditStamp++;

    /// <summary>
    /// Throws if a live particle's rest position, rest length or inverse mass is not finite (or a rest length or
    /// inverse mass is negative): data written straight into the arrays is checked when the step first sees the
    /// edit, before anything moves, instead of spreading NaN or freezing the scene.
    /// </summary>
    public void ValidateRestData()
    {
        for (int s = 0; s < StrandCount; s++)
        {
            int first = StrandFirst[s], end = first + StrandParticleCount[s];
            for (int i = first; i < end; i++)
            {
                if (!InRange(new Vector3(RestX[i], RestY[i], RestZ[i])))
                    throw new ArgumentException($"Strand {s}: the rest position of particle {i - first} must be finite and within ±{MaxCoordinate:G} m, got {GetRest(i)}.");
                if (!(RestLength[i] >= 0f && RestLength[i] <= MaxCoordinate))
                    throw new ArgumentException($"Strand {s}: the rest length of particle {i - first} must be in 0 … {MaxCoordinate:G} m, got {RestLength[i]}.");
                if (!float.IsFinite(InvMass[i]) || InvMass[i] < 0f)
                    throw new ArgumentException($"Strand {s}: the inverse mass of particle {i - first} must be finite and ≥ 0, got {InvMass[i]}.");
            }
        }
    }

    /// <summary>Total rest length of the live part of all strands.</summary>
    public double TotalRestLength()
    {
        double sum = 0;
        for (int s = 0; s < StrandCount; s++)
        {
            int first = StrandFirst[s];
            for (int k = 1; k < StrandParticleCount[s]; k++) sum += RestLength[first + k];
        }
        return sum;
    }

    /// <summary>A deep copy (undo snapshots, determinism tests, reference-vs-fast comparisons).</summary>
    public HairWorld Clone()
    {
        var c = new HairWorld(SheetStrandCount, StrandCapacity);
        CopyTo(c);
        return c;
    }

    /// <summary>Copies all state into a world of identical layout.</summary>
    public void CopyTo(HairWorld target)
    {
        if (!SameLayout(target)) throw new ArgumentException("Worlds differ in layout.", nameof(target));
        float[][] src = Buffers(), dst = target.Buffers();
        for (int b = 0; b < src.Length; b++) Array.Copy(src[b], dst[b], src[b].Length);
        Array.Copy(StrandParticleCount, target.StrandParticleCount, StrandCount);
        target.Head = Head;
        // Strictly newer than anything either world has had, so caches keyed on the target's stamp (the pipeline's reach) see the change.
        target.EditStamp = Math.Max(target.EditStamp, EditStamp) + 1;
    }

    /// <summary>
    /// Copies only the simulated state (positions, velocities, head pose) into a world of identical layout whose
    /// masses, rest pose and live counts already match: replays and benchmarks that restart from a saved moment.
    /// Not an edit, so the target's stamp (and what systems cached from it) stays.
    /// </summary>
    public void CopyMotionTo(HairWorld target)
    {
        if (!SameLayout(target)) throw new ArgumentException("Worlds differ in layout.", nameof(target));
        Array.Copy(PosX, target.PosX, PosX.Length); Array.Copy(PosY, target.PosY, PosY.Length); Array.Copy(PosZ, target.PosZ, PosZ.Length);
        Array.Copy(VelX, target.VelX, VelX.Length); Array.Copy(VelY, target.VelY, VelY.Length); Array.Copy(VelZ, target.VelZ, VelZ.Length);
        target.Head = Head;
    }

    public bool SameLayout(HairWorld other) =>
        other.ParticleCount == ParticleCount && other.StrandCount == StrandCount && other.SheetCount == SheetCount &&
        StrandCapacity.AsSpan().SequenceEqual(other.StrandCapacity) && SheetStrandCount.AsSpan().SequenceEqual(other.SheetStrandCount);

    /// <summary>Bit-for-bit equality of every buffer, strand count and the head pose.</summary>
    public bool BitEquals(HairWorld other)
    {
        if (!SameLayout(other) || !Head.Equals(other.Head)) return false;
        if (!StrandParticleCount.AsSpan().SequenceEqual(other.StrandParticleCount)) return false;
        float[][] a = Buffers(), b = other.Buffers();
        for (int k = 0; k < a.Length; k++)
            if (!System.Runtime.InteropServices.MemoryMarshal.AsBytes(a[k].AsSpan())
                .SequenceEqual(System.Runtime.InteropServices.MemoryMarshal.AsBytes(b[k].AsSpan()))) return false;
        return true;
    }

    /// <summary>All float buffers, in a fixed order (for copying, hashing and files).</summary>
    public float[][] Buffers() =>
        [PosX, PosY, PosZ, VelX, VelY, VelZ, InvMass, RestLength, RestX, RestY, RestZ, ShapePrev, ShapeMid, ShapeNext, ShapeBend];

    /// <summary>Counts non-finite positions and velocities among live particles.</summary>
    public int CountNonFinite()
    {
        int bad = 0;
        for (int s = 0; s < StrandCount; s++)
        {
            int first = StrandFirst[s], end = first + StrandParticleCount[s];
            for (int i = first; i < end; i++)
                if (!float.IsFinite(PosX[i]) || !float.IsFinite(PosY[i]) || !float.IsFinite(PosZ[i]) ||
                    !float.IsFinite(VelX[i]) || !float.IsFinite(VelY[i]) || !float.IsFinite(VelZ[i])) bad++;
        }
        return bad;
    }
}
