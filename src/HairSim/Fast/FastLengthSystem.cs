using System.Numerics;
using System.Runtime.CompilerServices;

namespace HairSim.Fast;

/// <summary>
/// Fast <see cref="LengthSystem"/> in float. Follow-the-leader is a chain along each strand (particle k needs
/// particle k−1 already corrected), so it cannot be vectorised along the strand; it is vectorised across
/// strands instead: Width strands are transposed into a small per-thread tile (row k = particle k of each
/// strand), swept root to tip together, and written back. PBD runs the same way with its Gauss–Seidel sweeps.
/// Lanes past a strand's live count, and padding lanes of the last group, are masked out (InvMass 0).
/// </summary>
public sealed class FastLengthSystem : IHairSystem
{
    public string Name => LengthSystem.SystemName;
    public SystemPhase Phase => SystemPhase.Substep;

    // Tile fields, each maxCapacity rows × Width lanes.
    private const int TX = 0, TY = 1, TZ = 2, TVx = 3, TVy = 4, TVz = 5, TM = 6, TL = 7, TOx = 8, TOy = 9, TOz = 10, FieldCount = 11;

    private readonly int _maxCapacity;

    public FastLengthSystem(int maxStrandCapacity) => _maxCapacity = maxStrandCapacity;

    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var st = ctx.Settings;
        if (st.Length == LengthMode.None) return;
        var w = scene.World;
        int width = Vector<float>.Count;
        // The tile is a StrandScratch whose "capacity" is rows × lanes.
        var scratch = StrandScratch.For(_maxCapacity * width, FieldCount);
        var head = new PoseLanes(ctx.HeadAt(substep));
        Span<int> firsts = stackalloc int[width];
        Span<int> counts = stackalloc int[width];
        for (int s0 = begin; s0 < end; s0 += width)
        {
            int lanes = Math.Min(width, end - s0);
            int rows = 0;
            for (int l = 0; l < width; l++)
            {
                firsts[l] = l < lanes ? w.StrandFirst[s0 + l] : 0;
                counts[l] = l < lanes ? w.StrandParticleCount[s0 + l] : 0;
                rows = Math.Max(rows, counts[l]);
            }
            Gather(w, scratch, firsts, counts, rows);
            if (st.Length == LengthMode.FollowTheLeader) FollowTheLeader(w, scratch, firsts, counts, rows, ctx.H, st.LengthDamping, in head);
            else Pbd(scratch, rows, ctx.H, st.LengthIterations);
            Scatter(w, scratch, firsts, counts);
        }
    }

    private static void Gather(HairWorld w, StrandScratch t, ReadOnlySpan<int> firsts, ReadOnlySpan<int> counts, int rows)
    {
        int width = Vector<float>.Count;
        float[] d = t.Data;
        int ox = t.Offset(TX), oy = t.Offset(TY), oz = t.Offset(TZ), ovx = t.Offset(TVx), ovy = t.Offset(TVy), ovz = t.Offset(TVz),
            om = t.Offset(TM), ol = t.Offset(TL);
        // Masked lanes: InvMass 0 (never moved) at a finite position; their results are never written back.
        d.AsSpan(om, rows * width).Clear();
        d.AsSpan(ox, rows * width).Clear(); d.AsSpan(oy, rows * width).Clear(); d.AsSpan(oz, rows * width).Clear();
        d.AsSpan(ol, rows * width).Clear();
        for (int l = 0; l < width; l++)
        {
            int first = firsts[l], n = counts[l];
            for (int k = 0; k < n; k++)
            {
                int i = first + k, r = k * width + l;
                d[ox + r] = w.PosX[i]; d[oy + r] = w.PosY[i]; d[oz + r] = w.PosZ[i];
                d[ovx + r] = w.VelX[i]; d[ovy + r] = w.VelY[i]; d[ovz + r] = w.VelZ[i];
                d[om + r] = w.InvMass[i]; d[ol + r] = w.RestLength[i];
            }
        }
    }

    private static void Scatter(HairWorld w, StrandScratch t, ReadOnlySpan<int> firsts, ReadOnlySpan<int> counts)
    {
        int width = Vector<float>.Count;
        float[] d = t.Data;
        int ox = t.Offset(TX), oy = t.Offset(TY), oz = t.Offset(TZ), ovx = t.Offset(TVx), ovy = t.Offset(TVy), ovz = t.Offset(TVz);
        for (int l = 0; l < width; l++)
        {
            int first = firsts[l], n = counts[l];
            for (int k = 0; k < n; k++)
            {
                int i = first + k, r = k * width + l;
                w.PosX[i] = d[ox + r]; w.PosY[i] = d[oy + r]; w.PosZ[i] = d[oz + r];
                w.VelX[i] = d[ovx + r]; w.VelY[i] = d[ovy + r]; w.VelZ[i] = d[ovz + r];
            }
        }
    }

    private static void FollowTheLeader(HairWorld w, StrandScratch t, ReadOnlySpan<int> firsts, ReadOnlySpan<int> counts, int rows,
                                        float h, float damping, in PoseLanes head)
    {
        int width = Vector<float>.Count;
        ref float d = ref t.Data[0];
        int ox = t.Offset(TX), oy = t.Offset(TY), oz = t.Offset(TZ), ovx = t.Offset(TVx), ovy = t.Offset(TVy), ovz = t.Offset(TVz),
            om = t.Offset(TM), ol = t.Offset(TL);
        var invH = new Vector<float>(1f / h);
        var damp = new Vector<float>(damping);
        var eps = new Vector<float>(1e-12f);
        var px = Simd.Ld(ref d, ox); var py = Simd.Ld(ref d, oy); var pz = Simd.Ld(ref d, oz);
        Vector<float> dxPrev = default, dyPrev = default, dzPrev = default;
        Vector<int> freePrev = default;
        for (int k = 1; k < rows; k++)
        {
            int r = k * width;
            var x = Simd.Ld(ref d, ox + r); var y = Simd.Ld(ref d, oy + r); var z = Simd.Ld(ref d, oz + r);
            var free = ~Vector.Equals(Simd.Ld(ref d, om + r), Vector<float>.Zero);
            var ex = x - px; var ey = y - py; var ez = z - pz;
            var len = Vector.SquareRoot(ex * ex + ey * ey + ez * ez);
            var degenerate = free & Vector.LessThan(len, eps);
            if (!Vector.EqualsAll(degenerate, Vector<int>.Zero))
                RestAxis(w, firsts, k, degenerate, in head, ref ex, ref ey, ref ez, ref len);
            var ratio = Simd.Ld(ref d, ol + r) / Simd.Sel(free, len, Vector<float>.One);
            // Correction d = leader + e·ratio − x. With e = x − leader that is e·(ratio − 1), which keeps float
            // rounding at segment scale (the reference computes it in double); a fallback axis uses the long form.
            var corr = ratio - Vector<float>.One;
            var dx = Simd.Sel(free, Simd.Sel(degenerate, (px - x) + ex * ratio, ex * corr), Vector<float>.Zero);
            var dy = Simd.Sel(free, Simd.Sel(degenerate, (py - y) + ey * ratio, ey * corr), Vector<float>.Zero);
            var dz = Simd.Sel(free, Simd.Sel(degenerate, (pz - z) + ez * ratio, ez * corr), Vector<float>.Zero);
            var tx = x + dx; var ty = y + dy; var tz = z + dz;
            Simd.St(ref d, ox + r, tx); Simd.St(ref d, oy + r, ty); Simd.St(ref d, oz + r, tz);
            // Velocity of particle k−1 now that its successor's correction is known: v += (d[k−1] − s·d[k]) / h.
            if (k >= 2) Kick(ref d, (k - 1) * width, ovx, ovy, ovz, freePrev, dxPrev - damp * dx, dyPrev - damp * dy, dzPrev - damp * dz, invH);
            px = tx; py = ty; pz = tz;
            dxPrev = dx; dyPrev = dy; dzPrev = dz; freePrev = free;
        }
        if (rows >= 2) Kick(ref d, (rows - 1) * width, ovx, ovy, ovz, freePrev, dxPrev, dyPrev, dzPrev, invH);
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Kick(ref float d, int r, int ovx, int ovy, int ovz, Vector<int> free,
                             Vector<float> cx, Vector<float> cy, Vector<float> cz, Vector<float> invH)
    {
        var vx = Simd.Ld(ref d, ovx + r); var vy = Simd.Ld(ref d, ovy + r); var vz = Simd.Ld(ref d, ovz + r);
        Simd.St(ref d, ovx + r, Simd.Sel(free, vx + cx * invH, vx));
        Simd.St(ref d, ovy + r, Simd.Sel(free, vy + cy * invH, vy));
        Simd.St(ref d, ovz + r, Simd.Sel(free, vz + cz * invH, vz));
    }

    /// <summary>Coincident neighbours (the reference's fallback): the edge takes the rest direction carried by the head, else −Y.</summary>
    private static void RestAxis(HairWorld w, ReadOnlySpan<int> firsts, int k, Vector<int> degenerate, in PoseLanes head,
                                 ref Vector<float> ex, ref Vector<float> ey, ref Vector<float> ez, ref Vector<float> len)
    {
        int width = Vector<float>.Count;
        Span<float> buf = stackalloc float[4 * width];
        ex.CopyTo(buf); ey.CopyTo(buf.Slice(width)); ez.CopyTo(buf.Slice(2 * width)); len.CopyTo(buf.Slice(3 * width));
        for (int l = 0; l < width; l++)
        {
            if (degenerate[l] == 0) continue;
            int i = firsts[l] + k;
            var axis = head.Direction(w.GetRest(i) - w.GetRest(i - 1));
            float al = axis.Length();
            if (al < 1e-12f) { axis = -Vector3.UnitY; al = 1f; }
            buf[l] = axis.X; buf[width + l] = axis.Y; buf[2 * width + l] = axis.Z; buf[3 * width + l] = al;
        }
        ex = new Vector<float>(buf); ey = new Vector<float>(buf.Slice(width)); ez = new Vector<float>(buf.Slice(2 * width)); len = new Vector<float>(buf.Slice(3 * width));
    }

    private static void Pbd(StrandScratch t, int rows, float h, int iterations)
    {
        int width = Vector<float>.Count;
        ref float d = ref t.Data[0];
        int ox = t.Offset(TX), oy = t.Offset(TY), oz = t.Offset(TZ), ovx = t.Offset(TVx), ovy = t.Offset(TVy), ovz = t.Offset(TVz),
            om = t.Offset(TM), ol = t.Offset(TL), oox = t.Offset(TOx), ooy = t.Offset(TOy), ooz = t.Offset(TOz);
        int cells = rows * width;
        t.Data.AsSpan(ox, cells).CopyTo(t.Data.AsSpan(oox, cells));
        t.Data.AsSpan(oy, cells).CopyTo(t.Data.AsSpan(ooy, cells));
        t.Data.AsSpan(oz, cells).CopyTo(t.Data.AsSpan(ooz, cells));
        var eps = new Vector<float>(1e-12f);
        for (int it = 0; it < iterations; it++)
        {
            for (int k = 1; k < rows; k++)
            {
                int a = (k - 1) * width, b = k * width;
                var wa = Simd.Ld(ref d, om + a); var wb = Simd.Ld(ref d, om + b);
                var wsum = wa + wb;
                var ax = Simd.Ld(ref d, ox + a); var ay = Simd.Ld(ref d, oy + a); var az = Simd.Ld(ref d, oz + a);
                var bx = Simd.Ld(ref d, ox + b); var by = Simd.Ld(ref d, oy + b); var bz = Simd.Ld(ref d, oz + b);
                var ex = bx - ax; var ey = by - ay; var ez = bz - az;
                var len = Vector.SquareRoot(ex * ex + ey * ey + ez * ez);
                var act = ~Vector.Equals(wsum, Vector<float>.Zero) & Vector.GreaterThanOrEqual(len, eps);
                if (Vector.EqualsAll(act, Vector<int>.Zero)) continue;
                var c = Simd.Sel(act, (len - Simd.Ld(ref d, ol + b)) / Simd.Sel(act, len * wsum, Vector<float>.One), Vector<float>.Zero);
                var ca = wa * c; var cb = wb * c;
                Simd.St(ref d, ox + a, ax + ca * ex); Simd.St(ref d, oy + a, ay + ca * ey); Simd.St(ref d, oz + a, az + ca * ez);
                Simd.St(ref d, ox + b, bx - cb * ex); Simd.St(ref d, oy + b, by - cb * ey); Simd.St(ref d, oz + b, bz - cb * ez);
            }
        }
        var invH = new Vector<float>(1f / h);
        for (int r = 0; r < cells; r += width)
        {
            var free = ~Vector.Equals(Simd.Ld(ref d, om + r), Vector<float>.Zero);
            Kick(ref d, r, ovx, ovy, ovz, free,
                Simd.Ld(ref d, ox + r) - Simd.Ld(ref d, oox + r), Simd.Ld(ref d, oy + r) - Simd.Ld(ref d, ooy + r),
                Simd.Ld(ref d, oz + r) - Simd.Ld(ref d, ooz + r), invH);
        }
    }
}
