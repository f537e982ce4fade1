namespace HairSim;

/// <summary>
/// Inextensibility, which the source lacks (its shape matching alone lets a hanging strand stretch).
/// FollowTheLeader: Müller et al. 2012 (DFTL): each particle is put back at its rest distance from the
/// previous one, root to tip, and velocity gets v_i += Δx_i/h − s·Δx_{i+1}/h.
/// Pbd: Gauss–Seidel distance constraints (pinned particles do not move), velocity v += Δx/h.
/// </summary>
public sealed class LengthSystem : IHairSystem
{
    public const string SystemName = "Length";
    public string Name => SystemName;
    public SystemPhase Phase => SystemPhase.Substep;

    private readonly double[] _dx, _dy, _dz;

    /// <summary>
    /// Whether the bend sweep already puts every particle at its rest length (follow-the-leader fused in), leaving this
    /// pass nothing to do: always under <see cref="BendModel.RestShape"/>, whose sweep is inextensible by construction
    /// (the length mode applies to the other bend models).
    /// </summary>
    public static bool FusedIntoBend(SimulationSettings st) => st.Bend == BendModel.RestShape;

    public LengthSystem(int maxStrandCapacity)
    {
        _dx = new double[maxStrandCapacity + 1]; _dy = new double[maxStrandCapacity + 1]; _dz = new double[maxStrandCapacity + 1];
    }

    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var w = scene.World;
        var st = ctx.Settings;
        if (LengthSystem.FusedIntoBend(st)) return;
        double h = ctx.H;
        for (int s = begin; s < end; s++)
        {
            if (st.Length == LengthMode.FollowTheLeader && w.IsFreeStrand(s)) FreeStrands.Relax(w, s, h);
            else if (st.Length == LengthMode.FollowTheLeader) FollowTheLeader(w, s, h, st.LengthDamping, ctx.HeadAt(substep));
            else if (st.Length == LengthMode.Pbd) Pbd(w, s, h, st.LengthIterations);
        }
    }

    private void FollowTheLeader(HairWorld w, int s, double h, double damping, in RigidTransform head)
    {
        int first = w.StrandFirst[s], n = w.StrandParticleCount[s];
        _dx[0] = _dy[0] = _dz[0] = 0;
        for (int k = 1; k < n; k++)
        {
            int i = first + k;
            _dx[k] = _dy[k] = _dz[k] = 0;
            if (w.InvMass[i] == 0f) continue;
            double px = w.PosX[i - 1], py = w.PosY[i - 1], pz = w.PosZ[i - 1];
            double ex = w.PosX[i] - px, ey = w.PosY[i] - py, ez = w.PosZ[i] - pz;
            double len = Math.Sqrt(ex * ex + ey * ey + ez * ez);
            if (len < 1e-12)
            {
                var axis = head.TransformDirection(w.GetRest(i) - w.GetRest(i - 1));
                ex = axis.X; ey = axis.Y; ez = axis.Z;
                len = Math.Sqrt(ex * ex + ey * ey + ez * ez);
                if (len < 1e-12) { ex = 0; ey = -1; ez = 0; len = 1; }
            }
            double r = w.RestLength[i] / len;
            double tx = px + ex * r, ty = py + ey * r, tz = pz + ez * r;
            _dx[k] = tx - w.PosX[i]; _dy[k] = ty - w.PosY[i]; _dz[k] = tz - w.PosZ[i];
            w.PosX[i] = (float)tx; w.PosY[i] = (float)ty; w.PosZ[i] = (float)tz;
        }
        _dx[n] = _dy[n] = _dz[n] = 0;
        for (int k = 1; k < n; k++)
        {
            int i = first + k;
            if (w.InvMass[i] == 0f) continue;
            w.VelX[i] = (float)(w.VelX[i] + (_dx[k] - damping * _dx[k + 1]) / h);
            w.VelY[i] = (float)(w.VelY[i] + (_dy[k] - damping * _dy[k + 1]) / h);
            w.VelZ[i] = (float)(w.VelZ[i] + (_dz[k] - damping * _dz[k + 1]) / h);
        }
    }

    private void Pbd(HairWorld w, int s, double h, int iterations)
    {
        int first = w.StrandFirst[s], n = w.StrandParticleCount[s];
        for (int k = 0; k < n; k++) { int i = first + k; _dx[k] = w.PosX[i]; _dy[k] = w.PosY[i]; _dz[k] = w.PosZ[i]; }
        for (int it = 0; it < iterations; it++)
        {
            for (int k = 1; k < n; k++)
            {
                int i = first + k;
                double wa = w.InvMass[i - 1], wb = w.InvMass[i];
                if (wa + wb == 0) continue;
                double ex = w.PosX[i] - w.PosX[i - 1], ey = w.PosY[i] - w.PosY[i - 1], ez = w.PosZ[i] - w.PosZ[i - 1];
                double len = Math.Sqrt(ex * ex + ey * ey + ez * ez);
                if (len < 1e-12) continue;
                double c = (len - w.RestLength[i]) / (len * (wa + wb));
                w.PosX[i - 1] = (float)(w.PosX[i - 1] + wa * c * ex); w.PosY[i - 1] = (float)(w.PosY[i - 1] + wa * c * ey); w.PosZ[i - 1] = (float)(w.PosZ[i - 1] + wa * c * ez);
                w.PosX[i] = (float)(w.PosX[i] - wb * c * ex); w.PosY[i] = (float)(w.PosY[i] - wb * c * ey); w.PosZ[i] = (float)(w.PosZ[i] - wb * c * ez);
            }
        }
        for (int k = 0; k < n; k++)
        {
            int i = first + k;
            if (w.InvMass[i] == 0f) continue;
            w.VelX[i] = (float)(w.VelX[i] + (w.PosX[i] - _dx[k]) / h);
            w.VelY[i] = (float)(w.VelY[i] + (w.PosY[i] - _dy[k]) / h);
            w.VelZ[i] = (float)(w.VelZ[i] + (w.PosZ[i] - _dz[k]) / h);
        }
    }
}
