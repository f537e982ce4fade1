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
    /// <summary>Sweep constants broadcast to 16 lanes.</summary>
    private readonly struct Consts16
    {
        public readonly V H, InvH, Reaction, FallX, FallY, FallZ, Eps, Flip, MaxSpeed, MaxSpeedSq;

        public Consts16(in SweepParams p)
        {
            H = Vector512.Create(p.H); InvH = Vector512.Create(p.InvH); Reaction = Vector512.Create(p.Reaction); MaxSpeed = Vector512.Create(p.MaxSpeed); MaxSpeedSq = Vector512.Create(p.MaxSpeed * p.MaxSpeed);
            FallX = Vector512.Create(p.FallX); FallY = Vector512.Create(p.FallY); FallZ = Vector512.Create(p.FallZ);
            Eps = Vector512.Create(1e-6f); Flip = Vector512.Create(-0.9999f);
        }
    }

    /// <summary><see cref="Sweep"/> on 16-lane vectors.</summary>
    [SkipLocalsInit]
    private static void Sweep16(ref float d, ref float rest, int rows, in SweepParams p)
    {
        const int width = 16; int lanes = p.Lanes;
        var c = new Consts16(in p);
        var one = V.One;
        var zero = V.Zero;
        Span<float> stateSpan = stackalloc float[Slots * lanes];
        ref float s = ref stateSpan[0];
        for (int h = 0; h < lanes; h += width)
        {
            St16(ref s, Sqx * lanes + h, Vector512.Create(p.Qx)); St16(ref s, Sqy * lanes + h, Vector512.Create(p.Qy));
            St16(ref s, Sqz * lanes + h, Vector512.Create(p.Qz)); St16(ref s, Sqw * lanes + h, Vector512.Create(p.Qw));
            // Direction, turn and correction start at zero. The root is never kicked: it follows the head.
            for (int slot = Sdx; slot < Slots; slot++) St16(ref s, slot * lanes + h, zero);
        }
        for (int k = 1; k < rows; k++)
        {
            for (int h = 0; h < lanes; h += width)
            {
                int r = k * lanes + h;
                var qx = Ld16(ref s, Sqx * lanes + h); var qy = Ld16(ref s, Sqy * lanes + h); var qz = Ld16(ref s, Sqz * lanes + h); var qw = Ld16(ref s, Sqw * lanes + h);
                var px = Ld16(ref d, p.Ox + r - lanes); var py = Ld16(ref d, p.Oy + r - lanes); var pz = Ld16(ref d, p.Oz + r - lanes);
                var x = Ld16(ref d, p.Ox + r); var y = Ld16(ref d, p.Oy + r); var z = Ld16(ref d, p.Oz + r);
                var free = ~Vector512.Equals(Ld16(ref d, p.Om + r), zero);
                var rl = Ld16(ref d, p.Ol + r);
                var rx = Ld16(ref rest, p.Orx + r); var ry = Ld16(ref rest, p.Ory + r); var rz = Ld16(ref rest, p.Orz + r);
                var ex = x - px; var ey = y - py; var ez = z - pz;
                var len = Vector512.Sqrt(ex * ex + ey * ey + ez * ez);
                var hasLen = Vector512.GreaterThan(len, zero);
                // Masks that are all set (the common case: every lane a live, moving, non-degenerate segment) make
                // their selects identities, so those are skipped: the same bits with fewer operations.
                bool allLen = AllSet(hasLen);
                var inv = allLen ? one / len : Sel16(hasLen, one / Sel16(hasLen, len, one), zero);
                var ux0 = ex * inv; var uy0 = ey * inv; var uz0 = ez * inv;
                // Target: the rest direction turned by the frame carried from the root (v' = v + 2w(q×v) + 2q×(q×v)).
                // With c = 2q×v (the doubling by adds: the sweep is bound by its multiplies): v' = v + w·c + q×c.
                var q2x = qx + qx; var q2y = qy + qy; var q2z = qz + qz;
                var cx = q2y * rz - q2z * ry; var cy = q2z * rx - q2x * rz; var cz = q2x * ry - q2y * rx;
                var tx = rx + qw * cx + (qy * cz - qz * cy); var ty = ry + qw * cy + (qz * cx - qx * cz); var tz = rz + qw * cz + (qx * cy - qy * cx);
                // A rest direction to turn (any component non-zero, by bits: no multiplies).
                var restOk = ~Vector512.Equals((rx.AsUInt32() | ry.AsUInt32() | rz.AsUInt32()) & Vector512.Create(0x7fffffffu), Vector512<uint>.Zero).AsSingle();
                if (!AllSet(restOk))
                {
                    tx = Sel16(restOk, tx, Sel16(hasLen, ux0, zero));
                    ty = Sel16(restOk, ty, Sel16(hasLen, uy0, Vector512.Create(-1f)));
                    tz = Sel16(restOk, tz, Sel16(hasLen, uz0, zero));
                }
                var okLen = Vector512.GreaterThan(len, c.Eps * rl) & hasLen;
                V dx = ux0, dy = uy0, dz = uz0;
                if (!AllSet(okLen)) { dx = Sel16(okLen, ux0, tx); dy = Sel16(okLen, uy0, ty); dz = Sel16(okLen, uz0, tz); }
                // How far this segment turned since the substep's start (see BendSystem).
                var hvx = c.H * Ld16(ref d, p.Ovx + r); var hvy = c.H * Ld16(ref d, p.Ovy + r); var hvz = c.H * Ld16(ref d, p.Ovz + r);
                var ux = hvx - (c.H * Ld16(ref d, p.Ovx + r - lanes) + Ld16(ref s, SDx * lanes + h));
                var uy = hvy - (c.H * Ld16(ref d, p.Ovy + r - lanes) + Ld16(ref s, SDy * lanes + h));
                var uz = hvz - (c.H * Ld16(ref d, p.Ovz + r - lanes) + Ld16(ref s, SDz * lanes + h));
                var along = ux * dx + uy * dy + uz * dz;
                var tcx = (ux - along * dx) * inv; var tcy = (uy - along * dy) * inv; var tcz = (uz - along * dz) * inv;
                // Target turned with the parent: Δt = (d_p × c_p) × t.
                var pdx = Ld16(ref s, Sdx * lanes + h); var pdy = Ld16(ref s, Sdy * lanes + h); var pdz = Ld16(ref s, Sdz * lanes + h);
                var pcx = Ld16(ref s, Scx * lanes + h); var pcy = Ld16(ref s, Scy * lanes + h); var pcz = Ld16(ref s, Scz * lanes + h);
                var wx = pdy * pcz - pdz * pcy; var wy = pdz * pcx - pdx * pcz; var wz = pdx * pcy - pdy * pcx;
                var ttx = wy * tz - wz * ty; var tty = wz * tx - wx * tz; var ttz = wx * ty - wy * tx;
                // The joint's spring and dashpot shares, cached per strand for this h (see CacheShares).
                var a = Ld16(ref rest, p.Oa + r); var b = Ld16(ref rest, p.Ob + r);
                var ox = dx - tx; var oy = dy - ty; var oz = dz - tz;
                var sx = ox - (tcx - ttx); var sy = oy - (tcy - tty); var sz = oz - (tcz - ttz);
                var mx = tx + a * ox + b * sx; var my = ty + a * oy + b * sy; var mz = tz + a * oz + b * sz;
                var ml = Vector512.Sqrt(mx * mx + my * my + mz * mz);
                var mOk = Vector512.GreaterThan(ml, c.Eps);
                bool allFree = AllSet(free);
                if (AllSet(mOk))
                {
                    var invM = one / ml;
                    if (allFree) { dx = mx * invM; dy = my * invM; dz = mz * invM; }
                    else { dx = Sel16(free, mx * invM, dx); dy = Sel16(free, my * invM, dy); dz = Sel16(free, mz * invM, dz); }
                }
                else
                {
                    var invM = one / Sel16(mOk, ml, one);
                    var ndx = Sel16(mOk, mx * invM, tx); var ndy = Sel16(mOk, my * invM, ty); var ndz = Sel16(mOk, mz * invM, tz);
                    dx = Sel16(free, ndx, dx); dy = Sel16(free, ndy, dy); dz = Sel16(free, ndz, dz);
                }
                var nx = px + dx * rl; var ny = py + dy * rl; var nz = pz + dz * rl;
                V cdx = nx - x, cdy = ny - y, cdz = nz - z;
                if (!allFree) { cdx = Sel16(free, cdx, zero); cdy = Sel16(free, cdy, zero); cdz = Sel16(free, cdz, zero); }
                x += cdx; y += cdy; z += cdz;
                St16(ref d, p.Ox + r, x); St16(ref d, p.Oy + r, y); St16(ref d, p.Oz + r, z);
                // The row above takes its kick now that this row's correction is known.
                Kick16(ref d, in p, in c, r - lanes, k == 1 ? zero : ~Vector512.Equals(Ld16(ref d, p.Om + r - lanes), zero),
                    Ld16(ref s, SDx * lanes + h), Ld16(ref s, SDy * lanes + h), Ld16(ref s, SDz * lanes + h),
                    cdx + (allFree ? c.FallX : Sel16(free, c.FallX, zero)), cdy + (allFree ? c.FallY : Sel16(free, c.FallY, zero)),
                    cdz + (allFree ? c.FallZ : Sel16(free, c.FallZ, zero)));
                St16(ref s, SDx * lanes + h, cdx); St16(ref s, SDy * lanes + h, cdy); St16(ref s, SDz * lanes + h, cdz);
                // This segment's turn over the substep so far, for its child.
                ux += cdx; uy += cdy; uz += cdz;
                along = ux * dx + uy * dy + uz * dz;
                St16(ref s, Scx * lanes + h, (ux - along * dx) * inv); St16(ref s, Scy * lanes + h, (uy - along * dy) * inv);
                St16(ref s, Scz * lanes + h, (uz - along * dz) * inv);
                St16(ref s, Sdx * lanes + h, dx); St16(ref s, Sdy * lanes + h, dy); St16(ref s, Sdz * lanes + h, dz);
                // Frame: the smallest rotation taking t onto d, then the frame so far (identity if they are opposite).
                var dot = tx * dx + ty * dy + tz * dz;
                var fx = ty * dz - tz * dy; var fy = tz * dx - tx * dz; var fz = tx * dy - ty * dx; var fw = one + dot;
                var flip = Vector512.LessThan(dot, c.Flip);
                if (flip != V.Zero) { fx = Sel16(flip, zero, fx); fy = Sel16(flip, zero, fy); fz = Sel16(flip, zero, fz); fw = Sel16(flip, one, fw); }
                // f normalised by its own length (not 2(1 + t·d), which amplifies any error in |t| near a flip), and
                // f∘q left as it is: a product of unit quaternions, and q is rebuilt from the head every substep.
                var fInv = one / Vector512.Sqrt(fx * fx + fy * fy + fz * fz + fw * fw);
                fx *= fInv; fy *= fInv; fz *= fInv; fw *= fInv;
                var nqx = fw * qx + fx * qw + fy * qz - fz * qy;
                var nqy = fw * qy - fx * qz + fy * qw + fz * qx;
                var nqz = fw * qz + fx * qy - fy * qx + fz * qw;
                var nqw = fw * qw - fx * qx - fy * qy - fz * qz;
                St16(ref s, Sqx * lanes + h, nqx); St16(ref s, Sqy * lanes + h, nqy);
                St16(ref s, Sqz * lanes + h, nqz); St16(ref s, Sqw * lanes + h, nqw);
            }
        }
        if (rows < 2) return;
        for (int h = 0; h < lanes; h += width)
            Kick16(ref d, in p, in c, (rows - 1) * lanes + h, ~Vector512.Equals(Ld16(ref d, p.Om + (rows - 1) * lanes + h), zero),
                Ld16(ref s, SDx * lanes + h), Ld16(ref s, SDy * lanes + h), Ld16(ref s, SDz * lanes + h), zero, zero, zero);
    }

    /// <summary>v += (Δ − s·next) / h on the free lanes of row r.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Kick16(ref float d, in SweepParams p, in Consts16 c, int r, V free, V dx, V dy, V dz, V nx, V ny, V nz)
    {
        var vx = Ld16(ref d, p.Ovx + r); var vy = Ld16(ref d, p.Ovy + r); var vz = Ld16(ref d, p.Ovz + r);
        var wx = vx + (dx - c.Reaction * nx) * c.InvH; var wy = vy + (dy - c.Reaction * ny) * c.InvH; var wz = vz + (dz - c.Reaction * nz) * c.InvH;
        // Squared speeds compared, the root taken only where a lane is over the limit.
        var speedSq = wx * wx + wy * wy + wz * wz;
        var over = Vector512.GreaterThan(speedSq, c.MaxSpeedSq);
        if (over != V.Zero)
        {
            var f = c.MaxSpeed / Sel16(over, Vector512.Sqrt(speedSq), V.One);
            wx = Sel16(over, wx * f, wx); wy = Sel16(over, wy * f, wy); wz = Sel16(over, wz * f, wz);
        }
        if (!AllSet(free)) { wx = Sel16(free, wx, vx); wy = Sel16(free, wy, vy); wz = Sel16(free, wz, vz); }
        St16(ref d, p.Ovx + r, wx);
        St16(ref d, p.Ovy + r, wy);
        St16(ref d, p.Ovz + r, wz);
    }

    /// <summary>Every lane of the mask set.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static bool AllSet(V mask) => Vector512.EqualsAll(mask.AsInt32(), Vector512<int>.AllBitsSet);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static V Ld16(ref float r, int i) => Vector512.LoadUnsafe(ref r, (nuint)i);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void St16(ref float r, int i, V v) => v.StoreUnsafe(ref r, (nuint)i);

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static V Sel16(V mask, V ifTrue, V ifFalse) => Vector512.ConditionalSelect(mask, ifTrue, ifFalse);
}
