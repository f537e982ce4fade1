using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.Intrinsics;
using System.Runtime.Intrinsics.X86;

namespace HairSim.Fast;

/// <summary>
/// The follow-the-leader sweep over a 32-strand tile in two 16-lane (AVX-512) chains: the same arithmetic, in the
/// same order, as <see cref="FollowTheLeader"/> over two 8-lane chains (the reciprocal square root is the AVX
/// estimate of each half, so the bits are the same), with twice the strands per row latency.
/// </summary>
public sealed partial class FastLengthSystem : IStrandChunkSystem
{
    bool IStrandChunkSystem.SupportsChunks => UsesWide;
    ChunkFields IStrandChunkSystem.ChunkNeeds => ChunkFields.RestLength;
    /// <summary>Each substep's head pose (the sweep's fallback axis), built once per frame for all chunks.</summary>
    private PoseLanes[] _chunkHeads = [];

    bool IStrandChunkSystem.BeginChunkFrame(FrameContext ctx)
    {
        if (ctx.Settings.Length is not (LengthMode.None or LengthMode.FollowTheLeader)) return false;
        if (_chunkHeads.Length < ctx.Substeps) _chunkHeads = new PoseLanes[ctx.Substeps];
        for (int s = 0; s < ctx.Substeps; s++) _chunkHeads[s] = new PoseLanes(ctx.HeadAt(s));
        return true;
    }

    /// <summary>
    /// The sweep on a chunk, whose first slots are this system's tile fields: no gather or scatter, only the velocity
    /// kicks added to the chunk's velocities (as <see cref="Scatter"/> adds them to the world's).
    /// </summary>
    bool IStrandChunkSystem.RunChunk(HairScene scene, FrameContext ctx, int substep, scoped in StrandChunk chunk)
    {
        var st = ctx.Settings;
        if (st.Length == LengthMode.None || LengthSystem.FusedIntoBend(st)) return true;
        FollowTheLeader16(scene.World, chunk.Tile, chunk.Firsts, StrandChunk.Rows, ctx.H, st.LengthDamping, in _chunkHeads[substep]);
        for (int f = 0; f < 3; f++)
        {
            ref float v = ref chunk.Row(StrandChunk.VelX + f, 0);
            ref float kick = ref chunk.Row(StrandChunk.KickX + f, 0);
            for (int i = 0; i < StrandChunk.Cells; i += 16)
                (Vector512.LoadUnsafe(ref v, (nuint)i) + Vector512.LoadUnsafe(ref kick, (nuint)i)).StoreUnsafe(ref v, (nuint)i);
        }
        return true;
    }

    private static void FollowTheLeader16(HairWorld w, scoped StrandScratch t, ReadOnlySpan<int> firsts, int rows, float h, float damping, in PoseLanes head)
    {
        const int W = 16;
        ref float d = ref t.Data[0];
        var p = new FtlParams(t, h, damping, firsts.Length);
        var invH = Vector512.Create(1f / h); var damp = Vector512.Create(damping); var eps2 = Vector512.Create(1e-24f);
        var ax = Vector512.LoadUnsafe(ref d, (nuint)p.Ox); var ay = Vector512.LoadUnsafe(ref d, (nuint)p.Oy); var az = Vector512.LoadUnsafe(ref d, (nuint)p.Oz);
        var bx = Vector512.LoadUnsafe(ref d, (nuint)(p.Ox + W)); var by = Vector512.LoadUnsafe(ref d, (nuint)(p.Oy + W)); var bz = Vector512.LoadUnsafe(ref d, (nuint)(p.Oz + W));
        Vector512<float> adx = default, ady = default, adz = default, bdx = default, bdy = default, bdz = default, aFree = default, bFree = default;
        int k = 1;
        for (; k < rows; k++)
        {
            int ra = k * p.Lanes, rb = ra + W;
            var xa = Vector512.LoadUnsafe(ref d, (nuint)(p.Ox + ra)); var ya = Vector512.LoadUnsafe(ref d, (nuint)(p.Oy + ra)); var za = Vector512.LoadUnsafe(ref d, (nuint)(p.Oz + ra));
            var xb = Vector512.LoadUnsafe(ref d, (nuint)(p.Ox + rb)); var yb = Vector512.LoadUnsafe(ref d, (nuint)(p.Oy + rb)); var zb = Vector512.LoadUnsafe(ref d, (nuint)(p.Oz + rb));
            var freeA = ~Vector512.Equals(Vector512.LoadUnsafe(ref d, (nuint)(p.Om + ra)), Vector512<float>.Zero);
            var freeB = ~Vector512.Equals(Vector512.LoadUnsafe(ref d, (nuint)(p.Om + rb)), Vector512<float>.Zero);
            var exa = xa - ax; var eya = ya - ay; var eza = za - az;
            var exb = xb - bx; var eyb = yb - by; var ezb = zb - bz;
            var len2a = exa * exa + eya * eya + eza * eza;
            var len2b = exb * exb + eyb * eyb + ezb * ezb;
            var degenerate = (freeA & Vector512.LessThan(len2a, eps2)) | (freeB & Vector512.LessThan(len2b, eps2));
            if (degenerate != Vector512<float>.Zero) break;
            Advance16(ref d, in p, k, ra, xa, ya, za, exa, eya, eza, len2a, freeA, damp, invH, ref ax, ref ay, ref az, ref adx, ref ady, ref adz, ref aFree);
            Advance16(ref d, in p, k, rb, xb, yb, zb, exb, eyb, ezb, len2b, freeB, damp, invH, ref bx, ref by, ref bz, ref bdx, ref bdy, ref bdz, ref bFree);
        }
        if (k < rows)
        {
            // Hand the four 8-lane halves to the general step, which has the reference's fallback axis.
            SweepWithFallback(w, t, firsts, rows, k, h, damping, in head,
                Half(ax, ay, az, adx, ady, adz, aFree, upper: false), Half(ax, ay, az, adx, ady, adz, aFree, upper: true),
                Half(bx, by, bz, bdx, bdy, bdz, bFree, upper: false), Half(bx, by, bz, bdx, bdy, bdz, bFree, upper: true));
            return;
        }
        if (rows >= 2)
        {
            int r = (rows - 1) * p.Lanes;
            Kick16(ref d, r, in p, aFree, adx, ady, adz, invH);
            Kick16(ref d, r + W, in p, bFree, bdx, bdy, bdz, invH);
        }
    }

    /// <summary>Row k of one 16-lane chain whose neighbours do not coincide (see <see cref="Advance"/>).</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Advance16(ref float d, in FtlParams p, int k, int r, Vector512<float> x, Vector512<float> y, Vector512<float> z,
        Vector512<float> ex, Vector512<float> ey, Vector512<float> ez, Vector512<float> len2, Vector512<float> free, Vector512<float> damp, Vector512<float> invH,
        ref Vector512<float> cx, ref Vector512<float> cy, ref Vector512<float> cz, ref Vector512<float> cdx, ref Vector512<float> cdy, ref Vector512<float> cdz,
        ref Vector512<float> cFree)
    {
        var l2 = Vector512.ConditionalSelect(free, len2, Vector512<float>.One);
        var inv = Simd.InvSqrt16(l2);
        var corr = Vector512.LoadUnsafe(ref d, (nuint)(p.Ol + r)) * inv - Vector512<float>.One;
        corr = Vector512.ConditionalSelect(free, corr, Vector512<float>.Zero);
        var dx = ex * corr; var dy = ey * corr; var dz = ez * corr;
        var tx = x + dx; var ty = y + dy; var tz = z + dz;
        tx.StoreUnsafe(ref d, (nuint)(p.Ox + r)); ty.StoreUnsafe(ref d, (nuint)(p.Oy + r)); tz.StoreUnsafe(ref d, (nuint)(p.Oz + r));
        if (k >= 2) Kick16(ref d, r - p.Lanes, in p, cFree, cdx - damp * dx, cdy - damp * dy, cdz - damp * dz, invH);
        cx = tx; cy = ty; cz = tz;
        cdx = dx; cdy = dy; cdz = dz; cFree = free;
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Kick16(ref float d, int r, in FtlParams p, Vector512<float> free, Vector512<float> cx, Vector512<float> cy, Vector512<float> cz, Vector512<float> invH)
    {
        Vector512.ConditionalSelect(free, cx * invH, Vector512<float>.Zero).StoreUnsafe(ref d, (nuint)(p.Ovx + r));
        Vector512.ConditionalSelect(free, cy * invH, Vector512<float>.Zero).StoreUnsafe(ref d, (nuint)(p.Ovy + r));
        Vector512.ConditionalSelect(free, cz * invH, Vector512<float>.Zero).StoreUnsafe(ref d, (nuint)(p.Ovz + r));
    }

    private static Chain Half(Vector512<float> px, Vector512<float> py, Vector512<float> pz, Vector512<float> dx, Vector512<float> dy, Vector512<float> dz,
        Vector512<float> free, bool upper) => upper
        ? new Chain { Px = px.GetUpper().AsVector(), Py = py.GetUpper().AsVector(), Pz = pz.GetUpper().AsVector(),
                      Dx = dx.GetUpper().AsVector(), Dy = dy.GetUpper().AsVector(), Dz = dz.GetUpper().AsVector(), Free = free.AsInt32().GetUpper().AsVector() }
        : new Chain { Px = px.GetLower().AsVector(), Py = py.GetLower().AsVector(), Pz = pz.GetLower().AsVector(),
                      Dx = dx.GetLower().AsVector(), Dy = dy.GetLower().AsVector(), Dz = dz.GetLower().AsVector(), Free = free.AsInt32().GetLower().AsVector() };
}
