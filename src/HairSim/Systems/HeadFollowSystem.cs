namespace HairSim;

/// <summary>
/// Roots follow the head: pinned particles are placed at head·rest for each substep (the head pose is
/// interpolated across substeps). On a teleport frame every particle is first carried rigidly with the
/// head, so a sudden jump does not stretch the hair.
/// </summary>
public sealed class HeadFollowSystem : IHairSystem
{
    public const string SystemName = "HeadFollow";
    public string Name => SystemName;
    public SystemPhase Phase => SystemPhase.Substep;

    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var w = scene.World;
        if (substep == 0 && ctx.Teleported) CarryRigidly(w, ctx.TeleportDelta, begin, end);
        var head = ctx.HeadAt(substep);
        for (int s = begin; s < end; s++)
        {
            int first = w.StrandFirst[s], last = first + w.StrandParticleCount[s];
            for (int i = first; i < last; i++)
            {
                if (w.InvMass[i] != 0f) continue;
                w.PutPosition(i, head.TransformPoint(w.GetRest(i)));
                w.VelX[i] = w.VelY[i] = w.VelZ[i] = 0f;
            }
        }
    }

    internal static void CarryRigidly(HairWorld w, in RigidTransform delta, int begin, int end)
    {
        for (int s = begin; s < end; s++)
        {
            int first = w.StrandFirst[s], last = first + w.StrandCapacity[s];
            for (int i = first; i < last; i++)
            {
                w.PutPosition(i, delta.TransformPoint(w.GetPosition(i)));
                w.PutVelocity(i, delta.TransformDirection(w.GetVelocity(i)));
            }
        }
    }
}
