namespace HairSim.Fast;

public sealed partial class FastBendSystem
{
    /// <summary>
    /// Strands of [begin, end) in tiles, except free strands (no pinned particle), which take <see cref="FreeStrands.Relax"/>
    /// one by one: nothing holds their root for a sweep to lead from. A groom without free strands runs its tiles exactly as before.
    /// </summary>
    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var w = scene.World;
        if (w.FreeStrandCount == 0) { RunTiles(scene, ctx, substep, begin, end); return; }
        var st = ctx.Settings;
        if (st.Bend != BendModel.RestShape) return;
        int from = begin;
        for (int s = begin; s < end; s++)
        {
            if (!w.IsFreeStrand(s)) continue;
            if (from < s) RunTiles(scene, ctx, substep, from, s);
            EnsureCache(w, s, st.Sag, ctx.H, st.BendDamping);
            // _jointT2[first + k] holds joint k − 1.
            FreeStrands.Relax(w, s, ctx.H, _jointT2, w.StrandFirst[s] + 1);
            from = s + 1;
        }
        if (from < end) RunTiles(scene, ctx, substep, from, end);
    }
}
