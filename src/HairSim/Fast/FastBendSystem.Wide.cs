using System.Diagnostics;
using System.Runtime.CompilerServices;
using System.Runtime.Intrinsics;
using V = System.Runtime.Intrinsics.Vector512<float>;

namespace HairSim.Fast;

// Generated from FastBendSystem.Sweep.cs by replacing the 8-lane operations with their 16-lane twins; keep the two in step.

/// <summary>
/// The sweep over a tile of two 16-lane (AVX-512) chains per row: <see cref="Sweep"/>'s arithmetic in the same order
/// on 16-lane vectors (lane-wise IEEE operations only, no estimates), so every strand gets the bits the 8-lane sweep
/// gives it, with twice the strands per row latency.
/// </summary>
public sealed partial class FastBendSystem
{
    /// <summary>
    /// <see cref="Sweep"/> on 16-lane vectors. The constants are broadcast where they are used
    /// (<c>Vector512.Create(p.H)</c>): the JIT folds each into its instruction as an embedded broadcast from memory, so
    /// none holds one of the 32 vector registers; held in a struct of vectors they pushed the row's own values onto
    /// the stack (twice the spills, and a clearly slower frame).
    /// </summary>
    private static void Sweep16(ref float d, ref float rest, int rows, in SweepParams p) => Sweep16<Apart>(ref d, ref rest, rows, in p);

    /// <summary>
    /// <see cref="Sweep16"/>; with <typeparamref name="TIntegrate"/> = <see cref="Fused"/> each row is first stepped as
    /// <see cref="FastIntegrateSystem"/> steps it (gravity, damping, speed limit, x += h·v; the same operations in the
    /// same order), in registers just before the sweep reads it: one pass over the chunk's rows per substep instead of
    /// two. No row's sweep reads a later row's position or velocity, so the bits are those of the two passes.
    /// </summary>
    [SkipLocalsInit]
    private static void Sweep16<TIntegrate>(ref float d, ref float rest, int rows, in SweepParams p) where TIntegrate : struct
    {
        // The 16-lane sweep always runs two chains of 16 (a chunk's 32 strands, or a tile of 32): the state slots then sit
        // at constant offsets from each chain's base.
        const int width = 16, lanes = 2 * width;
        Debug.Assert(p.Lanes == lanes);
        var one = V.One;
        var zero = V.Zero;
        Span<float> stateSpan = stackalloc float[Slots * lanes];
        ref float s = ref stateSpan[0];
        // Each field's row 0, and rows addressed by a native-sized index: one addressing mode per access, where an
        // offset read from p, added, sign-extended and scaled took four instructions more each time.
        ref float X = ref Unsafe.Add(ref d, p.Ox), Y = ref Unsafe.Add(ref d, p.Oy), Z = ref Unsafe.Add(ref d, p.Oz);
        ref float Vx = ref Unsafe.Add(ref d, p.Ovx), Vy = ref Unsafe.Add(ref d, p.Ovy), Vz = ref Unsafe.Add(ref d, p.Ovz);
        ref float M = ref Unsafe.Add(ref d, p.Om), Ln = ref Unsafe.Add(ref d, p.Ol);
        ref float Rx = ref Unsafe.Add(ref rest, p.Orx), Ry = ref Unsafe.Add(ref rest, p.Ory), Rz = ref Unsafe.Add(ref rest, p.Orz);
        ref float A = ref Unsafe.Add(ref rest, p.Oa), B = ref Unsafe.Add(ref rest, p.Ob);
        for (int h = 0; h < lanes; h += width)
        {
            ref float sh = ref Unsafe.Add(ref s, h);
            if (typeof(TIntegrate) == typeof(Fused))
            {
                // The root row (pins, which integration leaves as they are, unless a lane holds a free root).
                nuint r0 = (nuint)h;
                var x0 = Ld16(ref X, r0); var y0 = Ld16(ref Y, r0); var z0 = Ld16(ref Z, r0);
                Integrate16(ref Vx, ref Vy, ref Vz, r0, Ld16(ref M, r0), false, in p, ref x0, ref y0, ref z0, out _, out _, out _);
                St16(ref X, r0, x0); St16(ref Y, r0, y0); St16(ref Z, r0, z0);
            }
            St16(ref sh, Sqx * lanes, Vector512.Create(p.Qx)); St16(ref sh, Sqy * lanes, Vector512.Create(p.Qy));
            St16(ref sh, Sqz * lanes, Vector512.Create(p.Qz)); St16(ref sh, Sqw * lanes, Vector512.Create(p.Qw));
            // Direction, turn and correction start at zero. The root is never kicked: it follows the head.
            for (int slot = Swx; slot < Stx; slot++) St16(ref sh, slot * lanes, zero);
            if (rows < 2) continue;
            // Segment 1's target: its rest direction turned by the head.
            Turn16(Vector512.Create(p.Qx), Vector512.Create(p.Qy), Vector512.Create(p.Qz), Vector512.Create(p.Qw),
                Ld16(ref rest, p.Orx + lanes + h), Ld16(ref rest, p.Ory + lanes + h), Ld16(ref rest, p.Orz + lanes + h), out var tx1, out var ty1, out var tz1);
            St16(ref sh, Stx * lanes, tx1); St16(ref sh, Sty * lanes, ty1); St16(ref sh, Stz * lanes, tz1);
        }
        // Rows with a free lane inside the collider's far sphere, for the collision just after (StrandChunk.FarRows):
        // the root row as it stands now (nothing below moves it), each later row once its position is final. A half
        // row pinned in every lane is left out too: the kernel pushes no pinned particle.
        ulong far = 0;
        if (p.FarRows != 0 && (NearFree16(ref X, ref Y, ref Z, ref M, 0, in p) || NearFree16(ref X, ref Y, ref Z, ref M, width, in p)))
            far = 1;
        for (int k = 1; k < rows; k++)
        {
            for (int h = 0; h < lanes; h += width)
            {
                // A share of the next chunk's prefetch per half row: small enough not to fill the core's miss buffers.
                Prefetcher.Row(p.Prefetch);
                ref float sh = ref Unsafe.Add(ref s, h);
                nuint u = (nuint)(k * lanes + h), up = u - (nuint)lanes, un = u + (nuint)lanes;
                var px = Ld16(ref X, up); var py = Ld16(ref Y, up); var pz = Ld16(ref Z, up);
                var x = Ld16(ref X, u); var y = Ld16(ref Y, u); var z = Ld16(ref Z, u);
                // The tests that pick a row's common case reduce their compares straight to a flag (a compare into a
                // mask register and a test); the masks themselves are formed only on the rare paths that select by them.
                var m = Ld16(ref M, u);
                bool allFree = !Vector512.EqualsAny(m, zero), noneFree = Vector512.EqualsAll(m, zero);
                V vux, vuy, vuz;
                if (typeof(TIntegrate) == typeof(Fused))
                    Integrate16(ref Vx, ref Vy, ref Vz, u, m, allFree, in p, ref x, ref y, ref z, out vux, out vuy, out vuz);
                else { vux = Ld16(ref Vx, u); vuy = Ld16(ref Vy, u); vuz = Ld16(ref Vz, u); }
                var rl = Ld16(ref Ln, u);
                var rx = Ld16(ref Rx, u); var ry = Ld16(ref Ry, u); var rz = Ld16(ref Rz, u);
                var ex = x - px; var ey = y - py; var ez = z - pz;
                var len2 = Fma(ez, ez, Fma(ey, ey, ex * ex));
                var len = Vector512.Sqrt(len2);
                // Masks that are all set (the common case: every lane a live, moving, non-degenerate segment) make
                // their selects identities, so those are skipped: the same bits with fewer operations.
                // 1/len as len/len² where len² is far from underflow: the root and the division run side by side
                // instead of one after the other (the row's new position waits on them, and on |m| below).
                bool allClear = Vector512.GreaterThanAll(len2, Vector512.Create(1e-30f));
                var inv2 = one / len2;
                var inv = len * inv2;
                if (!allClear)
                {
                    var hasLen = Vector512.GreaterThan(len, zero);
                    inv = Sel16(Vector512.GreaterThan(len2, Vector512.Create(1e-30f)), inv, Sel16(hasLen, one / Sel16(hasLen, len, one), zero));
                }
                var ux0 = ex * inv; var uy0 = ey * inv; var uz0 = ez * inv;
                // Target: the rest direction turned by the frame carried from the root, worked out at the end of the
                // row above (see below).
                var tx = Ld16(ref sh, Stx * lanes); var ty = Ld16(ref sh, Sty * lanes); var tz = Ld16(ref sh, Stz * lanes);
                // A rest direction to turn (any component non-zero, by bits: no multiplies).
                var restBits = (rx.AsUInt32() | ry.AsUInt32() | rz.AsUInt32()) & Vector512.Create(0x7fffffffu);
                if (Vector512.EqualsAny(restBits, Vector512<uint>.Zero))
                {
                    var restOk = ~Vector512.Equals(restBits, Vector512<uint>.Zero).AsSingle();
                    var hasLen = Vector512.GreaterThan(len, zero);
                    tx = Sel16(restOk, tx, Sel16(hasLen, ux0, zero));
                    ty = Sel16(restOk, ty, Sel16(hasLen, uy0, Vector512.Create(-1f)));
                    tz = Sel16(restOk, tz, Sel16(hasLen, uz0, zero));
                }
                // Every lane long enough (len > 0 follows from len² > 1e-30).
                bool allOkLen = allClear && Vector512.GreaterThanAll(len, Vector512.Create(1e-6f) * rl);
                V dx = ux0, dy = uy0, dz = uz0;
                if (!allOkLen)
                {
                    var okLen = OkLen(len, rl);
                    dx = Sel16(okLen, ux0, tx); dy = Sel16(okLen, uy0, ty); dz = Sel16(okLen, uz0, tz);
                }
                // How far this segment turned since the substep's start (see BendSystem).
                // h·(v − v_parent) − the parent's correction: one multiply a component (the sweep is bound by those).
                var ux = Fms(Vector512.Create(p.H), vux - Ld16(ref Vx, up), Ld16(ref sh, SDx * lanes));
                var uy = Fms(Vector512.Create(p.H), vuy - Ld16(ref Vy, up), Ld16(ref sh, SDy * lanes));
                var uz = Fms(Vector512.Create(p.H), vuz - Ld16(ref Vz, up), Ld16(ref sh, SDz * lanes));
                // A row pinned in every lane (each strand's second particle, the rows past a cut) does not move: its
                // joint's spring m and the target's turn are not needed, only the frame it hands on (taken from d).
                V mx = zero, my = zero, mz = zero, ml = zero;
                bool allMOk = false;
                V cdx = zero, cdy = zero, cdz = zero;
                if (!noneFree)
                {
                    // Where d = e/len: (u − (u·d)d)/len = (u − (u·e)/len² e)/len, whose u·e does not wait for the root.
                    var ue = Fma(uz, ez, Fma(uy, ey, ux * ex)) * inv2;
                    var tcx = Fnma(ue, ex, ux) * inv; var tcy = Fnma(ue, ey, uy) * inv; var tcz = Fnma(ue, ez, uz) * inv;
                    if (!allOkLen)
                    {
                        var byE = Vector512.GreaterThan(len2, Vector512.Create(1e-30f)) & OkLen(len, rl);
                        var al = Fma(uz, dz, Fma(uy, dy, ux * dx));
                        tcx = Sel16(byE, tcx, Fnma(al, dx, ux) * inv); tcy = Sel16(byE, tcy, Fnma(al, dy, uy) * inv); tcz = Sel16(byE, tcz, Fnma(al, dz, uz) * inv);
                    }
                    // Target turned with the parent: Δt = w_p × t.
                    var wx = Ld16(ref sh, Swx * lanes); var wy = Ld16(ref sh, Swy * lanes); var wz = Ld16(ref sh, Swz * lanes);
                    var ttx = Fms(wy, tz, wz * ty); var tty = Fms(wz, tx, wx * tz); var ttz = Fms(wx, ty, wy * tx);
                    // The joint's spring and dashpot shares, cached per strand for this h (see CacheShares).
                    var a = Ld16(ref A, u); var b = Ld16(ref B, u);
                    var ox = dx - tx; var oy = dy - ty; var oz = dz - tz;
                    var sx = ox - (tcx - ttx); var sy = oy - (tcy - tty); var sz = oz - (tcz - ttz);
                    mx = Fma(b, sx, Fma(a, ox, tx)); my = Fma(b, sy, Fma(a, oy, ty)); mz = Fma(b, sz, Fma(a, oz, tz));
                    var m2 = Fma(mz, mz, Fma(my, my, mx * mx));
                    ml = Vector512.Sqrt(m2);
                    allMOk = Vector512.GreaterThanAll(ml, Vector512.Create(1e-6f));
                    if (allMOk)
                    {
                        var invM = ml * (one / m2);
                        if (allFree) { dx = mx * invM; dy = my * invM; dz = mz * invM; }
                        else
                        {
                            var free = Free16(m);
                            dx = Sel16(free, mx * invM, dx); dy = Sel16(free, my * invM, dy); dz = Sel16(free, mz * invM, dz);
                        }
                    }
                    else
                    {
                        var free = Free16(m);
                        var mOk = Vector512.GreaterThan(ml, Vector512.Create(1e-6f));
                        var invM = ml * (one / Sel16(mOk, m2, one));
                        var ndx = Sel16(mOk, mx * invM, tx); var ndy = Sel16(mOk, my * invM, ty); var ndz = Sel16(mOk, mz * invM, tz);
                        dx = Sel16(free, ndx, dx); dy = Sel16(free, ndy, dy); dz = Sel16(free, ndz, dz);
                    }
                    var nx = Fma(dx, rl, px); var ny = Fma(dy, rl, py); var nz = Fma(dz, rl, pz);
                    cdx = nx - x; cdy = ny - y; cdz = nz - z;
                    if (!allFree) { var free = Free16(m); cdx = Sel16(free, cdx, zero); cdy = Sel16(free, cdy, zero); cdz = Sel16(free, cdz, zero); }
                }
                x += cdx; y += cdy; z += cdz;
                St16(ref X, u, x); St16(ref Y, u, y); St16(ref Z, u, z);
                if (p.FarRows != 0 && !noneFree && Near16(x, y, z, in p)) far |= 1UL << k;
                // The row above takes its kick now that this row's correction is known.
                V fallX = Vector512.Create(p.FallX), fallY = Vector512.Create(p.FallY), fallZ = Vector512.Create(p.FallZ);
                if (!allFree)
                {
                    var free = Free16(m);
                    fallX = Sel16(free, fallX, zero); fallY = Sel16(free, fallY, zero); fallZ = Sel16(free, fallZ, zero);
                }
                Kick16(ref Vx, ref Vy, ref Vz, in p, up, k == 1 ? zero : Ld16(ref M, up),
                    Ld16(ref sh, SDx * lanes), Ld16(ref sh, SDy * lanes), Ld16(ref sh, SDz * lanes), cdx + fallX, cdy + fallY, cdz + fallZ);
                St16(ref sh, SDx * lanes, cdx); St16(ref sh, SDy * lanes, cdy); St16(ref sh, SDz * lanes, cdz);
                // This segment's turn over the substep so far, for its child.
                ux += cdx; uy += cdy; uz += cdz;
                // As the child's parent turn: w = d × c = (d × u)/len.
                St16(ref sh, Swx * lanes, Fms(dy, uz, dz * uy) * inv); St16(ref sh, Swy * lanes, Fms(dz, ux, dx * uz) * inv);
                St16(ref sh, Swz * lanes, Fms(dx, uy, dy * ux) * inv);
                // Frame: the smallest rotation taking t onto d, then the frame so far (identity if they are opposite).
                // It is built from m and |m| (f ∝ (t × m, |m| + t·m)), not from d = m/|m|, and left unnormalised (below).
                V gx = dx, gy = dy, gz = dz, gl = one;
                if (allFree && allMOk) { gx = mx; gy = my; gz = mz; gl = ml; }
                else if (!noneFree)
                {
                    var byM = Free16(m) & Vector512.GreaterThan(ml, Vector512.Create(1e-6f));
                    gx = Sel16(byM, mx, dx); gy = Sel16(byM, my, dy); gz = Sel16(byM, mz, dz); gl = Sel16(byM, ml, one);
                }
                var dot = Fma(tz, gz, Fma(ty, gy, tx * gx));
                var fx = Fms(ty, gz, tz * gy); var fy = Fms(tz, gx, tx * gz); var fz = Fms(tx, gy, ty * gx); var fw = gl + dot;
                if (Vector512.LessThanAny(dot, Vector512.Create(-0.9999f) * gl))
                {
                    var flip = Vector512.LessThan(dot, Vector512.Create(-0.9999f) * gl);
                    fx = Sel16(flip, zero, fx); fy = Sel16(flip, zero, fy); fz = Sel16(flip, zero, fz); fw = Sel16(flip, one, fw);
                }
                var invF2 = one / Fma(fw, fw, Fma(fz, fz, Fma(fy, fy, fx * fx)));
                var qx = Ld16(ref sh, Sqx * lanes); var qy = Ld16(ref sh, Sqy * lanes); var qz = Ld16(ref sh, Sqz * lanes); var qw = Ld16(ref sh, Sqw * lanes);
                // The frame so far, Q = f∘q, left unnormalised (|Q|² = |f|² as q is a unit quaternion): the next target,
                // this row's next rest direction turned by Q, is r + (2/|Q|²)(Q_w (Q×r) + Q×(Q×r)) with 1/|f|² from above,
                // so it waits for no square root; q for the next row is Q scaled to unit length, off that chain.
                var fqx = Fnma(fz, qy, Fma(fy, qz, Fma(fx, qw, fw * qx)));
                var fqy = Fma(fz, qx, Fma(fy, qw, Fnma(fx, qz, fw * qy)));
                var fqz = Fma(fz, qw, Fnma(fy, qx, Fma(fx, qy, fw * qz)));
                var fqw = Fnma(fz, qz, Fnma(fy, qy, Fnma(fx, qx, fw * qw)));
                if (k + 1 < rows)
                {
                    var nx1 = Ld16(ref Rx, un); var ny1 = Ld16(ref Ry, un); var nz1 = Ld16(ref Rz, un);
                    var cx1 = Fms(fqy, nz1, fqz * ny1); var cy1 = Fms(fqz, nx1, fqx * nz1); var cz1 = Fms(fqx, ny1, fqy * nx1);
                    var gx1 = Fnma(fqz, cy1, Fma(fqy, cz1, fqw * cx1)); var gy1 = Fnma(fqx, cz1, Fma(fqz, cx1, fqw * cy1));
                    var gz1 = Fnma(fqy, cx1, Fma(fqx, cy1, fqw * cz1));
                    var twice = invF2 + invF2;
                    St16(ref sh, Stx * lanes, Fma(gx1, twice, nx1)); St16(ref sh, Sty * lanes, Fma(gy1, twice, ny1));
                    St16(ref sh, Stz * lanes, Fma(gz1, twice, nz1));
                }
                var fInv = Vector512.Sqrt(invF2);
                St16(ref sh, Sqx * lanes, fqx * fInv); St16(ref sh, Sqy * lanes, fqy * fInv);
                St16(ref sh, Sqz * lanes, fqz * fInv); St16(ref sh, Sqw * lanes, fqw * fInv);
            }
        }
        if (p.FarRows != 0) unsafe { *(ulong*)p.FarRows = far; }
        if (rows < 2) return;
        for (int h = 0; h < lanes; h += width)
        {
            ref float sh = ref Unsafe.Add(ref s, h);
            Kick16(ref Vx, ref Vy, ref Vz, in p, (nuint)((rows - 1) * lanes + h), Ld16(ref M, (nuint)((rows - 1) * lanes + h)),
                Ld16(ref sh, SDx * lanes), Ld16(ref sh, SDy * lanes), Ld16(ref sh, SDz * lanes), zero, zero, zero);
        }
    }

    /// <summary>
    /// v turned by the unit quaternion q: v + 2w(q×v) + 2q×(q×v), as v + w·c + q×c with c = 2q×v (the doubling by adds).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Turn16(V qx, V qy, V qz, V qw, V rx, V ry, V rz, out V tx, out V ty, out V tz)
    {
        var q2x = qx + qx; var q2y = qy + qy; var q2z = qz + qz;
        var cx = Fms(q2y, rz, q2z * ry); var cy = Fms(q2z, rx, q2x * rz); var cz = Fms(q2x, ry, q2y * rx);
        tx = Fnma(qz, cy, Fma(qy, cz, Fma(qw, cx, rx))); ty = Fnma(qx, cz, Fma(qz, cx, Fma(qw, cy, ry)));
        tz = Fnma(qy, cx, Fma(qx, cy, Fma(qw, cz, rz)));
    }

    /// <summary>
    /// Row r as <see cref="FastIntegrateSystem"/>'s 16-lane kernel steps it (the same operations in the same order): its
    /// velocity stored and returned, its position (x, y, z in) moved by h·v on the free lanes (m: the row's inverse masses).
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Integrate16(ref float Vx, ref float Vy, ref float Vz, nuint r, V m, bool nonePinned, in SweepParams p,
        ref V x, ref V y, ref V z, out V vx, out V vy, out V vz)
    {
        var ox = Ld16(ref Vx, r); var oy = Ld16(ref Vy, r); var oz = Ld16(ref Vz, r);
        var keep = Vector512.Create(p.Keep);
        var nx = (ox + Vector512.Create(p.GravityStepX)) * keep; var ny = (oy + Vector512.Create(p.GravityStepY)) * keep;
        var nz = (oz + Vector512.Create(p.GravityStepZ)) * keep;
        // Every component within the bound (the common row): no lane over the limit, no squares needed.
        if (!Simd.AllWithin(nx, ny, nz, Vector512.Create(p.SpeedBound)))
        {
            var spSq = nx * nx + ny * ny + nz * nz;
            if (Vector512.GreaterThanAny(spSq, Vector512.Create(p.MaxSpeedSq)))
            {
                var over = Vector512.GreaterThan(spSq, Vector512.Create(p.MaxSpeedSq));
                var f = Vector512.ConditionalSelect(over, Vector512.Create(p.MaxSpeed) / Vector512.Sqrt(spSq), V.One);
                nx *= f; ny *= f; nz *= f;
            }
        }
        var h = Vector512.Create(p.H);
        if (nonePinned)
        {
            // Every lane free (the common row): the selects would be identities.
            vx = nx; vy = ny; vz = nz;
            x += h * nx; y += h * ny; z += h * nz;
        }
        else
        {
            var pinned = Vector512.Equals(m, V.Zero);
            vx = Sel16(pinned, ox, nx); vy = Sel16(pinned, oy, ny); vz = Sel16(pinned, oz, nz);
            x = Sel16(pinned, x, x + h * nx); y = Sel16(pinned, y, y + h * ny); z = Sel16(pinned, z, z + h * nz);
        }
        St16(ref Vx, r, vx); St16(ref Vy, r, vy); St16(ref Vz, r, vz);
    }

    /// <summary>v += (Δ − s·next) / h on the free lanes (m: inverse masses) of row r.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Kick16(ref float Vx, ref float Vy, ref float Vz, in SweepParams p, nuint r, V m, V dx, V dy, V dz, V nx, V ny, V nz)
    {
        var vx = Ld16(ref Vx, r); var vy = Ld16(ref Vy, r); var vz = Ld16(ref Vz, r);
        var wx = Fma(Fnma(Vector512.Create(p.Reaction), nx, dx), Vector512.Create(p.InvH), vx); var wy = Fma(Fnma(Vector512.Create(p.Reaction), ny, dy), Vector512.Create(p.InvH), vy); var wz = Fma(Fnma(Vector512.Create(p.Reaction), nz, dz), Vector512.Create(p.InvH), vz);
        // Squared speeds compared where a component is past the bound, the root taken only where a lane is over the limit.
        if (!Simd.AllWithin(wx, wy, wz, Vector512.Create(p.SpeedBound)))
        {
            var speedSq = Fma(wz, wz, Fma(wy, wy, wx * wx));
            if (Vector512.GreaterThanAny(speedSq, Vector512.Create(p.MaxSpeedSq)))
            {
                var over = Vector512.GreaterThan(speedSq, Vector512.Create(p.MaxSpeedSq));
                var f = Vector512.Create(p.MaxSpeed) / Sel16(over, Vector512.Sqrt(speedSq), V.One);
                wx = Sel16(over, wx * f, wx); wy = Sel16(over, wy * f, wy); wz = Sel16(over, wz * f, wz);
            }
        }
        if (Vector512.EqualsAny(m, V.Zero)) { var free = Free16(m); wx = Sel16(free, wx, vx); wy = Sel16(free, wy, vy); wz = Sel16(free, wz, vz); }
        St16(ref Vx, r, wx);
        St16(ref Vy, r, wy);
        St16(ref Vz, r, wz);
    }

    // a·b + c, c − a·b and a·b − c, each rounded once (Simd.MulAdd): the sweep is bound by its operation count.
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static V Fma(V a, V b, V c) => Simd.MulAdd(a, b, c);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static V Fnma(V a, V b, V c) => Simd.NegMulAdd(a, b, c);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static V Fms(V a, V b, V c) => Simd.MulSub(a, b, c);

    /// <summary>
    /// Whether some lane is inside the far sphere of <paramref name="p"/>: the ellipsoid kernel's own far test
    /// (FastCollideSystem.FarSphere), the same operations on the same values, so a row it passes is one the kernel skips.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static bool Near16(V x, V y, V z, in SweepParams p)
    {
        var dx = x - Vector512.Create(p.FarX); var dy = y - Vector512.Create(p.FarY); var dz = z - Vector512.Create(p.FarZ);
        return !Vector512.GreaterThanAll(dx * dx + dy * dy + dz * dz, Vector512.Create(p.FarOuter2));
    }

    /// <summary><see cref="Near16"/> for the root row's half from <paramref name="i"/>, and some lane of it free.</summary>
    private static bool NearFree16(ref float X, ref float Y, ref float Z, ref float M, int i, in SweepParams p) =>
        !Vector512.EqualsAll(Ld16(ref M, i), V.Zero) && Near16(Ld16(ref X, i), Ld16(ref Y, i), Ld16(ref Z, i), in p);

    /// <summary>The free lanes (inverse mass m ≠ 0): the mask the rare paths select by.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static V Free16(V m) => ~Vector512.Equals(m, V.Zero);

    /// <summary>The lanes whose segment is long enough to give a direction: len &gt; 10⁻⁶·rest length, and len &gt; 0.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static V OkLen(V len, V rl) => Vector512.GreaterThan(len, Vector512.Create(1e-6f) * rl) & Vector512.GreaterThan(len, V.Zero);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static V Ld16(ref float r, int i) => Vector512.LoadUnsafe(ref r, (nuint)i);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void St16(ref float r, int i, V v) => v.StoreUnsafe(ref r, (nuint)i);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static V Ld16(ref float r, nuint i) => Vector512.LoadUnsafe(ref r, i);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void St16(ref float r, nuint i, V v) => v.StoreUnsafe(ref r, i);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static V Sel16(V mask, V ifTrue, V ifFalse) => Vector512.ConditionalSelect(mask, ifTrue, ifFalse);
}
