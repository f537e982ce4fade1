using System.Numerics;
using System.Runtime.CompilerServices;

namespace HairSim.Fast;

/// <summary>
/// Fast <see cref="BendSystem"/> in float. The sweep is a chain along each strand (segment k's target needs the
/// frame carried through k−1), so it is vectorised across strands: Vector&lt;float&gt;.Count strands are put into a
/// stack tile (row k = particle k of each strand), swept root to tip together, and written back. Per strand the rest
/// directions and joint time constants are cached until the world is edited or Sag changes. Same arithmetic as the
/// reference, in float; lanes past a strand's live count, and padding lanes, are masked out (InvMass 0).
/// </summary>
public sealed class FastBendSystem : IHairSystem
{
    public string Name => BendSystem.SystemName;
    public SystemPhase Phase => SystemPhase.Substep;

    private const int TX = 0, TY = 1, TZ = 2, TVx = 3, TVy = 4, TVz = 5, TM = 6, TL = 7, TRx = 8, TRy = 9, TRz = 10, TT2 = 11,
        TDx = 12, TDy = 13, TDz = 14, FieldCount = 15;

    private readonly int _maxCapacity;
    // Per particle k of a strand: the rest unit direction of segment k (k−1 → k, head space; 0 if degenerate) and the
    // T² of the joint that holds it (joint k−1), cached per strand until the world's next edit or a new Sag.
    private readonly float[] _restX, _restY, _restZ, _jointT2, _profile;
    private readonly long[] _profileAt;
    private readonly float[] _profileSag;

    public FastBendSystem(HairWorld world)
    {
        _maxCapacity = world.MaxStrandCapacity;
        int n = world.ParticleCount;
        _restX = new float[n]; _restY = new float[n]; _restZ = new float[n]; _jointT2 = new float[n]; _profile = new float[n];
        _profileAt = new long[world.StrandCount];
        _profileSag = new float[world.StrandCount];
    }

    private void EnsureCache(HairWorld w, int s, float sag)
    {
        long stamp = w.EditStamp + 1L;
        if (_profileAt[s] == stamp && _profileSag[s] == sag) return;
        BendProfile.Compute(w, s, sag, _profile);
        int first = w.StrandFirst[s], cap = w.StrandCapacity[s];
        for (int k = 0; k < cap; k++)
        {
            int i = first + k;
            _jointT2[i] = k == 0 ? 0f : _profile[i - 1];
            if (k == 0) { _restX[i] = _restY[i] = _restZ[i] = 0f; continue; }
            double rx = w.RestX[i] - w.RestX[i - 1], ry = w.RestY[i] - w.RestY[i - 1], rz = w.RestZ[i] - w.RestZ[i - 1];
            double rl = Math.Sqrt(rx * rx + ry * ry + rz * rz);
            if (rl > 0) { _restX[i] = (float)(rx / rl); _restY[i] = (float)(ry / rl); _restZ[i] = (float)(rz / rl); }
            else _restX[i] = _restY[i] = _restZ[i] = 0f;
        }
        _profileAt[s] = stamp; _profileSag[s] = sag;
    }

    [SkipLocalsInit]
    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var w = scene.World;
        var st = ctx.Settings;
        if (st.Bend != BendModel.RestShape) return;
        int lanes = Vector<float>.Count;
        for (int s = begin; s < end; s++) EnsureCache(w, s, st.Sag);
        int size = StrandScratch.Size(_maxCapacity * lanes, FieldCount);
        var t = new StrandScratch(size <= StrandScratch.StackFloats ? stackalloc float[size] : StrandScratch.Heap(size), _maxCapacity * lanes);
        var p = new SweepParams(ctx, substep, t);
        Span<int> firsts = stackalloc int[lanes];
        Span<int> counts = stackalloc int[lanes];
        for (int s0 = begin; s0 < end; s0 += lanes)
        {
            int used = Math.Min(lanes, end - s0), rows = 0;
            for (int l = 0; l < lanes; l++)
            {
                firsts[l] = l < used ? w.StrandFirst[s0 + l] : 0;
                counts[l] = l < used ? w.StrandParticleCount[s0 + l] : 0;
                rows = Math.Max(rows, counts[l]);
            }
            Gather(w, t, firsts, counts, rows);
            Sweep(t, rows, in p);
            Scatter(w, t, firsts, counts);
        }
    }

    private void Gather(HairWorld w, scoped StrandScratch t, ReadOnlySpan<int> firsts, ReadOnlySpan<int> counts, int rows)
    {
        int lanes = firsts.Length;
        Span<float> d = t.Data;
        // Masked cells: InvMass 0 (never moved) at finite zeros; their results are never written back.
        for (int f = 0; f < FieldCount; f++) d.Slice(t.Offset(f), rows * lanes).Clear();
        ReadOnlySpan<float[]> src = [w.PosX, w.PosY, w.PosZ, w.VelX, w.VelY, w.VelZ, w.InvMass, w.RestLength, _restX, _restY, _restZ, _jointT2];
        for (int f = 0; f < src.Length; f++)
        {
            var a = src[f];
            int o = t.Offset(f);
            for (int l = 0; l < lanes; l++)
            {
                int first = firsts[l], n = counts[l];
                for (int k = 0; k < n; k++) d[o + k * lanes + l] = a[first + k];
            }
        }
    }

    private static void Scatter(HairWorld w, scoped StrandScratch t, ReadOnlySpan<int> firsts, ReadOnlySpan<int> counts)
    {
        int lanes = firsts.Length;
        Span<float> d = t.Data;
        int ox = t.Offset(TX), oy = t.Offset(TY), oz = t.Offset(TZ), ovx = t.Offset(TVx), ovy = t.Offset(TVy), ovz = t.Offset(TVz);
        for (int l = 0; l < lanes; l++)
        {
            int first = firsts[l], n = counts[l];
            for (int k = 1; k < n; k++)
            {
                int i = first + k, r = k * lanes + l;
                w.PosX[i] = d[ox + r]; w.PosY[i] = d[oy + r]; w.PosZ[i] = d[oz + r];
                w.VelX[i] = d[ovx + r]; w.VelY[i] = d[ovy + r]; w.VelZ[i] = d[ovz + r];
            }
        }
    }

    private readonly struct SweepParams
    {
        public readonly Vector<float> H, HH, Zeta2H, InvH, Reaction, FallX, FallY, FallZ;
        public readonly float Qx, Qy, Qz, Qw;
        public readonly int Ox, Oy, Oz, Ovx, Ovy, Ovz, Om, Ol, Orx, Ory, Orz, Ot2, Odx, Ody, Odz;

        public SweepParams(FrameContext ctx, int substep, scoped StrandScratch t)
        {
            var st = ctx.Settings;
            float h = ctx.H;
            H = new(h); HH = new(h * h); Zeta2H = new(2f * st.BendDamping * h); InvH = new(1f / h);
            Reaction = new((float)BendSystem.ReactionShare);
            float kappa = MathF.Max(0f, 1f - st.Damping * h);
            FallX = new(st.Gravity.X * h * h * kappa); FallY = new(st.Gravity.Y * h * h * kappa); FallZ = new(st.Gravity.Z * h * h * kappa);
            var q = ctx.HeadAt(substep).Rotation;
            Qx = q.X; Qy = q.Y; Qz = q.Z; Qw = q.W;
            Ox = t.Offset(TX); Oy = t.Offset(TY); Oz = t.Offset(TZ); Ovx = t.Offset(TVx); Ovy = t.Offset(TVy); Ovz = t.Offset(TVz);
            Om = t.Offset(TM); Ol = t.Offset(TL); Orx = t.Offset(TRx); Ory = t.Offset(TRy); Orz = t.Offset(TRz); Ot2 = t.Offset(TT2);
            Odx = t.Offset(TDx); Ody = t.Offset(TDy); Odz = t.Offset(TDz);
        }
    }

    private static void Sweep(scoped StrandScratch tile, int rows, in SweepParams p)
    {
        int lanes = Vector<float>.Count;
        ref float d = ref tile.Data[0];
        var one = Vector<float>.One;
        var zero = Vector<float>.Zero;
        var qx = new Vector<float>(p.Qx); var qy = new Vector<float>(p.Qy); var qz = new Vector<float>(p.Qz); var qw = new Vector<float>(p.Qw);
        var px = Simd.Ld(ref d, p.Ox); var py = Simd.Ld(ref d, p.Oy); var pz = Simd.Ld(ref d, p.Oz);
        // Parent's previous move h·v + Δ, direction and turn; the root's parent is the head, still within a substep.
        var pux = p.H * Simd.Ld(ref d, p.Ovx); var puy = p.H * Simd.Ld(ref d, p.Ovy); var puz = p.H * Simd.Ld(ref d, p.Ovz);
        Vector<float> pdx = zero, pdy = zero, pdz = zero, pcx = zero, pcy = zero, pcz = zero;
        Simd.St(ref d, p.Odx, zero); Simd.St(ref d, p.Ody, zero); Simd.St(ref d, p.Odz, zero);
        var eps = new Vector<float>(1e-6f);
        var down = new Vector<float>(-1f);
        for (int k = 1; k < rows; k++)
        {
            int r = k * lanes;
            var x = Simd.Ld(ref d, p.Ox + r); var y = Simd.Ld(ref d, p.Oy + r); var z = Simd.Ld(ref d, p.Oz + r);
            var free = ~Vector.Equals(Simd.Ld(ref d, p.Om + r), zero);
            var rl = Simd.Ld(ref d, p.Ol + r);
            var rx = Simd.Ld(ref d, p.Orx + r); var ry = Simd.Ld(ref d, p.Ory + r); var rz = Simd.Ld(ref d, p.Orz + r);
            var ex = x - px; var ey = y - py; var ez = z - pz;
            var len = Vector.SquareRoot(ex * ex + ey * ey + ez * ez);
            var hasLen = Vector.GreaterThan(len, zero);
            var inv = Simd.Sel(hasLen, one / Simd.Sel(hasLen, len, one), zero);
            // Target: the rest direction turned by the frame carried from the root (v' = v + 2w(q×v) + 2q×(q×v)).
            var cx = qy * rz - qz * ry; var cy = qz * rx - qx * rz; var cz = qx * ry - qy * rx;
            var ccx = qy * cz - qz * cy; var ccy = qz * cx - qx * cz; var ccz = qx * cy - qy * cx;
            var tx = rx + (qw * cx + ccx) * 2f; var ty = ry + (qw * cy + ccy) * 2f; var tz = rz + (qw * cz + ccz) * 2f;
            var restOk = Vector.GreaterThan(rx * rx + ry * ry + rz * rz, zero);
            tx = Simd.Sel(restOk, tx, Simd.Sel(hasLen, ex * inv, zero));
            ty = Simd.Sel(restOk, ty, Simd.Sel(hasLen, ey * inv, down));
            tz = Simd.Sel(restOk, tz, Simd.Sel(hasLen, ez * inv, zero));
            var okLen = Vector.GreaterThan(len, eps * rl) & hasLen;
            var dx = Simd.Sel(okLen, ex * inv, tx); var dy = Simd.Sel(okLen, ey * inv, ty); var dz = Simd.Sel(okLen, ez * inv, tz);
            // How far this segment turned since the substep's start (see BendSystem).
            var ux = p.H * Simd.Ld(ref d, p.Ovx + r) - pux; var uy = p.H * Simd.Ld(ref d, p.Ovy + r) - puy; var uz = p.H * Simd.Ld(ref d, p.Ovz + r) - puz;
            var along = ux * dx + uy * dy + uz * dz;
            var tcx = (ux - along * dx) * inv; var tcy = (uy - along * dy) * inv; var tcz = (uz - along * dz) * inv;
            // Target turned with the parent: Δt = (d_p × c_p) × t.
            var wx = pdy * pcz - pdz * pcy; var wy = pdz * pcx - pdx * pcz; var wz = pdx * pcy - pdy * pcx;
            var ttx = wy * tz - wz * ty; var tty = wz * tx - wx * tz; var ttz = wx * ty - wy * tx;
            var t2 = Simd.Ld(ref d, p.Ot2 + r);
            var tt = Vector.SquareRoot(t2);
            var den = t2 + p.Zeta2H * tt + p.HH;
            var a = t2 / den; var b = p.Zeta2H * tt / den;
            var ox = dx - tx; var oy = dy - ty; var oz = dz - tz;
            var sx = ox - (tcx - ttx); var sy = oy - (tcy - tty); var sz = oz - (tcz - ttz);
            var mx = tx + a * ox + b * sx; var my = ty + a * oy + b * sy; var mz = tz + a * oz + b * sz;
            var ml = Vector.SquareRoot(mx * mx + my * my + mz * mz);
            var mOk = Vector.GreaterThan(ml, eps);
            var invM = one / Simd.Sel(mOk, ml, one);
            var ndx = Simd.Sel(mOk, mx * invM, tx); var ndy = Simd.Sel(mOk, my * invM, ty); var ndz = Simd.Sel(mOk, mz * invM, tz);
            dx = Simd.Sel(free, ndx, dx); dy = Simd.Sel(free, ndy, dy); dz = Simd.Sel(free, ndz, dz);
            var nx = px + dx * rl; var ny = py + dy * rl; var nz = pz + dz * rl;
            var cdx = Simd.Sel(free, nx - x, zero); var cdy = Simd.Sel(free, ny - y, zero); var cdz = Simd.Sel(free, nz - z, zero);
            x += cdx; y += cdy; z += cdz;
            Simd.St(ref d, p.Ox + r, x); Simd.St(ref d, p.Oy + r, y); Simd.St(ref d, p.Oz + r, z);
            Simd.St(ref d, p.Odx + r, cdx); Simd.St(ref d, p.Ody + r, cdy); Simd.St(ref d, p.Odz + r, cdz);
            // This segment's turn over the substep so far, for its child.
            ux += cdx; uy += cdy; uz += cdz;
            along = ux * dx + uy * dy + uz * dz;
            pcx = (ux - along * dx) * inv; pcy = (uy - along * dy) * inv; pcz = (uz - along * dz) * inv;
            pdx = dx; pdy = dy; pdz = dz;
            pux = p.H * Simd.Ld(ref d, p.Ovx + r) + cdx; puy = p.H * Simd.Ld(ref d, p.Ovy + r) + cdy; puz = p.H * Simd.Ld(ref d, p.Ovz + r) + cdz;
            px = x; py = y; pz = z;
            // Frame: the smallest rotation taking t onto d, then the frame so far (identity if they are opposite).
            var dot = tx * dx + ty * dy + tz * dz;
            var fx = ty * dz - tz * dy; var fy = tz * dx - tx * dz; var fz = tx * dy - ty * dx; var fw = one + dot;
            var flip = Vector.LessThan(dot, new Vector<float>(-0.9999f));
            fx = Simd.Sel(flip, zero, fx); fy = Simd.Sel(flip, zero, fy); fz = Simd.Sel(flip, zero, fz); fw = Simd.Sel(flip, one, fw);
            Normalize(ref fx, ref fy, ref fz, ref fw);
            var nqx = fw * qx + fx * qw + fy * qz - fz * qy;
            var nqy = fw * qy - fx * qz + fy * qw + fz * qx;
            var nqz = fw * qz + fx * qy - fy * qx + fz * qw;
            var nqw = fw * qw - fx * qx - fy * qy - fz * qz;
            Normalize(ref nqx, ref nqy, ref nqz, ref nqw);
            qx = nqx; qy = nqy; qz = nqz; qw = nqw;
        }
        // Velocities: v += (Δ_k − s·(Δ_{k+1} + fall of a free k+1)) / h for free particles (see BendSystem).
        for (int k = 1; k < rows; k++)
        {
            int r = k * lanes;
            var free = ~Vector.Equals(Simd.Ld(ref d, p.Om + r), zero);
            Vector<float> nx = zero, ny = zero, nz = zero;
            if (k + 1 < rows)
            {
                int rn = r + lanes;
                var nextFree = ~Vector.Equals(Simd.Ld(ref d, p.Om + rn), zero);
                nx = Simd.Ld(ref d, p.Odx + rn) + Simd.Sel(nextFree, p.FallX, zero);
                ny = Simd.Ld(ref d, p.Ody + rn) + Simd.Sel(nextFree, p.FallY, zero);
                nz = Simd.Ld(ref d, p.Odz + rn) + Simd.Sel(nextFree, p.FallZ, zero);
            }
            var vx = Simd.Ld(ref d, p.Ovx + r) + (Simd.Ld(ref d, p.Odx + r) - p.Reaction * nx) * p.InvH;
            var vy = Simd.Ld(ref d, p.Ovy + r) + (Simd.Ld(ref d, p.Ody + r) - p.Reaction * ny) * p.InvH;
            var vz = Simd.Ld(ref d, p.Ovz + r) + (Simd.Ld(ref d, p.Odz + r) - p.Reaction * nz) * p.InvH;
            Simd.St(ref d, p.Ovx + r, Simd.Sel(free, vx, Simd.Ld(ref d, p.Ovx + r)));
            Simd.St(ref d, p.Ovy + r, Simd.Sel(free, vy, Simd.Ld(ref d, p.Ovy + r)));
            Simd.St(ref d, p.Ovz + r, Simd.Sel(free, vz, Simd.Ld(ref d, p.Ovz + r)));
        }
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Normalize(ref Vector<float> x, ref Vector<float> y, ref Vector<float> z, ref Vector<float> w)
    {
        var inv = Vector<float>.One / Vector.SquareRoot(x * x + y * y + z * z + w * w);
        x *= inv; y *= inv; z *= inv; w *= inv;
    }
}
