using System.Numerics;
using System.Runtime.CompilerServices;
using V = System.Numerics.Vector<float>;

namespace HairSim.Fast;

/// <summary>
/// The sweep over a tile of two Vector&lt;float&gt; chains per row. The sweep is latency-bound (each row waits for
/// the last row's position and frame: square roots, divisions, two quaternion normalisations), so two independent
/// vectors of strands advance side by side. The row is written once, in the sweep's own loop: as a helper it was
/// too large for the JIT to inline, and a call per row kept every chain's state in memory behind references.
/// </summary>
public sealed partial class FastBendSystem
{
    /// <summary>Sweep constants broadcast to Vector&lt;float&gt; lanes.</summary>
    private readonly struct Consts
    {
        public readonly V H, InvH, Reaction, FallX, FallY, FallZ, Eps, Flip, MaxSpeed, MaxSpeedSq;

        public Consts(in SweepParams p)
        {
            H = new(p.H); InvH = new(p.InvH); Reaction = new(p.Reaction); MaxSpeed = new(p.MaxSpeed); MaxSpeedSq = new(p.MaxSpeed * p.MaxSpeed);
            FallX = new(p.FallX); FallY = new(p.FallY); FallZ = new(p.FallZ);
            Eps = new(1e-6f); Flip = new(-0.9999f);
        }
    }

    // Slots of a chain's state carried from row to row (each Vector<float>.Count wide, one per half of the tile row):
    // the frame q, the parent's direction and turn, and its correction Δ (its kick waits for this row's correction).
    // What can be read back from the tile instead is: the parent's position (stored there in its own row), its move
    // so far (h·v + Δ, with v not yet kicked) and whether it is free (its inverse mass). Fewer stores per row made
    // the sweep measurably faster (the same bits).
    private const int Sqx = 0, Sqy = 1, Sqz = 2, Sqw = 3, Sdx = 4, Sdy = 5, Sdz = 6, Scx = 7, Scy = 8, Scz = 9,
        SDx = 10, SDy = 11, SDz = 12, Slots = 13;

    /// <summary>
    /// Root to tip over rows 1 … rows−1, each row's velocity kick applied one row later (it needs the child's
    /// correction): v += (Δ_k − s·(Δ_{k+1} + fall of a free k+1)) / h for free particles (see BendSystem).
    /// The halves of a row are independent chains, so the CPU overlaps their latencies; each carries its state in
    /// a small stack buffer between rows (too much state for the registers anyway, and one loop body for both).
    /// </summary>
    [SkipLocalsInit]
    private static void Sweep(ref float d, ref float rest, int rows, in SweepParams p)
    {
        int width = V.Count, lanes = p.Lanes;
        var c = new Consts(in p);
        var one = V.One;
        var zero = V.Zero;
        Span<float> stateSpan = stackalloc float[Slots * lanes];
        ref float s = ref stateSpan[0];
        for (int h = 0; h < lanes; h += width)
        {
            Simd.St(ref s, Sqx * lanes + h, new V(p.Qx)); Simd.St(ref s, Sqy * lanes + h, new V(p.Qy));
            Simd.St(ref s, Sqz * lanes + h, new V(p.Qz)); Simd.St(ref s, Sqw * lanes + h, new V(p.Qw));
            // Direction, turn and correction start at zero. The root is never kicked: it follows the head.
            for (int slot = Sdx; slot < Slots; slot++) Simd.St(ref s, slot * lanes + h, zero);
        }
        for (int k = 1; k < rows; k++)
        {
            for (int h = 0; h < lanes; h += width)
            {
                int r = k * lanes + h;
                var qx = Simd.Ld(ref s, Sqx * lanes + h); var qy = Simd.Ld(ref s, Sqy * lanes + h); var qz = Simd.Ld(ref s, Sqz * lanes + h); var qw = Simd.Ld(ref s, Sqw * lanes + h);
                var px = Simd.Ld(ref d, p.Ox + r - lanes); var py = Simd.Ld(ref d, p.Oy + r - lanes); var pz = Simd.Ld(ref d, p.Oz + r - lanes);
                var x = Simd.Ld(ref d, p.Ox + r); var y = Simd.Ld(ref d, p.Oy + r); var z = Simd.Ld(ref d, p.Oz + r);
                var free = ~Vector.Equals(Simd.Ld(ref d, p.Om + r), zero);
                var rl = Simd.Ld(ref d, p.Ol + r);
                var rx = Simd.Ld(ref rest, p.Orx + r); var ry = Simd.Ld(ref rest, p.Ory + r); var rz = Simd.Ld(ref rest, p.Orz + r);
                var ex = x - px; var ey = y - py; var ez = z - pz;
                var len = Vector.SquareRoot(ex * ex + ey * ey + ez * ez);
                var hasLen = Vector.GreaterThan(len, zero);
                var inv = Simd.Sel(hasLen, one / Simd.Sel(hasLen, len, one), zero);
                var ux0 = ex * inv; var uy0 = ey * inv; var uz0 = ez * inv;
                // Target: the rest direction turned by the frame carried from the root (v' = v + 2w(q×v) + 2q×(q×v)).
                // With c = 2q×v (the doubling by adds: the sweep is bound by its multiplies): v' = v + w·c + q×c.
                var q2x = qx + qx; var q2y = qy + qy; var q2z = qz + qz;
                var cx = q2y * rz - q2z * ry; var cy = q2z * rx - q2x * rz; var cz = q2x * ry - q2y * rx;
                var tx = rx + qw * cx + (qy * cz - qz * cy); var ty = ry + qw * cy + (qz * cx - qx * cz); var tz = rz + qw * cz + (qx * cy - qy * cx);
                // A rest direction to turn (any component non-zero, by bits: no multiplies).
                var restOk = ~Vector.AsVectorInt32(Vector.Equals((Vector.AsVectorUInt32(rx) | Vector.AsVectorUInt32(ry) | Vector.AsVectorUInt32(rz)) & new Vector<uint>(0x7fffffffu), Vector<uint>.Zero));
                tx = Simd.Sel(restOk, tx, Simd.Sel(hasLen, ux0, zero));
                ty = Simd.Sel(restOk, ty, Simd.Sel(hasLen, uy0, new V(-1f)));
                tz = Simd.Sel(restOk, tz, Simd.Sel(hasLen, uz0, zero));
                var okLen = Vector.GreaterThan(len, c.Eps * rl) & hasLen;
                var dx = Simd.Sel(okLen, ux0, tx); var dy = Simd.Sel(okLen, uy0, ty); var dz = Simd.Sel(okLen, uz0, tz);
                // How far this segment turned since the substep's start (see BendSystem).
                var hvx = c.H * Simd.Ld(ref d, p.Ovx + r); var hvy = c.H * Simd.Ld(ref d, p.Ovy + r); var hvz = c.H * Simd.Ld(ref d, p.Ovz + r);
                var ux = hvx - (c.H * Simd.Ld(ref d, p.Ovx + r - lanes) + Simd.Ld(ref s, SDx * lanes + h));
                var uy = hvy - (c.H * Simd.Ld(ref d, p.Ovy + r - lanes) + Simd.Ld(ref s, SDy * lanes + h));
                var uz = hvz - (c.H * Simd.Ld(ref d, p.Ovz + r - lanes) + Simd.Ld(ref s, SDz * lanes + h));
                var along = ux * dx + uy * dy + uz * dz;
                var tcx = (ux - along * dx) * inv; var tcy = (uy - along * dy) * inv; var tcz = (uz - along * dz) * inv;
                // Target turned with the parent: Δt = (d_p × c_p) × t.
                var pdx = Simd.Ld(ref s, Sdx * lanes + h); var pdy = Simd.Ld(ref s, Sdy * lanes + h); var pdz = Simd.Ld(ref s, Sdz * lanes + h);
                var pcx = Simd.Ld(ref s, Scx * lanes + h); var pcy = Simd.Ld(ref s, Scy * lanes + h); var pcz = Simd.Ld(ref s, Scz * lanes + h);
                var wx = pdy * pcz - pdz * pcy; var wy = pdz * pcx - pdx * pcz; var wz = pdx * pcy - pdy * pcx;
                var ttx = wy * tz - wz * ty; var tty = wz * tx - wx * tz; var ttz = wx * ty - wy * tx;
                // The joint's spring and dashpot shares, cached per strand for this h (see CacheShares).
                var a = Simd.Ld(ref rest, p.Oa + r); var b = Simd.Ld(ref rest, p.Ob + r);
                var ox = dx - tx; var oy = dy - ty; var oz = dz - tz;
                var sx = ox - (tcx - ttx); var sy = oy - (tcy - tty); var sz = oz - (tcz - ttz);
                var mx = tx + a * ox + b * sx; var my = ty + a * oy + b * sy; var mz = tz + a * oz + b * sz;
                var ml = Vector.SquareRoot(mx * mx + my * my + mz * mz);
                var mOk = Vector.GreaterThan(ml, c.Eps);
                var invM = one / Simd.Sel(mOk, ml, one);
                var ndx = Simd.Sel(mOk, mx * invM, tx); var ndy = Simd.Sel(mOk, my * invM, ty); var ndz = Simd.Sel(mOk, mz * invM, tz);
                dx = Simd.Sel(free, ndx, dx); dy = Simd.Sel(free, ndy, dy); dz = Simd.Sel(free, ndz, dz);
                var nx = px + dx * rl; var ny = py + dy * rl; var nz = pz + dz * rl;
                var cdx = Simd.Sel(free, nx - x, zero); var cdy = Simd.Sel(free, ny - y, zero); var cdz = Simd.Sel(free, nz - z, zero);
                x += cdx; y += cdy; z += cdz;
                Simd.St(ref d, p.Ox + r, x); Simd.St(ref d, p.Oy + r, y); Simd.St(ref d, p.Oz + r, z);
                // The row above takes its kick now that this row's correction is known.
                Kick(ref d, in p, in c, r - lanes, k == 1 ? Vector<int>.Zero : ~Vector.Equals(Simd.Ld(ref d, p.Om + r - lanes), zero),
                    Simd.Ld(ref s, SDx * lanes + h), Simd.Ld(ref s, SDy * lanes + h), Simd.Ld(ref s, SDz * lanes + h),
                    cdx + Simd.Sel(free, c.FallX, zero), cdy + Simd.Sel(free, c.FallY, zero), cdz + Simd.Sel(free, c.FallZ, zero));
                Simd.St(ref s, SDx * lanes + h, cdx); Simd.St(ref s, SDy * lanes + h, cdy); Simd.St(ref s, SDz * lanes + h, cdz);
                // This segment's turn over the substep so far, for its child.
                ux += cdx; uy += cdy; uz += cdz;
                along = ux * dx + uy * dy + uz * dz;
                Simd.St(ref s, Scx * lanes + h, (ux - along * dx) * inv); Simd.St(ref s, Scy * lanes + h, (uy - along * dy) * inv);
                Simd.St(ref s, Scz * lanes + h, (uz - along * dz) * inv);
                Simd.St(ref s, Sdx * lanes + h, dx); Simd.St(ref s, Sdy * lanes + h, dy); Simd.St(ref s, Sdz * lanes + h, dz);
                // Frame: the smallest rotation taking t onto d, then the frame so far (identity if they are opposite).
                var dot = tx * dx + ty * dy + tz * dz;
                var fx = ty * dz - tz * dy; var fy = tz * dx - tx * dz; var fz = tx * dy - ty * dx; var fw = one + dot;
                var flip = Vector.LessThan(dot, c.Flip);
                fx = Simd.Sel(flip, zero, fx); fy = Simd.Sel(flip, zero, fy); fz = Simd.Sel(flip, zero, fz); fw = Simd.Sel(flip, one, fw);
                // f normalised by its own length (not 2(1 + t·d), which amplifies any error in |t| near a flip), and
                // f∘q left as it is: a product of unit quaternions, and q is rebuilt from the head every substep.
                var fInv = one / Vector.SquareRoot(fx * fx + fy * fy + fz * fz + fw * fw);
                fx *= fInv; fy *= fInv; fz *= fInv; fw *= fInv;
                var nqx = fw * qx + fx * qw + fy * qz - fz * qy;
                var nqy = fw * qy - fx * qz + fy * qw + fz * qx;
                var nqz = fw * qz + fx * qy - fy * qx + fz * qw;
                var nqw = fw * qw - fx * qx - fy * qy - fz * qz;
                Simd.St(ref s, Sqx * lanes + h, nqx); Simd.St(ref s, Sqy * lanes + h, nqy);
                Simd.St(ref s, Sqz * lanes + h, nqz); Simd.St(ref s, Sqw * lanes + h, nqw);
            }
        }
        if (rows < 2) return;
        for (int h = 0; h < lanes; h += width)
            Kick(ref d, in p, in c, (rows - 1) * lanes + h, ~Vector.Equals(Simd.Ld(ref d, p.Om + (rows - 1) * lanes + h), zero),
                Simd.Ld(ref s, SDx * lanes + h), Simd.Ld(ref s, SDy * lanes + h), Simd.Ld(ref s, SDz * lanes + h), zero, zero, zero);
    }

    /// <summary>v += (Δ − s·next) / h on the free lanes of row r, then clamped to the speed limit (the sweep writes velocities last).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Kick(ref float d, in SweepParams p, in Consts c, int r, Vector<int> free, V dx, V dy, V dz, V nx, V ny, V nz)
    {
        var vx = Simd.Ld(ref d, p.Ovx + r); var vy = Simd.Ld(ref d, p.Ovy + r); var vz = Simd.Ld(ref d, p.Ovz + r);
        var wx = vx + (dx - c.Reaction * nx) * c.InvH; var wy = vy + (dy - c.Reaction * ny) * c.InvH; var wz = vz + (dz - c.Reaction * nz) * c.InvH;
        // Squared speeds compared, the root taken only where a lane is over the limit.
        var speedSq = wx * wx + wy * wy + wz * wz;
        var over = Vector.GreaterThan(speedSq, c.MaxSpeedSq);
        if (!Vector.EqualsAll(over, Vector<int>.Zero))
        {
            var f = c.MaxSpeed / Simd.Sel(over, Vector.SquareRoot(speedSq), V.One);
            wx = Simd.Sel(over, wx * f, wx); wy = Simd.Sel(over, wy * f, wy); wz = Simd.Sel(over, wz * f, wz);
        }
        Simd.St(ref d, p.Ovx + r, Simd.Sel(free, wx, vx));
        Simd.St(ref d, p.Ovy + r, Simd.Sel(free, wy, vy));
        Simd.St(ref d, p.Ovz + r, Simd.Sel(free, wz, vz));
    }
}
