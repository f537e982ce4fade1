using System.Diagnostics;
using System.Numerics;
using System.Runtime.CompilerServices;
using V = System.Numerics.Vector<float>;

namespace HairSim.Fast;

/// <summary>
/// The sweep over a tile of two Vector&lt;float&gt; chains per row. The sweep is latency-bound (each row waits for
/// the last row's position and frame: square roots and divisions), so two independent
/// vectors of strands advance side by side. The row is written once, in the sweep's own loop: as a helper it was
/// too large for the JIT to inline, and a call per row kept every chain's state in memory behind references.
/// </summary>
public sealed partial class FastBendSystem
{
    // Slots of a chain's state carried from row to row (each Vector<float>.Count wide, one per half of the tile row):
    // the frame q, the parent's angular turn w = d × c (its direction crossed with its turn c = (u − (u·d)d)/len, which
    // is (d × u)/len: no projection needed), its correction Δ (its kick waits for this row's correction) and the
    // target.
    // What can be read back from the tile instead is: the parent's position (stored there in its own row), its move
    // so far (h·v + Δ, with v not yet kicked) and whether it is free (its inverse mass). Fewer stores per row made
    // the sweep measurably faster (the same bits).
    private const int Sqx = 0, Sqy = 1, Sqz = 2, Sqw = 3, Swx = 4, Swy = 5, Swz = 6,
        SDx = 7, SDy = 8, SDz = 9, Stx = 10, Sty = 11, Stz = 12, Slots = 13;

    /// <summary>
    /// Root to tip over rows 1 … rows−1, each row's velocity kick applied one row later (it needs the child's
    /// correction): v += (Δ_k − s·(Δ_{k+1} + fall of a free k+1)) / h for free particles (see BendSystem).
    /// The halves of a row are independent chains, so the CPU overlaps their latencies; each carries its state in
    /// a small stack buffer between rows (too much state for the registers anyway, and one loop body for both).
    /// Constants are broadcast where they are used (<c>new V(p.H)</c>), not held in vector registers: see Sweep16.
    /// </summary>
    [SkipLocalsInit]
    private static void Sweep(ref float d, ref float rest, int rows, in SweepParams p)
    {
        // Two chains of Vector<float>.Count lanes (a JIT-time constant), so the chain state sits at constant offsets.
        int width = V.Count, lanes = 2 * V.Count;
        Debug.Assert(p.Lanes == lanes);
        var one = V.One;
        var zero = V.Zero;
        Span<float> stateSpan = stackalloc float[Slots * lanes];
        ref float s = ref stateSpan[0];
        // Each field's row 0, rows addressed by a native-sized index (as in Sweep16).
        ref float X = ref Unsafe.Add(ref d, p.Ox), Y = ref Unsafe.Add(ref d, p.Oy), Z = ref Unsafe.Add(ref d, p.Oz);
        ref float Vx = ref Unsafe.Add(ref d, p.Ovx), Vy = ref Unsafe.Add(ref d, p.Ovy), Vz = ref Unsafe.Add(ref d, p.Ovz);
        ref float M = ref Unsafe.Add(ref d, p.Om), Ln = ref Unsafe.Add(ref d, p.Ol);
        ref float Rx = ref Unsafe.Add(ref rest, p.Orx), Ry = ref Unsafe.Add(ref rest, p.Ory), Rz = ref Unsafe.Add(ref rest, p.Orz);
        ref float A = ref Unsafe.Add(ref rest, p.Oa), B = ref Unsafe.Add(ref rest, p.Ob);
        for (int h = 0; h < lanes; h += width)
        {
            ref float sh = ref Unsafe.Add(ref s, h);
            Simd.St(ref sh, Sqx * lanes, new V(p.Qx)); Simd.St(ref sh, Sqy * lanes, new V(p.Qy));
            Simd.St(ref sh, Sqz * lanes, new V(p.Qz)); Simd.St(ref sh, Sqw * lanes, new V(p.Qw));
            // Direction, turn and correction start at zero. The root is never kicked: it follows the head.
            for (int slot = Swx; slot < Stx; slot++) Simd.St(ref sh, slot * lanes, zero);
            if (rows < 2) continue;
            // Segment 1's target: its rest direction turned by the head.
            Turn(new V(p.Qx), new V(p.Qy), new V(p.Qz), new V(p.Qw),
                Simd.Ld(ref rest, p.Orx + lanes + h), Simd.Ld(ref rest, p.Ory + lanes + h), Simd.Ld(ref rest, p.Orz + lanes + h), out var tx1, out var ty1, out var tz1);
            Simd.St(ref sh, Stx * lanes, tx1); Simd.St(ref sh, Sty * lanes, ty1); Simd.St(ref sh, Stz * lanes, tz1);
        }
        for (int k = 1; k < rows; k++)
        {
            for (int h = 0; h < lanes; h += width)
            {
                nuint u = (nuint)(k * lanes + h), up = u - (nuint)lanes, un = u + (nuint)lanes;
                ref float sh = ref Unsafe.Add(ref s, h);
                var px = Simd.Ld(ref X, up); var py = Simd.Ld(ref Y, up); var pz = Simd.Ld(ref Z, up);
                var x = Simd.Ld(ref X, u); var y = Simd.Ld(ref Y, u); var z = Simd.Ld(ref Z, u);
                // Masks that are all set (the common case: every lane a live, moving, non-degenerate segment) make
                // their selects identities, so those are skipped (as in Sweep16): the same bits with fewer operations.
                var m = Simd.Ld(ref M, u);
                bool allFree = !Vector.EqualsAny(m, zero), noneFree = Vector.EqualsAll(m, zero);
                var rl = Simd.Ld(ref Ln, u);
                var rx = Simd.Ld(ref Rx, u); var ry = Simd.Ld(ref Ry, u); var rz = Simd.Ld(ref Rz, u);
                var ex = x - px; var ey = y - py; var ez = z - pz;
                var len2 = Simd.MulAdd(ez, ez, Simd.MulAdd(ey, ey, ex * ex));
                var len = Vector.SquareRoot(len2);
                // 1/len as len/len² where len² is far from underflow: the root and the division run side by side
                // instead of one after the other (the row's new position waits on them, and on |m| below).
                bool allClear = Vector.GreaterThanAll(len2, new V(1e-30f));
                var inv2 = one / len2;
                var inv = len * inv2;
                if (!allClear)
                {
                    var hasLen = Vector.GreaterThan(len, zero);
                    inv = Simd.Sel(Vector.GreaterThan(len2, new V(1e-30f)), inv, Simd.Sel(hasLen, one / Simd.Sel(hasLen, len, one), zero));
                }
                var ux0 = ex * inv; var uy0 = ey * inv; var uz0 = ez * inv;
                // Target: the rest direction turned by the frame carried from the root, worked out at the end of the
                // row above (see below).
                var tx = Simd.Ld(ref sh, Stx * lanes); var ty = Simd.Ld(ref sh, Sty * lanes); var tz = Simd.Ld(ref sh, Stz * lanes);
                // A rest direction to turn (any component non-zero, by bits: no multiplies).
                var restBits = (Vector.AsVectorUInt32(rx) | Vector.AsVectorUInt32(ry) | Vector.AsVectorUInt32(rz)) & new Vector<uint>(0x7fffffffu);
                if (Vector.EqualsAny(restBits, Vector<uint>.Zero))
                {
                    var restOk = ~Vector.AsVectorInt32(Vector.Equals(restBits, Vector<uint>.Zero));
                    var hasLen = Vector.GreaterThan(len, zero);
                    tx = Simd.Sel(restOk, tx, Simd.Sel(hasLen, ux0, zero));
                    ty = Simd.Sel(restOk, ty, Simd.Sel(hasLen, uy0, new V(-1f)));
                    tz = Simd.Sel(restOk, tz, Simd.Sel(hasLen, uz0, zero));
                }
                // Every lane long enough (len > 0 follows from len² > 1e-30).
                bool allOkLen = allClear && Vector.GreaterThanAll(len, new V(1e-6f) * rl);
                V dx = ux0, dy = uy0, dz = uz0;
                if (!allOkLen)
                {
                    var okLen = OkLen(len, rl);
                    dx = Simd.Sel(okLen, ux0, tx); dy = Simd.Sel(okLen, uy0, ty); dz = Simd.Sel(okLen, uz0, tz);
                }
                // How far this segment turned since the substep's start (see BendSystem).
                // h·(v − v_parent) − the parent's correction: one multiply a component (the sweep is bound by those).
                var ux = Simd.MulSub(new V(p.H), Simd.Ld(ref Vx, u) - Simd.Ld(ref Vx, up), Simd.Ld(ref sh, SDx * lanes));
                var uy = Simd.MulSub(new V(p.H), Simd.Ld(ref Vy, u) - Simd.Ld(ref Vy, up), Simd.Ld(ref sh, SDy * lanes));
                var uz = Simd.MulSub(new V(p.H), Simd.Ld(ref Vz, u) - Simd.Ld(ref Vz, up), Simd.Ld(ref sh, SDz * lanes));
                // A row pinned in every lane (each strand's second particle, the rows past a cut) does not move: its
                // joint's spring m and the target's turn are not needed, only the frame it hands on (taken from d).
                V mx = zero, my = zero, mz = zero, ml = zero, cdx = zero, cdy = zero, cdz = zero;
                bool allMOk = false;
                if (!noneFree)
                {
                    // Where d = e/len: (u − (u·d)d)/len = (u − (u·e)/len² e)/len, whose u·e does not wait for the root.
                    var ue = Simd.MulAdd(uz, ez, Simd.MulAdd(uy, ey, ux * ex)) * inv2;
                    var tcx = Simd.NegMulAdd(ue, ex, ux) * inv; var tcy = Simd.NegMulAdd(ue, ey, uy) * inv; var tcz = Simd.NegMulAdd(ue, ez, uz) * inv;
                    if (!allOkLen)
                    {
                        var byE = Vector.GreaterThan(len2, new V(1e-30f)) & OkLen(len, rl);
                        var al = Simd.MulAdd(uz, dz, Simd.MulAdd(uy, dy, ux * dx));
                        tcx = Simd.Sel(byE, tcx, Simd.NegMulAdd(al, dx, ux) * inv);
                        tcy = Simd.Sel(byE, tcy, Simd.NegMulAdd(al, dy, uy) * inv);
                        tcz = Simd.Sel(byE, tcz, Simd.NegMulAdd(al, dz, uz) * inv);
                    }
                    // Target turned with the parent: Δt = w_p × t.
                    var wx = Simd.Ld(ref sh, Swx * lanes); var wy = Simd.Ld(ref sh, Swy * lanes); var wz = Simd.Ld(ref sh, Swz * lanes);
                    var ttx = Simd.MulSub(wy, tz, wz * ty); var tty = Simd.MulSub(wz, tx, wx * tz); var ttz = Simd.MulSub(wx, ty, wy * tx);
                    // The joint's spring and dashpot shares, cached per strand for this h (see CacheShares).
                    var a = Simd.Ld(ref A, u); var b = Simd.Ld(ref B, u);
                    var ox = dx - tx; var oy = dy - ty; var oz = dz - tz;
                    var sx = ox - (tcx - ttx); var sy = oy - (tcy - tty); var sz = oz - (tcz - ttz);
                    mx = Simd.MulAdd(b, sx, Simd.MulAdd(a, ox, tx)); my = Simd.MulAdd(b, sy, Simd.MulAdd(a, oy, ty)); mz = Simd.MulAdd(b, sz, Simd.MulAdd(a, oz, tz));
                    var m2 = Simd.MulAdd(mz, mz, Simd.MulAdd(my, my, mx * mx));
                    ml = Vector.SquareRoot(m2);
                    // 1/|m| as |m|/|m|², as 1/len above.
                    allMOk = Vector.GreaterThanAll(ml, new V(1e-6f));
                    if (allMOk)
                    {
                        var invM = ml * (one / m2);
                        if (allFree) { dx = mx * invM; dy = my * invM; dz = mz * invM; }
                        else
                        {
                            var free = Free(m);
                            dx = Simd.Sel(free, mx * invM, dx); dy = Simd.Sel(free, my * invM, dy); dz = Simd.Sel(free, mz * invM, dz);
                        }
                    }
                    else
                    {
                        var free = Free(m);
                        var mOk = Vector.GreaterThan(ml, new V(1e-6f));
                        var invM = ml * (one / Simd.Sel(mOk, m2, one));
                        var ndx = Simd.Sel(mOk, mx * invM, tx); var ndy = Simd.Sel(mOk, my * invM, ty); var ndz = Simd.Sel(mOk, mz * invM, tz);
                        dx = Simd.Sel(free, ndx, dx); dy = Simd.Sel(free, ndy, dy); dz = Simd.Sel(free, ndz, dz);
                    }
                    var nx = Simd.MulAdd(dx, rl, px); var ny = Simd.MulAdd(dy, rl, py); var nz = Simd.MulAdd(dz, rl, pz);
                    cdx = nx - x; cdy = ny - y; cdz = nz - z;
                    if (!allFree)
                    {
                        var free = Free(m);
                        cdx = Simd.Sel(free, cdx, zero); cdy = Simd.Sel(free, cdy, zero); cdz = Simd.Sel(free, cdz, zero);
                    }
                }
                x += cdx; y += cdy; z += cdz;
                Simd.St(ref X, u, x); Simd.St(ref Y, u, y); Simd.St(ref Z, u, z);
                // The row above takes its kick now that this row's correction is known.
                V fallX = new(p.FallX), fallY = new(p.FallY), fallZ = new(p.FallZ);
                if (!allFree)
                {
                    var free = Free(m);
                    fallX = Simd.Sel(free, fallX, zero); fallY = Simd.Sel(free, fallY, zero); fallZ = Simd.Sel(free, fallZ, zero);
                }
                Kick(ref Vx, ref Vy, ref Vz, in p, up, k == 1 ? zero : Simd.Ld(ref M, up),
                    Simd.Ld(ref sh, SDx * lanes), Simd.Ld(ref sh, SDy * lanes), Simd.Ld(ref sh, SDz * lanes), cdx + fallX, cdy + fallY, cdz + fallZ);
                Simd.St(ref sh, SDx * lanes, cdx); Simd.St(ref sh, SDy * lanes, cdy); Simd.St(ref sh, SDz * lanes, cdz);
                // This segment's turn over the substep so far, for its child.
                ux += cdx; uy += cdy; uz += cdz;
                // As the child's parent turn: w = d × c = (d × u)/len.
                Simd.St(ref sh, Swx * lanes, Simd.MulSub(dy, uz, dz * uy) * inv); Simd.St(ref sh, Swy * lanes, Simd.MulSub(dz, ux, dx * uz) * inv);
                Simd.St(ref sh, Swz * lanes, Simd.MulSub(dx, uy, dy * ux) * inv);
                // Frame: the smallest rotation taking t onto d, then the frame so far (identity if they are opposite).
                // It is built from m and |m| (f ∝ (t × m, |m| + t·m)), not from d = m/|m|, and left unnormalised (below).
                V gx = dx, gy = dy, gz = dz, gl = one;
                if (allFree && allMOk) { gx = mx; gy = my; gz = mz; gl = ml; }
                else if (!noneFree)
                {
                    var byM = Free(m) & Vector.GreaterThan(ml, new V(1e-6f));
                    gx = Simd.Sel(byM, mx, dx); gy = Simd.Sel(byM, my, dy); gz = Simd.Sel(byM, mz, dz); gl = Simd.Sel(byM, ml, one);
                }
                var dot = Simd.MulAdd(tz, gz, Simd.MulAdd(ty, gy, tx * gx));
                var fx = Simd.MulSub(ty, gz, tz * gy); var fy = Simd.MulSub(tz, gx, tx * gz); var fz = Simd.MulSub(tx, gy, ty * gx); var fw = gl + dot;
                if (Vector.LessThanAny(dot, new V(-0.9999f) * gl))
                {
                    var flip = Vector.LessThan(dot, new V(-0.9999f) * gl);
                    fx = Simd.Sel(flip, zero, fx); fy = Simd.Sel(flip, zero, fy); fz = Simd.Sel(flip, zero, fz); fw = Simd.Sel(flip, one, fw);
                }
                var invF2 = one / Simd.MulAdd(fw, fw, Simd.MulAdd(fz, fz, Simd.MulAdd(fy, fy, fx * fx)));
                var qx = Simd.Ld(ref sh, Sqx * lanes); var qy = Simd.Ld(ref sh, Sqy * lanes); var qz = Simd.Ld(ref sh, Sqz * lanes); var qw = Simd.Ld(ref sh, Sqw * lanes);
                // The frame so far, Q = f∘q, left unnormalised (|Q|² = |f|² as q is a unit quaternion): the next target,
                // this row's next rest direction turned by Q, is r + (2/|Q|²)(Q_w (Q×r) + Q×(Q×r)) with 1/|f|² from above,
                // so it waits for no square root; q for the next row is Q scaled to unit length, off that chain.
                var fqx = Simd.NegMulAdd(fz, qy, Simd.MulAdd(fy, qz, Simd.MulAdd(fx, qw, fw * qx)));
                var fqy = Simd.MulAdd(fz, qx, Simd.MulAdd(fy, qw, Simd.NegMulAdd(fx, qz, fw * qy)));
                var fqz = Simd.MulAdd(fz, qw, Simd.NegMulAdd(fy, qx, Simd.MulAdd(fx, qy, fw * qz)));
                var fqw = Simd.NegMulAdd(fz, qz, Simd.NegMulAdd(fy, qy, Simd.NegMulAdd(fx, qx, fw * qw)));
                if (k + 1 < rows)
                {
                    var nx1 = Simd.Ld(ref Rx, un); var ny1 = Simd.Ld(ref Ry, un); var nz1 = Simd.Ld(ref Rz, un);
                    var cx1 = Simd.MulSub(fqy, nz1, fqz * ny1); var cy1 = Simd.MulSub(fqz, nx1, fqx * nz1); var cz1 = Simd.MulSub(fqx, ny1, fqy * nx1);
                    var gx1 = Simd.NegMulAdd(fqz, cy1, Simd.MulAdd(fqy, cz1, fqw * cx1)); var gy1 = Simd.NegMulAdd(fqx, cz1, Simd.MulAdd(fqz, cx1, fqw * cy1));
                    var gz1 = Simd.NegMulAdd(fqy, cx1, Simd.MulAdd(fqx, cy1, fqw * cz1));
                    var twice = invF2 + invF2;
                    Simd.St(ref sh, Stx * lanes, Simd.MulAdd(gx1, twice, nx1)); Simd.St(ref sh, Sty * lanes, Simd.MulAdd(gy1, twice, ny1));
                    Simd.St(ref sh, Stz * lanes, Simd.MulAdd(gz1, twice, nz1));
                }
                var fInv = Vector.SquareRoot(invF2);
                Simd.St(ref sh, Sqx * lanes, fqx * fInv); Simd.St(ref sh, Sqy * lanes, fqy * fInv);
                Simd.St(ref sh, Sqz * lanes, fqz * fInv); Simd.St(ref sh, Sqw * lanes, fqw * fInv);
            }
        }
        if (rows < 2) return;
        for (int h = 0; h < lanes; h += width)
        {
            ref float sh = ref Unsafe.Add(ref s, h);
            Kick(ref Vx, ref Vy, ref Vz, in p, (nuint)((rows - 1) * lanes + h), Simd.Ld(ref M, (nuint)((rows - 1) * lanes + h)),
                Simd.Ld(ref sh, SDx * lanes), Simd.Ld(ref sh, SDy * lanes), Simd.Ld(ref sh, SDz * lanes), zero, zero, zero);
        }
    }

    /// <summary>The free lanes (inverse mass m ≠ 0): the mask the rare paths select by.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static Vector<int> Free(V m) => ~Vector.Equals(m, V.Zero);

    /// <summary>The lanes whose segment is long enough to give a direction: len &gt; 10⁻⁶·rest length, and len &gt; 0.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static Vector<int> OkLen(V len, V rl) => Vector.GreaterThan(len, new V(1e-6f) * rl) & Vector.GreaterThan(len, V.Zero);

    /// <summary>
    /// v turned by the unit quaternion q: v + 2w(q×v) + 2q×(q×v), as v + w·c + q×c with c = 2q×v (the doubling by adds).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Turn(V qx, V qy, V qz, V qw, V rx, V ry, V rz, out V tx, out V ty, out V tz)
    {
        var q2x = qx + qx; var q2y = qy + qy; var q2z = qz + qz;
        var cx = Simd.MulSub(q2y, rz, q2z * ry); var cy = Simd.MulSub(q2z, rx, q2x * rz); var cz = Simd.MulSub(q2x, ry, q2y * rx);
        tx = Simd.NegMulAdd(qz, cy, Simd.MulAdd(qy, cz, Simd.MulAdd(qw, cx, rx))); ty = Simd.NegMulAdd(qx, cz, Simd.MulAdd(qz, cx, Simd.MulAdd(qw, cy, ry)));
        tz = Simd.NegMulAdd(qy, cx, Simd.MulAdd(qx, cy, Simd.MulAdd(qw, cz, rz)));
    }

    /// <summary>v += (Δ − s·next) / h on the free lanes (m: inverse masses) of row r, then clamped to the speed limit (the sweep writes velocities last).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Kick(ref float Vx, ref float Vy, ref float Vz, in SweepParams p, nuint r, V m, V dx, V dy, V dz, V nx, V ny, V nz)
    {
        var vx = Simd.Ld(ref Vx, r); var vy = Simd.Ld(ref Vy, r); var vz = Simd.Ld(ref Vz, r);
        var wx = Simd.MulAdd(Simd.NegMulAdd(new V(p.Reaction), nx, dx), new V(p.InvH), vx); var wy = Simd.MulAdd(Simd.NegMulAdd(new V(p.Reaction), ny, dy), new V(p.InvH), vy);
        var wz = Simd.MulAdd(Simd.NegMulAdd(new V(p.Reaction), nz, dz), new V(p.InvH), vz);
        // Squared speeds compared where a component is past the bound, the root taken only where a lane is over the limit.
        if (!Simd.AllWithin(wx, wy, wz, new Vector<uint>(p.SpeedBound)))
        {
            var speedSq = Simd.MulAdd(wz, wz, Simd.MulAdd(wy, wy, wx * wx));
            if (Vector.GreaterThanAny(speedSq, new V(p.MaxSpeedSq)))
            {
                var over = Vector.GreaterThan(speedSq, new V(p.MaxSpeedSq));
                var f = new V(p.MaxSpeed) / Simd.Sel(over, Vector.SquareRoot(speedSq), V.One);
                wx = Simd.Sel(over, wx * f, wx); wy = Simd.Sel(over, wy * f, wy); wz = Simd.Sel(over, wz * f, wz);
            }
        }
        if (Vector.EqualsAny(m, V.Zero)) { var free = Free(m); wx = Simd.Sel(free, wx, vx); wy = Simd.Sel(free, wy, vy); wz = Simd.Sel(free, wz, vz); }
        Simd.St(ref Vx, r, wx);
        Simd.St(ref Vy, r, wy);
        Simd.St(ref Vz, r, wz);
    }
}
