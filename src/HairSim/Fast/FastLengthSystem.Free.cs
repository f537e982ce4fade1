namespace HairSim.Fast;

public sealed partial class FastLengthSystem
{
    /// <summary>
    /// Strands of [begin, end) in tiles, except free strands under follow-the-leader, which take
    /// <see cref="FreeStrands.Relax"/> one by one (nothing holds their root to lead from). PBD already weighs both ends
    /// of a segment by their inverse masses, so it keeps every strand in its tiles.
    /// </summary>
    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var w = scene.World;
        var st = ctx.Settings;
        if (w.FreeStrandCount == 0 || st.Length != LengthMode.FollowTheLeader || LengthSystem.FusedIntoBend(st))
        {
            RunTiles(scene, ctx, substep, begin, end);
            return;
        }
        int from = begin;
        for (int s = begin; s < end; s++)
        {
            if (!w.IsFreeStrand(s)) continue;
            if (from < s) RunTiles(scene, ctx, substep, from, s);
            FreeStrands.Relax(w, s, ctx.H);
            from = s + 1;
        }
        if (from < end) RunTiles(scene, ctx, substep, from, end);
    }
}
