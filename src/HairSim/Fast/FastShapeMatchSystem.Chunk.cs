using System.Runtime.CompilerServices;
using System.Runtime.Intrinsics;
using System.Runtime.Intrinsics.X86;

namespace HairSim.Fast;

/// <summary>
/// Shape matching on a <see cref="StrandChunk"/>: <see cref="Strand16"/> turned on its side. Row t of the chunk is
/// triple t of 32 strands, so a triple reads rows t − 1, t, t + 1 (no shuffles), and particle j sums the goal rows
/// prev[j + 1] + mid[j] + next[j − 1] (rows past the ends are zero). Same arithmetic, same order, as Strand16.
/// </summary>
public sealed partial class FastShapeMatchSystem : IStrandChunkSystem
{
    bool IStrandChunkSystem.SupportsChunks => _wide;
    ChunkFields IStrandChunkSystem.ChunkNeeds => ChunkFields.Shape;

    /// <summary>The 16-lane path's case: no global stiffness (or nothing to do at all).</summary>
    bool IStrandChunkSystem.BeginChunkFrame(FrameContext ctx) =>
        ctx.Settings.GlobalShapeStiffness == 0f || (ctx.Settings.Alpha <= 0f && ctx.Settings.GlobalShapeStiffness <= 0f);

    int IStrandChunkSystem.RefusedLane(HairWorld w, int s0)
    {
        for (int l = 0; l < StrandChunk.Lanes; l++)
            if (Bent(w, s0 + l, w.StrandFirst[s0 + l], StrandChunk.Rows)) return l;
        return -1;
    }


    bool IStrandChunkSystem.RunChunk(HairScene scene, FrameContext ctx, int substep, scoped in StrandChunk chunk)
    {
        var st = ctx.Settings;
        if (st.Alpha <= 0f) return true;
        // Coinciding triple ends need the reference's fallback axis: the chunk goes back to the per-strand path.
        if (!ChunkGoals(chunk)) return false;
        ChunkVelocities(chunk, GoalFactor(ctx.H, st.Alpha, st.Mode == ShapeMatchMode.LiteralForce));
        return true;
    }

    /// <summary>Goals of triples 1 … 14 into the goal rows; false if some triple's ends coincide.</summary>
    private static bool ChunkGoals(scoped in StrandChunk chunk)
    {
        var third = Vector512.Create(1f / 3f); var eps2 = Vector512.Create(1e-24f);
        var bad = Vector512<float>.Zero;
        for (int lane = 0; lane < StrandChunk.Lanes; lane += 16)
        {
            ref float px = ref Unsafe.Add(ref chunk.Row(StrandChunk.X, 0), lane);
            ref float py = ref Unsafe.Add(ref chunk.Row(StrandChunk.Y, 0), lane);
            ref float pz = ref Unsafe.Add(ref chunk.Row(StrandChunk.Z, 0), lane);
            ref float sp = ref Unsafe.Add(ref chunk.Row(StrandChunk.ShapePrev, 0), lane);
            ref float sm = ref Unsafe.Add(ref chunk.Row(StrandChunk.ShapeMid, 0), lane);
            ref float sn = ref Unsafe.Add(ref chunk.Row(StrandChunk.ShapeNext, 0), lane);
            ref float g = ref Unsafe.Add(ref chunk.GoalRow(0, 0), lane);
            nuint field = (nuint)chunk.Tile.Stride;
            for (int t = 1; t < StrandChunk.Rows - 1; t++)
            {
                nuint r = (nuint)(t * StrandChunk.Lanes), up = r - StrandChunk.Lanes, down = r + StrandChunk.Lanes;
                var bx = Vector512.LoadUnsafe(ref px, r); var by = Vector512.LoadUnsafe(ref py, r); var bz = Vector512.LoadUnsafe(ref pz, r);
                var ax = Vector512.LoadUnsafe(ref px, up) - bx; var ay = Vector512.LoadUnsafe(ref py, up) - by; var az = Vector512.LoadUnsafe(ref pz, up) - bz;
                var cx = Vector512.LoadUnsafe(ref px, down) - bx; var cy = Vector512.LoadUnsafe(ref py, down) - by; var cz = Vector512.LoadUnsafe(ref pz, down) - bz;
                var ox = (ax + cx) * third; var oy = (ay + cy) * third; var oz = (az + cz) * third;
                var ex = cx - ax; var ey = cy - ay; var ez = cz - az;
                var len2 = ex * ex + ey * ey + ez * ez;
                var ok = Vector512.GreaterThan(len2, eps2);
                bad |= ~ok;
                var l2 = Vector512.ConditionalSelect(ok, len2, Vector512<float>.One);
                var inv = Simd.InvSqrt14x16(l2);
                ex *= inv; ey *= inv; ez *= inv;
                var pa = Vector512.LoadUnsafe(ref sp, r); var pm = Vector512.LoadUnsafe(ref sm, r); var pn = Vector512.LoadUnsafe(ref sn, r);
                ((ox - ax) + pa * ex).StoreUnsafe(ref g, r); ((oy - ay) + pa * ey).StoreUnsafe(ref g, r + field);
                ((oz - az) + pa * ez).StoreUnsafe(ref g, r + 2 * field);
                (ox + pm * ex).StoreUnsafe(ref g, r + 3 * field); (oy + pm * ey).StoreUnsafe(ref g, r + 4 * field);
                (oz + pm * ez).StoreUnsafe(ref g, r + 5 * field);
                ((ox - cx) + pn * ex).StoreUnsafe(ref g, r + 6 * field); ((oy - cy) + pn * ey).StoreUnsafe(ref g, r + 7 * field);
                ((oz - cz) + pn * ez).StoreUnsafe(ref g, r + 8 * field);
            }
        }
        return bad == Vector512<float>.Zero;
    }

    /// <summary>v += f_j · (prev goal of triple j + 1 + mid goal of triple j + next goal of triple j − 1) on free particles.</summary>
    private static void ChunkVelocities(scoped in StrandChunk chunk, float f)
    {
        // α/h over the goal count: 1 at the root and the tip, 2 next to them, 3 elsewhere (as Consts16.F).
        var fOne = Vector512.Create(f); var fHalf = Vector512.Create(f / 2f); var fThird = Vector512.Create(f / 3f);
        nuint field = (nuint)chunk.Tile.Stride, lanes = StrandChunk.Lanes;
        ref float g = ref chunk.GoalRow(0, 0);
        ref float m = ref chunk.Row(StrandChunk.InvMass, 0);
        ref float vx = ref chunk.Row(StrandChunk.VelX, 0); ref float vy = ref chunk.Row(StrandChunk.VelY, 0); ref float vz = ref chunk.Row(StrandChunk.VelZ, 0);
        for (int j = 0; j < StrandChunk.Rows; j++)
        {
            var fj = j == 0 || j == StrandChunk.Rows - 1 ? fOne : j == 1 || j == StrandChunk.Rows - 2 ? fHalf : fThird;
            for (int lane = 0; lane < StrandChunk.Lanes; lane += 16)
            {
                nuint r = (nuint)(j * StrandChunk.Lanes + lane);
                var sx = Vector512.LoadUnsafe(ref g, r + lanes) + Vector512.LoadUnsafe(ref g, r + 3 * field) + Vector512.LoadUnsafe(ref g, r + 6 * field - lanes);
                var sy = Vector512.LoadUnsafe(ref g, r + field + lanes) + Vector512.LoadUnsafe(ref g, r + 4 * field) + Vector512.LoadUnsafe(ref g, r + 7 * field - lanes);
                var sz = Vector512.LoadUnsafe(ref g, r + 2 * field + lanes) + Vector512.LoadUnsafe(ref g, r + 5 * field) + Vector512.LoadUnsafe(ref g, r + 8 * field - lanes);
                var apply = ~Vector512.Equals(Vector512.LoadUnsafe(ref m, r), Vector512<float>.Zero);
                var x = Vector512.LoadUnsafe(ref vx, r); var y = Vector512.LoadUnsafe(ref vy, r); var z = Vector512.LoadUnsafe(ref vz, r);
                Vector512.ConditionalSelect(apply, x + fj * sx, x).StoreUnsafe(ref vx, r);
                Vector512.ConditionalSelect(apply, y + fj * sy, y).StoreUnsafe(ref vy, r);
                Vector512.ConditionalSelect(apply, z + fj * sz, z).StoreUnsafe(ref vz, r);
            }
        }
    }
}
