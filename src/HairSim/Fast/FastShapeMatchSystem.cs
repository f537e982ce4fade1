using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.Intrinsics;
using System.Runtime.Intrinsics.X86;

namespace HairSim.Fast;

/// <summary>
/// Fast <see cref="ShapeMatchSystem"/> in float SIMD, vectorised along each strand: one pass computes the
/// three goals of Width triples at once (triple k reads particles k−1, k, k+1 with unaligned loads), a second
/// pass sums each particle's goals (from triples j+1, j, j−1) and updates its velocity. Bent strands first get
/// their bend directions in a scalar pass (the reference carries a frame from root to tip, a chain). Triples whose
/// ends coincide are redone in scalar code with the reference's fallback axis. Strands shorter than Width + 2 are
/// copied into padded scratch first, so no load or store ever leaves the strand.
/// </summary>
public sealed partial class FastShapeMatchSystem : IHairSystem
{
    public string Name => ShapeMatchSystem.SystemName;
    public SystemPhase Phase => SystemPhase.Substep;

    // Scratch fields: 9 goal components, then the padded copy of a short strand.
    private const int GPx = 0, GPy = 1, GPz = 2, GMx = 3, GMy = 4, GMz = 5, GNx = 6, GNy = 7, GNz = 8;
    private const int CPx = 9, CPy = 10, CPz = 11, CVx = 12, CVy = 13, CVz = 14, CM = 15, CRx = 16, CRy = 17, CRz = 18,
        CSp = 19, CSm = 20, CSn = 21, CSb = 22, BNx = 23, BNy = 24, BNz = 25, FieldCount = 26;

    private readonly int _maxCapacity;
    private readonly bool _wide;

    /// <param name="maxStrandCapacity">The longest strand's capacity (sizes the per-thread scratch).</param>
    /// <param name="allowWide">Use the 16-lane AVX-512 path where the CPU has it (tests turn it off to check the 8-lane path).</param>
    /// <param name="world">The world it will run on, if known: then whether each strand's rest shape is bent is cached until the world is edited.</param>
    public FastShapeMatchSystem(int maxStrandCapacity, bool allowWide = true, HairWorld? world = null)
        : this(maxStrandCapacity, allowWide, registerStrands: true, world) { }

    /// <param name="registerStrands">Let the 8-lane path shape-match 16-particle strands in registers (tests compare it with the goal-scratch path).</param>
    internal FastShapeMatchSystem(int maxStrandCapacity, bool allowWide, bool registerStrands, HairWorld? world = null)
    {
        _maxCapacity = maxStrandCapacity;
        _wide = allowWide && WideAvailable;
        _registers = registerStrands && Avx2.IsSupported && Vector<float>.Count == 8;
        int n = world?.StrandCount ?? 0;
        _bentAt = new long[n];
        _bent = new bool[n];
    }

    // Per strand: the world's edit stamp + 1 when its bend flag was found (0: never), and the flag.
    private readonly long[] _bentAt;
    private readonly bool[] _bent;

    /// <summary>Whether strand s (live count n) has a bent rest shape; cached per strand until the world's next edit.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private bool Bent(HairWorld w, int s, int first, int n)
    {
        if ((uint)s >= (uint)_bentAt.Length) return HasBend(ref Simd.At(w.ShapeBend, first), n);
        long stamp = w.EditStamp + 1L;
        if (_bentAt[s] != stamp)
        {
            _bent[s] = HasBend(ref Simd.At(w.ShapeBend, first), n);
            _bentAt[s] = stamp;
        }
        return _bent[s];
    }

    private readonly bool _registers;

    /// <summary>Whether this instance takes the 16-lane path for the strands it can.</summary>
    internal bool UsesWide => _wide;

    private ref struct StrandView
    {
        public ref float Px, Py, Pz, Vx, Vy, Vz, M, Rx, Ry, Rz, Sp, Sm, Sn, Sb;
    }

    private readonly struct Params
    {
        public readonly Vector<float> F, FHalf, FThird, BetaOverH, Third, LenEps2;
        public readonly Vector<int> Two, Three;
        /// <summary><see cref="Simd.Lane"/>, copied once per run: Run is compiled before tiering, where each read of the static would cost a helper call.</summary>
        public readonly Vector<int> Lane;
        /// <summary>α/h divided by the goal count of the first and last Width particles of a long strand (1, 2, 3, … / …, 3, 2, 1).</summary>
        public readonly Vector<float> FirstF, LastF;
        public readonly float Alpha, Beta;
        public readonly PoseLanes Head;
        public readonly Quaternion HeadRotation;

        public Params(float h, float alpha, float beta, bool literal, in RigidTransform head)
        {
            Alpha = alpha; Beta = beta;
            float f = GoalFactor(h, alpha, literal);
            F = new(f); FHalf = new(f / 2f); FThird = new(f / 3f);
            Two = new(2); Three = new(3); Lane = Simd.Lane;
            int width = Vector<float>.Count;
            Span<float> first = stackalloc float[width], last = stackalloc float[width];
            for (int l = 0; l < width; l++)
            {
                first[l] = l == 0 ? f : l == 1 ? f / 2f : f / 3f;
                last[l] = l == width - 1 ? f : l == width - 2 ? f / 2f : f / 3f;
            }
            FirstF = new(first); LastF = new(last);
            BetaOverH = new(beta / h);
            Third = new(1f / 3f);
            LenEps2 = new(1e-24f); // |p[k+1] − p[k−1]| > 1e-12, squared
            Head = new PoseLanes(head);
            HeadRotation = head.Rotation;
        }
    }

    /// <summary>The pull of one goal: α·h (literal force) or α/h (Müller), divided by each particle's goal count.</summary>
    private static float GoalFactor(float h, float alpha, bool literal) => literal ? h * alpha : alpha / h;

    // The stack scratch is fully written before it is read, or only read in lanes that are masked out.
    [SkipLocalsInit]
    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var w = scene.World;
        var st = ctx.Settings;
        var p = new Params(ctx.H, st.Alpha, st.GlobalShapeStiffness, st.Mode == ShapeMatchMode.LiteralForce, ctx.HeadAt(substep));
        if (p.Alpha <= 0f && p.Beta <= 0f) return;
        if (_wide && p.Beta == 0f)
        {
            RunWide(w, begin, end, in p);
            return;
        }
        int size = StrandScratch.Size(_maxCapacity, FieldCount);
        var scratch = new StrandScratch(size <= StrandScratch.StackFloats ? stackalloc float[size] : StrandScratch.Heap(size), _maxCapacity);
        int width = Vector<float>.Count;
        Span<float> d = scratch.Data;
        // Goal slots no long strand's triple writes stay zero from one strand to the next of the same length.
        int zeroedFor = -1;
        bool registers = _registers && p.Beta == 0f && p.Alpha > 0f;
        int length = w.PosX.Length;
        for (int s = begin; s < end; s++)
        {
            int first = w.StrandFirst[s], n = w.StrandParticleCount[s];
            if (n == 16 && registers && first >= 1 && first + 17 < length && !Bent(w, s, first, n) && Strand16Narrow(w, first, in p)) continue;
            if (n >= width + 2)
            {
                var v = View(w, first);
                Strand(ref v, w, first, n, padded: false, zeroSlots: n != zeroedFor, in p, scratch);
                zeroedFor = n;
            }
            else
            {
                ShortStrand(w, first, n, in p, scratch);
                zeroedFor = -1; // defensive: a padded strand writes goal slots 1 … Width, which other lengths use
            }
        }
    }

    /// <summary>Refs to strand data from particle <paramref name="first"/> on.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static StrandView View(HairWorld w, int first) => new()
    {
        Px = ref Simd.At(w.PosX, first), Py = ref Simd.At(w.PosY, first), Pz = ref Simd.At(w.PosZ, first),
        Vx = ref Simd.At(w.VelX, first), Vy = ref Simd.At(w.VelY, first), Vz = ref Simd.At(w.VelZ, first),
        M = ref Simd.At(w.InvMass, first),
        Rx = ref Simd.At(w.RestX, first), Ry = ref Simd.At(w.RestY, first), Rz = ref Simd.At(w.RestZ, first),
        Sp = ref Simd.At(w.ShapePrev, first), Sm = ref Simd.At(w.ShapeMid, first),
        Sn = ref Simd.At(w.ShapeNext, first), Sb = ref Simd.At(w.ShapeBend, first),
    };

    /// <summary>
    /// A strand shorter than Width + 2: work on a padded copy, write back only its live velocities. Kept out of
    /// <see cref="Run"/> (not inlined) so the JIT's inlining budget for Run goes to the long-strand path, whose
    /// SIMD helpers must all be inlined.
    /// </summary>
    [MethodImpl(MethodImplOptions.NoInlining)]
    private static void ShortStrand(HairWorld w, int first, int n, in Params p, scoped StrandScratch scratch)
    {
        Span<float> d = scratch.Data;
        Copy(w.PosX, first, n, scratch, CPx); Copy(w.PosY, first, n, scratch, CPy); Copy(w.PosZ, first, n, scratch, CPz);
        Copy(w.VelX, first, n, scratch, CVx); Copy(w.VelY, first, n, scratch, CVy); Copy(w.VelZ, first, n, scratch, CVz);
        Copy(w.InvMass, first, n, scratch, CM);
        Copy(w.RestX, first, n, scratch, CRx); Copy(w.RestY, first, n, scratch, CRy); Copy(w.RestZ, first, n, scratch, CRz);
        Copy(w.ShapePrev, first, n, scratch, CSp); Copy(w.ShapeMid, first, n, scratch, CSm);
        Copy(w.ShapeNext, first, n, scratch, CSn); Copy(w.ShapeBend, first, n, scratch, CSb);
        var v = new StrandView
        {
            Px = ref d[scratch.Offset(CPx)], Py = ref d[scratch.Offset(CPy)], Pz = ref d[scratch.Offset(CPz)],
            Vx = ref d[scratch.Offset(CVx)], Vy = ref d[scratch.Offset(CVy)], Vz = ref d[scratch.Offset(CVz)],
            M = ref d[scratch.Offset(CM)],
            Rx = ref d[scratch.Offset(CRx)], Ry = ref d[scratch.Offset(CRy)], Rz = ref d[scratch.Offset(CRz)],
            Sp = ref d[scratch.Offset(CSp)], Sm = ref d[scratch.Offset(CSm)], Sn = ref d[scratch.Offset(CSn)], Sb = ref d[scratch.Offset(CSb)],
        };
        Strand(ref v, w, first, n, padded: true, zeroSlots: false, in p, scratch);
        d.Slice(scratch.Offset(CVx), n).CopyTo(w.VelX.AsSpan(first, n));
        d.Slice(scratch.Offset(CVy), n).CopyTo(w.VelY.AsSpan(first, n));
        d.Slice(scratch.Offset(CVz), n).CopyTo(w.VelZ.AsSpan(first, n));
    }

    private static void Copy(float[] src, int first, int n, scoped StrandScratch scratch, int field)
    {
        src.AsSpan(first, n).CopyTo(scratch.Data.Slice(scratch.Offset(field), n));
        // Padding lanes hold zeros (finite), never a previous strand's values that could be NaN.
        scratch.Data.Slice(scratch.Offset(field) + n, 2 * Vector<float>.Count).Clear();
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static Vector<int> ValidTriple(Vector<int> lane, int k0, int n)
    {
        var k = lane + new Vector<int>(k0);
        return Vector.GreaterThanOrEqual(k, Vector<int>.One) & Vector.LessThanOrEqual(k, new Vector<int>(n - 2));
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Strand(ref StrandView v, HairWorld w, int first, int n, bool padded, bool zeroSlots, in Params p, scoped StrandScratch scratch)
    {
        int width = Vector<float>.Count;
        ref float g = ref scratch.Data[0];
        if (p.Alpha > 0f && n >= 3)
        {
            bool bent = HasBend(ref v.Sb, n);
            if (bent) BendDirections(ref v, w, first, n, in p, scratch, ref g);
            if (padded)
                for (int k0 = 1; k0 <= n - 2; k0 += width) Triples(ref v, k0, n, bent, in p, scratch, ref g);
            else
            {
                int k0 = 1;
                for (; k0 + width - 1 <= n - 2; k0 += width) Triples(ref v, k0, n, bent, in p, scratch, ref g);
                // Overlapping last chunk: recomputes some triples with identical results.
                if (k0 <= n - 2) Triples(ref v, n - 1 - width, n, bent, in p, scratch, ref g);
            }
        }
        if (padded)
            for (int j0 = 0; j0 < n; j0 += width) Particles(ref v, j0, j0, n, in p, scratch, ref g);
        else if (p.Alpha > 0f)
        {
            // Zero the goal slots no triple fills (before the root's and past the tip's), so the sums need no masks;
            // triples write only slots 1 … n − 2, so these stay zero for the next strand of the same length.
            int o = scratch.Offset(0), st = scratch.Stride;
            for (int c = 0; zeroSlots && c < 3; c++)
            {
                Unsafe.Add(ref g, o + (GPx + c) * st + n - 1) = 0f; Unsafe.Add(ref g, o + (GPx + c) * st + n) = 0f;
                Unsafe.Add(ref g, o + (GMx + c) * st) = 0f; Unsafe.Add(ref g, o + (GMx + c) * st + n - 1) = 0f;
                Unsafe.Add(ref g, o + (GNx + c) * st - 1) = 0f; Unsafe.Add(ref g, o + (GNx + c) * st) = 0f;
            }
            int j0 = 0;
            for (; j0 + width <= n; j0 += width)
            {
                // A chunk ending just short of the tip holds a count-2 particle in an odd lane: the masked version.
                if (j0 != 0 && j0 + width != n && j0 + width - 1 >= n - 2) Particles(ref v, j0, j0, n, in p, scratch, ref g);
                else ParticlesAlongStrand(ref v, j0, j0, n, in p, scratch, ref g);
            }
            // Overlapping last chunk: lanes before j0 were already updated and are masked out.
            if (j0 < n) ParticlesAlongStrand(ref v, n - width, j0, n, in p, scratch, ref g);
        }
        else GlobalOnly(ref v, n, in p, scratch, ref g);
    }

    /// <summary>Velocities of a long strand when only the global stiffness pulls (α = 0); not inlined, like <see cref="ShortStrand"/>.</summary>
    [MethodImpl(MethodImplOptions.NoInlining)]
    private static void GlobalOnly(ref StrandView v, int n, in Params p, scoped StrandScratch scratch, ref float g)
    {
        int width = Vector<float>.Count;
        int j0 = 0;
        for (; j0 + width <= n; j0 += width) Particles(ref v, j0, j0, n, in p, scratch, ref g);
        if (j0 < n) Particles(ref v, n - width, j0, n, in p, scratch, ref g);
    }

    /// <summary>
    /// <see cref="Particles"/> for a strand of at least Width + 2 particles whose unused goal slots are zero: the
    /// goal count is 1, 2, 3, …, 3, 2, 1 along the strand, so the first and last chunk take fixed factor patterns
    /// and the sums need no masks.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void ParticlesAlongStrand(ref StrandView v, int j0, int fresh, int n, in Params p, scoped StrandScratch scratch, ref float g)
    {
        int o = scratch.Offset(0) + j0, st = scratch.Stride;
        var sx = Simd.Ld(ref g, o + 1 + GPx * st) + Simd.Ld(ref g, o + GMx * st) + Simd.Ld(ref g, o - 1 + GNx * st);
        var sy = Simd.Ld(ref g, o + 1 + GPy * st) + Simd.Ld(ref g, o + GMy * st) + Simd.Ld(ref g, o - 1 + GNy * st);
        var sz = Simd.Ld(ref g, o + 1 + GPz * st) + Simd.Ld(ref g, o + GMz * st) + Simd.Ld(ref g, o - 1 + GNz * st);
        var f = j0 == 0 ? p.FirstF : j0 + Vector<float>.Count == n ? p.LastF : p.FThird;
        var dvx = f * sx; var dvy = f * sy; var dvz = f * sz;
        if (p.Beta > 0f)
        {
            var x = Simd.Ld(ref v.Px, j0); var y = Simd.Ld(ref v.Py, j0); var z = Simd.Ld(ref v.Pz, j0);
            p.Head.Point(Simd.Ld(ref v.Rx, j0), Simd.Ld(ref v.Ry, j0), Simd.Ld(ref v.Rz, j0), out var gx, out var gy, out var gz);
            dvx += p.BetaOverH * (gx - x); dvy += p.BetaOverH * (gy - y); dvz += p.BetaOverH * (gz - z);
        }
        var apply = ~Vector.Equals(Simd.Ld(ref v.M, j0), Vector<float>.Zero);
        if (fresh != j0) apply &= Vector.GreaterThanOrEqual(p.Lane + new Vector<int>(j0), new Vector<int>(fresh));
        Simd.St(ref v.Vx, j0, Simd.Sel(apply, Simd.Ld(ref v.Vx, j0) + dvx, Simd.Ld(ref v.Vx, j0)));
        Simd.St(ref v.Vy, j0, Simd.Sel(apply, Simd.Ld(ref v.Vy, j0) + dvy, Simd.Ld(ref v.Vy, j0)));
        Simd.St(ref v.Vz, j0, Simd.Sel(apply, Simd.Ld(ref v.Vz, j0) + dvz, Simd.Ld(ref v.Vz, j0)));
    }

    /// <summary>Does any triple of the strand (1 … n − 2) have a bent rest shape?</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static bool HasBend(ref float bend, int n)
    {
        int width = Vector<float>.Count;
        if (n >= width + 2)
        {
            int k = 1;
            for (; k + width - 1 <= n - 2; k += width)
                if (!Vector.EqualsAll(Simd.Ld(ref bend, k), Vector<float>.Zero)) return true;
            return k <= n - 2 && !Vector.EqualsAll(Simd.Ld(ref bend, n - 1 - width), Vector<float>.Zero);
        }
        for (int k = 1; k <= n - 2; k++)
            if (Unsafe.Add(ref bend, k) != 0f) return true;
        return false;
    }

    /// <summary>
    /// Bend directions of a bent strand's triples, in scalar code: the reference carries a rest-to-current frame
    /// from the root to the tip (<see cref="ShapeMatchSystem.TransportFrame"/>, a chain: each triple needs the
    /// previous frame), so this part cannot run across particles. It runs only for strands with a bent rest shape.
    /// </summary>
    private static void BendDirections(ref StrandView v, HairWorld w, int first, int n, in Params p, scoped StrandScratch scratch, ref float g)
    {
        var frame = p.HeadRotation;
        int o = scratch.Offset(0), st = scratch.Stride;
        for (int k = 1; k <= n - 2; k++)
        {
            frame = ShapeMatchSystem.TransportFrame(w, first + k, frame);
            float bend = Unsafe.Add(ref v.Sb, k);
            var nrm = Vector3.Zero;
            if (bend != 0f)
            {
                TripleAxis(ref v, k, in p, out var e, out var centroid, out float len);
                nrm = BendDirection(ref v, k, frame, e, -centroid, len);
            }
            Unsafe.Add(ref g, o + BNx * st + k) = nrm.X;
            Unsafe.Add(ref g, o + BNy * st + k) = nrm.Y;
            Unsafe.Add(ref g, o + BNz * st + k) = nrm.Z;
        }
    }

    /// <summary>Unit axis of triple k (with the reference's coincident-ends fallback), its centroid relative to the middle particle, and |p[k+1] − p[k−1]|.</summary>
    private static void TripleAxis(ref StrandView v, int k, in Params p, out Vector3 e, out Vector3 centroid, out float len)
    {
        var b = new Vector3(Unsafe.Add(ref v.Px, k), Unsafe.Add(ref v.Py, k), Unsafe.Add(ref v.Pz, k));
        var a = new Vector3(Unsafe.Add(ref v.Px, k - 1), Unsafe.Add(ref v.Py, k - 1), Unsafe.Add(ref v.Pz, k - 1)) - b;
        var c = new Vector3(Unsafe.Add(ref v.Px, k + 1), Unsafe.Add(ref v.Py, k + 1), Unsafe.Add(ref v.Pz, k + 1)) - b;
        centroid = (a + c) * (1f / 3f);
        e = c - a;
        len = e.Length();
        if (len > 1e-12f) { e /= len; return; }
        var restA = new Vector3(Unsafe.Add(ref v.Rx, k - 1), Unsafe.Add(ref v.Ry, k - 1), Unsafe.Add(ref v.Rz, k - 1));
        var restC = new Vector3(Unsafe.Add(ref v.Rx, k + 1), Unsafe.Add(ref v.Ry, k + 1), Unsafe.Add(ref v.Rz, k + 1));
        var axis = p.Head.Direction(restC - restA);
        float al = axis.Length();
        e = al > 1e-12f ? axis / al : -Vector3.UnitY;
    }

    /// <summary>
    /// Float port of <see cref="ShapeMatchSystem.BendDirection"/>: the rest pose's bend direction turned by the
    /// carried frame and made perpendicular to the current axis e; else the current middle offset u; else any
    /// perpendicular. Rest offsets are taken relative to the middle particle (segment-scale rounding).
    /// </summary>
    private static Vector3 BendDirection(ref StrandView v, int k, Quaternion frame, Vector3 e, Vector3 u, float axisLength)
    {
        var rb = new Vector3(Unsafe.Add(ref v.Rx, k), Unsafe.Add(ref v.Ry, k), Unsafe.Add(ref v.Rz, k));
        var ra = new Vector3(Unsafe.Add(ref v.Rx, k - 1), Unsafe.Add(ref v.Ry, k - 1), Unsafe.Add(ref v.Rz, k - 1)) - rb;
        var rc = new Vector3(Unsafe.Add(ref v.Rx, k + 1), Unsafe.Add(ref v.Ry, k + 1), Unsafe.Add(ref v.Rz, k + 1)) - rb;
        var r = rc - ra;
        float rl = r.Length();
        if (rl > 1e-12f) r /= rl;
        var m = -(ra + rc) * (1f / 3f);
        m -= Vector3.Dot(m, r) * r;
        var d = Vector3.Transform(m, frame);
        float restLength = d.Length();
        d -= Vector3.Dot(d, e) * e;
        float dl = d.Length();
        if (dl > 1e-3f * restLength && dl > 1e-15f) return d / dl;
        u -= Vector3.Dot(u, e) * e;
        float ul = u.Length();
        if (ul > 1e-9f * (axisLength + 1e-12f)) return u / ul;
        return RestShape.AnyPerpendicular(e);
    }

    /// <summary>
    /// Goals of triples k0 … k0 + Width − 1 into the scratch goal fields, each stored relative to the particle
    /// it pulls (goal − x). Working in offsets from the middle particle keeps float rounding at the scale of a
    /// segment (~1e-9 m) instead of the scale of world coordinates (~3e-8 m at 0.3 m): the reference computes
    /// in double, and a particle moves exactly onto its goal, so absolute-coordinate rounding would pile up.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Triples(ref StrandView v, int k0, int n, bool bent, in Params p, scoped StrandScratch scratch, ref float g)
    {
        var valid = ValidTriple(p.Lane, k0, n);
        var bx = Simd.Ld(ref v.Px, k0); var by = Simd.Ld(ref v.Py, k0); var bz = Simd.Ld(ref v.Pz, k0);
        var ax = Simd.Ld(ref v.Px, k0 - 1) - bx; var ay = Simd.Ld(ref v.Py, k0 - 1) - by; var az = Simd.Ld(ref v.Pz, k0 - 1) - bz;
        var cx = Simd.Ld(ref v.Px, k0 + 1) - bx; var cy = Simd.Ld(ref v.Py, k0 + 1) - by; var cz = Simd.Ld(ref v.Pz, k0 + 1) - bz;
        // Centroid relative to the middle particle.
        var ox = (ax + cx) * p.Third; var oy = (ay + cy) * p.Third; var oz = (az + cz) * p.Third;
        var ex = cx - ax; var ey = cy - ay; var ez = cz - az;
        var len2 = ex * ex + ey * ey + ez * ez;
        var ok = Vector.GreaterThan(len2, p.LenEps2);
        var inv = Simd.InvSqrt14(Simd.Sel(ok, len2, Vector<float>.One));
        ex *= inv; ey *= inv; ez *= inv;
        var degenerate = valid & ~ok;
        int o = scratch.Offset(0) + k0, st = scratch.Stride;
        var pa = Simd.Ld(ref v.Sp, k0); var pm = Simd.Ld(ref v.Sm, k0); var pn = Simd.Ld(ref v.Sn, k0);
        if (!bent)
        {
            // Straight rest shape (the source's model): goals lie on the axis.
            Simd.St(ref g, o + GPx * st, (ox - ax) + pa * ex); Simd.St(ref g, o + GPy * st, (oy - ay) + pa * ey); Simd.St(ref g, o + GPz * st, (oz - az) + pa * ez);
            Simd.St(ref g, o + GMx * st, ox + pm * ex); Simd.St(ref g, o + GMy * st, oy + pm * ey); Simd.St(ref g, o + GMz * st, oz + pm * ez);
            Simd.St(ref g, o + GNx * st, (ox - cx) + pn * ex); Simd.St(ref g, o + GNy * st, (oy - cy) + pn * ey); Simd.St(ref g, o + GNz * st, (oz - cz) + pn * ez);
        }
        else
        {
            var bend = Simd.Ld(ref v.Sb, k0);
            var nx = Simd.Ld(ref g, o + BNx * st); var ny = Simd.Ld(ref g, o + BNy * st); var nz = Simd.Ld(ref g, o + BNz * st);
            var hb = bend * new Vector<float>(0.5f);
            BentGoals(ref g, o, st, ox, oy, oz, ax, ay, az, cx, cy, cz, ex, ey, ez, pa, pm, pn, bend, hb, nx, ny, nz);
        }
        if (Vector.EqualsAll(degenerate, Vector<int>.Zero)) return;
        for (int l = 0; l < Vector<float>.Count; l++)
            if (degenerate[l] != 0) ScalarTriple(ref v, k0 + l, bent, in p, scratch, ref g);
    }

    private static void BentGoals(ref float g, int o, int st, Vector<float> ox, Vector<float> oy, Vector<float> oz,
        Vector<float> ax, Vector<float> ay, Vector<float> az, Vector<float> cx, Vector<float> cy, Vector<float> cz,
        Vector<float> ex, Vector<float> ey, Vector<float> ez, Vector<float> pa, Vector<float> pm, Vector<float> pn,
        Vector<float> bend, Vector<float> hb, Vector<float> nx, Vector<float> ny, Vector<float> nz)
    {
        Simd.St(ref g, o + GPx * st, (ox - ax) + pa * ex - hb * nx);
        Simd.St(ref g, o + GPy * st, (oy - ay) + pa * ey - hb * ny);
        Simd.St(ref g, o + GPz * st, (oz - az) + pa * ez - hb * nz);
        Simd.St(ref g, o + GMx * st, ox + pm * ex + bend * nx);
        Simd.St(ref g, o + GMy * st, oy + pm * ey + bend * ny);
        Simd.St(ref g, o + GMz * st, oz + pm * ez + bend * nz);
        Simd.St(ref g, o + GNx * st, (ox - cx) + pn * ex - hb * nx);
        Simd.St(ref g, o + GNy * st, (oy - cy) + pn * ey - hb * ny);
        Simd.St(ref g, o + GNz * st, (oz - cz) + pn * ez - hb * nz);
    }

    /// <summary>One triple whose ends coincide: the axis falls back to the rest axis carried by the head, as in the reference.</summary>
    private static void ScalarTriple(ref StrandView v, int k, bool bent, in Params p, scoped StrandScratch scratch, ref float g)
    {
        TripleAxis(ref v, k, in p, out var e, out var o, out _);
        var b = new Vector3(Unsafe.Add(ref v.Px, k), Unsafe.Add(ref v.Py, k), Unsafe.Add(ref v.Pz, k));
        var a = new Vector3(Unsafe.Add(ref v.Px, k - 1), Unsafe.Add(ref v.Py, k - 1), Unsafe.Add(ref v.Pz, k - 1)) - b;
        var c = new Vector3(Unsafe.Add(ref v.Px, k + 1), Unsafe.Add(ref v.Py, k + 1), Unsafe.Add(ref v.Pz, k + 1)) - b;
        float bend = Unsafe.Add(ref v.Sb, k);
        int i = scratch.Offset(0) + k, st = scratch.Stride;
        var nrm = bent ? new Vector3(Unsafe.Add(ref g, i + BNx * st), Unsafe.Add(ref g, i + BNy * st), Unsafe.Add(ref g, i + BNz * st)) : Vector3.Zero;
        var gp = (o - a) + Unsafe.Add(ref v.Sp, k) * e - 0.5f * bend * nrm;
        var gm = o + Unsafe.Add(ref v.Sm, k) * e + bend * nrm;
        var gn = (o - c) + Unsafe.Add(ref v.Sn, k) * e - 0.5f * bend * nrm;
        Unsafe.Add(ref g, i + GPx * st) = gp.X; Unsafe.Add(ref g, i + GPy * st) = gp.Y; Unsafe.Add(ref g, i + GPz * st) = gp.Z;
        Unsafe.Add(ref g, i + GMx * st) = gm.X; Unsafe.Add(ref g, i + GMy * st) = gm.Y; Unsafe.Add(ref g, i + GMz * st) = gm.Z;
        Unsafe.Add(ref g, i + GNx * st) = gn.X; Unsafe.Add(ref g, i + GNy * st) = gn.Y; Unsafe.Add(ref g, i + GNz * st) = gn.Z;
    }

    /// <summary>Velocity change of particles j0 … j0 + Width − 1 (lanes below <paramref name="fresh"/> are left alone).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Particles(ref StrandView v, int j0, int fresh, int n, in Params p, scoped StrandScratch scratch, ref float g)
    {
        var dvx = Vector<float>.Zero; var dvy = Vector<float>.Zero; var dvz = Vector<float>.Zero;
        if (p.Alpha > 0f && n >= 3)
        {
            var fromNext = ValidTriple(p.Lane, j0 + 1, n); // triple j+1 gave particle j its "prev" goal
            var fromSelf = ValidTriple(p.Lane, j0, n);
            var fromPrev = ValidTriple(p.Lane, j0 - 1, n);
            int o = scratch.Offset(0) + j0, st = scratch.Stride;
            var sx = Simd.Sel(fromNext, Simd.Ld(ref g, o + 1 + GPx * st), default) + Simd.Sel(fromSelf, Simd.Ld(ref g, o + GMx * st), default) + Simd.Sel(fromPrev, Simd.Ld(ref g, o - 1 + GNx * st), default);
            var sy = Simd.Sel(fromNext, Simd.Ld(ref g, o + 1 + GPy * st), default) + Simd.Sel(fromSelf, Simd.Ld(ref g, o + GMy * st), default) + Simd.Sel(fromPrev, Simd.Ld(ref g, o - 1 + GNy * st), default);
            var sz = Simd.Sel(fromNext, Simd.Ld(ref g, o + 1 + GPz * st), default) + Simd.Sel(fromSelf, Simd.Ld(ref g, o + GMz * st), default) + Simd.Sel(fromPrev, Simd.Ld(ref g, o - 1 + GNz * st), default);
            // Goals are already relative to the particle: the mean offset (sum / count, count 0 … 3) is the pull.
            var count = -(fromNext + fromSelf + fromPrev);
            var f = Simd.Sel(Vector.Equals(count, p.Three), p.FThird,
                    Simd.Sel(Vector.Equals(count, p.Two), p.FHalf,
                    Simd.Sel(Vector.Equals(count, Vector<int>.One), p.F, Vector<float>.Zero)));
            dvx = f * sx; dvy = f * sy; dvz = f * sz;
        }
        if (p.Beta > 0f)
        {
            var x = Simd.Ld(ref v.Px, j0); var y = Simd.Ld(ref v.Py, j0); var z = Simd.Ld(ref v.Pz, j0);
            p.Head.Point(Simd.Ld(ref v.Rx, j0), Simd.Ld(ref v.Ry, j0), Simd.Ld(ref v.Rz, j0), out var gx, out var gy, out var gz);
            dvx += p.BetaOverH * (gx - x); dvy += p.BetaOverH * (gy - y); dvz += p.BetaOverH * (gz - z);
        }
        var apply = ~Vector.Equals(Simd.Ld(ref v.M, j0), Vector<float>.Zero)
                    & Vector.GreaterThanOrEqual(p.Lane + new Vector<int>(j0), new Vector<int>(fresh));
        Simd.St(ref v.Vx, j0, Simd.Sel(apply, Simd.Ld(ref v.Vx, j0) + dvx, Simd.Ld(ref v.Vx, j0)));
        Simd.St(ref v.Vy, j0, Simd.Sel(apply, Simd.Ld(ref v.Vy, j0) + dvy, Simd.Ld(ref v.Vy, j0)));
        Simd.St(ref v.Vz, j0, Simd.Sel(apply, Simd.Ld(ref v.Vz, j0) + dvz, Simd.Ld(ref v.Vz, j0)));
    }
}
