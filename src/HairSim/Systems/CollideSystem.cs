namespace HairSim;

/// <summary>
/// Head collision (SPEC A.4, Algorithm 1) against ellipsoids, spheres and capsules: a particle found
/// inside goes back to the surface, its inward velocity is removed and the rest is kept (scaled by
/// ContactSlide), so hair slides along the head.
/// </summary>
public sealed class CollideSystem : IHairSystem
{
    public const string SystemName = "Collide";
    public string Name => SystemName;
    public SystemPhase Phase => SystemPhase.Substep;

    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var w = scene.World;
        var colliders = ctx.CollidersAt(substep);
        double slide = ctx.Settings.ContactSlide;
        for (int s = begin; s < end; s++)
        {
            int first = w.StrandFirst[s], last = first + w.StrandParticleCount[s];
            for (int i = first; i < last; i++)
            {
                if (w.InvMass[i] == 0f) continue;
                for (int c = 0; c < colliders.Length; c++)
                {
                    if (!colliders[c].Resolve(w.GetPosition(i), out var surface, out var normal, out _)) continue;
                    w.SetPosition(i, surface);
                    double vx = w.VelX[i], vy = w.VelY[i], vz = w.VelZ[i];
                    double vn = vx * normal.X + vy * normal.Y + vz * normal.Z;
                    if (vn < 0)
                    {
                        vx = (vx - vn * normal.X) * slide; vy = (vy - vn * normal.Y) * slide; vz = (vz - vn * normal.Z) * slide;
                        w.VelX[i] = (float)vx; w.VelY[i] = (float)vy; w.VelZ[i] = (float)vz;
                    }
                }
            }
        }
    }
}
