namespace HairSim;

/// <summary>
/// Time integration of free particles: v += h·gravity, velocity damping, a speed limit (guard), x += h·v.
/// Shape matching has already added its velocity change for this substep.
/// </summary>
public sealed class IntegrateSystem : IHairSystem
{
    public const string SystemName = "Integrate";
    public string Name => SystemName;
    public SystemPhase Phase => SystemPhase.Substep;

    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var w = scene.World;
        var st = ctx.Settings;
        double h = ctx.H;
        double gx = st.Gravity.X, gy = st.Gravity.Y, gz = st.Gravity.Z;
        double keep = Math.Max(0.0, 1.0 - st.Damping * h);
        double maxSpeed = st.MaxSpeed;
        for (int s = begin; s < end; s++)
        {
            int first = w.StrandFirst[s], last = first + w.StrandParticleCount[s];
            for (int i = first; i < last; i++)
            {
                if (w.InvMass[i] == 0f) continue;
                double vx = (w.VelX[i] + h * gx) * keep, vy = (w.VelY[i] + h * gy) * keep, vz = (w.VelZ[i] + h * gz) * keep;
                if (maxSpeed > 0)
                {
                    double sp = Math.Sqrt(vx * vx + vy * vy + vz * vz);
                    if (sp > maxSpeed) { double f = maxSpeed / sp; vx *= f; vy *= f; vz *= f; }
                }
                w.VelX[i] = (float)vx; w.VelY[i] = (float)vy; w.VelZ[i] = (float)vz;
                w.PosX[i] = (float)(w.PosX[i] + h * vx);
                w.PosY[i] = (float)(w.PosY[i] + h * vy);
                w.PosZ[i] = (float)(w.PosZ[i] + h * vz);
            }
        }
    }
}
