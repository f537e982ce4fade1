using System.Numerics;

namespace HairSim;

/// <summary>
/// The default shape model (<see cref="BendModel.RestShape"/>), reference implementation in double precision.
/// After integration, one sweep from root to tip: segment k's target direction is its rest direction (head space)
/// turned by the frame carried from the root (parallel transport, so twist and curls are held); the segment keeps
/// a share of its deviation from the target set by an implicit spring and dashpot per joint (<see cref="BendProfile"/>:
/// any substep is stable and the held shape does not depend on h), the particle is placed along the new direction
/// at its rest length (follow-the-leader fused in: the sweep is inextensible by itself, whatever the length mode), and
/// its velocity takes the move: v += Δx/h − s·Δx_next/h (Müller 2012's reaction, s = <see cref="ReactionShare"/>).
/// See docs/styles.md for why this model and what it measures.
/// </summary>
public sealed class BendSystem : IHairSystem
{
    public const string SystemName = "Bend";
    public string Name => SystemName;
    public SystemPhase Phase => SystemPhase.Substep;

    private readonly double[] _dx, _dy, _dz;
    private readonly float[] _t2;
    // Per strand: the world's edit stamp + 1 and the Sag its profile was computed for (0: never).
    private readonly long[] _profileAt;
    private readonly float[] _profileSag;

    /// <summary>
    /// Share of each child's correction given back to its parent's velocity as a reaction (Müller 2012's s). Without
    /// it a one-sided sweep is a follower force and flutters once substeps are short against the joints' time
    /// constants; at 0.7 and above curls flutter at the finest substeps. 0.5 was stable over the whole sweep of
    /// docs/styles.md (1 cm … 10 m, 30 … 240 Hz, 1 … 64 substeps).
    /// </summary>
    public const double ReactionShare = 0.5;

    public BendSystem(HairWorld world)
    {
        int cap = world.MaxStrandCapacity;
        _dx = new double[cap + 1]; _dy = new double[cap + 1]; _dz = new double[cap + 1];
        _t2 = new float[world.ParticleCount];
        _profileAt = new long[world.StrandCount];
        _profileSag = new float[world.StrandCount];
    }

    /// <summary>Strand s's joint profile, recomputed after an edit or a change of Sag (each strand is one job's, so no race).</summary>
    internal static void EnsureProfile(HairWorld w, int s, float sag, float[] t2, long[] at, float[] atSag)
    {
        long stamp = w.EditStamp + 1L;
        if (at[s] == stamp && atSag[s] == sag) return;
        BendProfile.Compute(w, s, sag, t2);
        at[s] = stamp; atSag[s] = sag;
    }

    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var w = scene.World;
        var st = ctx.Settings;
        if (st.Bend != BendModel.RestShape) return;
        double h = ctx.H;
        const double damping = ReactionShare;
        // What integration added to each free particle's move this substep through gravity (h²·g·κ, κ the damping
        // factor): at rest the sweep takes exactly that back, and the reaction below leaves it out (see Sweep).
        double kappa = Math.Max(0.0, 1.0 - st.Damping * h);
        var fall = new Vector3D(st.Gravity.X * h * h * kappa, st.Gravity.Y * h * h * kappa, st.Gravity.Z * h * h * kappa);
        var head = ctx.HeadAt(substep);
        for (int s = begin; s < end; s++)
        {
            EnsureProfile(w, s, st.Sag, _t2, _profileAt, _profileSag);
            Sweep(w, s, h, damping, st.BendDamping, st.MaxSpeed > 0f ? st.MaxSpeed : double.PositiveInfinity, fall, head);
        }
    }

    private void Sweep(HairWorld w, int s, double h, double damping, double zeta, double maxSpeed, in Vector3D fall, in RigidTransform head)
    {
        int first = w.StrandFirst[s], n = w.StrandParticleCount[s];
        // Nothing holds a free strand's root for the sweep to lead from; joint j's T² is at _t2[first + j] (see BendProfile).
        if (w.IsFreeStrand(s)) { FreeStrands.Relax(w, s, h, _t2, first); return; }
        var q = new QuatD(head.Rotation);
        double hh = h * h, zeta2h = 2 * zeta * h;
        // The parent segment's direction and its change over this substep's prediction (h × its angular rate, from
        // the velocities integration left): the root's parent is the head, taken as still within a substep.
        double pdx = 0, pdy = 0, pdz = 0, pcx = 0, pcy = 0, pcz = 0;
        _dx[0] = _dy[0] = _dz[0] = 0;
        for (int k = 1; k < n; k++)
        {
            int i = first + k;
            _dx[k] = _dy[k] = _dz[k] = 0;
            // Target: the rest segment turned by the frame carried from the root.
            double rx = w.RestX[i] - w.RestX[i - 1], ry = w.RestY[i] - w.RestY[i - 1], rz = w.RestZ[i] - w.RestZ[i - 1];
            double rl = Math.Sqrt(rx * rx + ry * ry + rz * rz);
            double px = w.PosX[i - 1], py = w.PosY[i - 1], pz = w.PosZ[i - 1];
            double ex = w.PosX[i] - px, ey = w.PosY[i] - py, ez = w.PosZ[i] - pz;
            double len = Math.Sqrt(ex * ex + ey * ey + ez * ez);
            double tx, ty, tz;
            if (rl > 0) { q.Rotate(rx / rl, ry / rl, rz / rl, out tx, out ty, out tz); }
            else if (len > 0) { tx = ex / len; ty = ey / len; tz = ez / len; }
            else { tx = 0; ty = -1; tz = 0; }
            double dx, dy, dz;
            if (len > 1e-6 * w.RestLength[i] && len > 0) { dx = ex / len; dy = ey / len; dz = ez / len; }
            else { dx = tx; dy = ty; dz = tz; }
            // How far this segment turned since the substep's start: the child's predicted move h·v_k against the
            // parent's whole move so far (h·v_{k−1} plus its correction in this sweep), across the segment / length.
            double ux = h * w.VelX[i] - (h * w.VelX[i - 1] + _dx[k - 1]);
            double uy = h * w.VelY[i] - (h * w.VelY[i - 1] + _dy[k - 1]);
            double uz = h * w.VelZ[i] - (h * w.VelZ[i - 1] + _dz[k - 1]);
            double along = ux * dx + uy * dy + uz * dz, inv = len > 0 ? 1 / len : 0;
            double cx = (ux - along * dx) * inv, cy = (uy - along * dy) * inv, cz = (uz - along * dz) * inv;
            if (w.InvMass[i] != 0f)
            {
                // The target turned with the parent over the prediction: Δt = (d_p × Δd_p) × t.
                double wx = pdy * pcz - pdz * pcy, wy = pdz * pcx - pdx * pcz, wz = pdx * pcy - pdy * pcx;
                double ttx = wy * tz - wz * ty, tty = wz * tx - wx * tz, ttz = wx * ty - wy * tx;
                // Deviation from the target now (predicted) and at the substep's start; implicit spring-dashpot:
                // δ' = (T²·δ + 2ζhT·δ_start) / (T² + 2ζhT + h²).
                double t2 = _t2[i - 1], tt = Math.Sqrt(t2);
                double ox = dx - tx, oy = dy - ty, oz = dz - tz;
                double sx = ox - (cx - ttx), sy = oy - (cy - tty), sz = oz - (cz - ttz);
                double den = t2 + zeta2h * tt + hh;
                double a = den > 0 ? t2 / den : 0, b = den > 0 ? zeta2h * tt / den : 0;
                double mx = tx + a * ox + b * sx, my = ty + a * oy + b * sy, mz = tz + a * oz + b * sz;
                double ml = Math.Sqrt(mx * mx + my * my + mz * mz);
                if (ml > 1e-6) { dx = mx / ml; dy = my / ml; dz = mz / ml; }
                else { dx = tx; dy = ty; dz = tz; }
                double l = w.RestLength[i];
                double nx = px + dx * l, ny = py + dy * l, nz = pz + dz * l;
                _dx[k] = nx - w.PosX[i]; _dy[k] = ny - w.PosY[i]; _dz[k] = nz - w.PosZ[i];
                w.PosX[i] = (float)nx; w.PosY[i] = (float)ny; w.PosZ[i] = (float)nz;
            }
            // The turn this segment made over the whole substep so far, for its child's target (Δt above).
            ux += _dx[k]; uy += _dy[k]; uz += _dz[k];
            along = ux * dx + uy * dy + uz * dz;
            pcx = (ux - along * dx) * inv; pcy = (uy - along * dy) * inv; pcz = (uz - along * dz) * inv;
            pdx = dx; pdy = dy; pdz = dz;
            q = QuatD.FromTo(tx, ty, tz, dx, dy, dz).Mul(q);
        }
        // The reaction of each child's correction on its parent (Müller 2012's −s·Δx_next/h), which keeps a
        // one-sided sweep from pumping energy in (a push without a reaction is a follower force and flutters).
        // The part of the correction that only holds the child up against gravity is carried down the strand to the
        // root, not into the parent's velocity: so a strand at rest has zero velocity and its sag does not depend on s.
        for (int k = 1; k < n; k++)
        {
            if (w.InvMass[first + k] == 0f) continue;
            _dx[k] += fall.X; _dy[k] += fall.Y; _dz[k] += fall.Z;
        }
        _dx[n] = _dy[n] = _dz[n] = 0;
        for (int k = 1; k < n; k++)
        {
            int i = first + k;
            if (w.InvMass[i] == 0f) continue;
            double vx = w.VelX[i] + (_dx[k] - fall.X - damping * _dx[k + 1]) / h;
            double vy = w.VelY[i] + (_dy[k] - fall.Y - damping * _dy[k + 1]) / h;
            double vz = w.VelZ[i] + (_dz[k] - fall.Z - damping * _dz[k + 1]) / h;
            // The sweep writes velocities last (collision only takes speed away): the speed limit is a bound here.
            double speed = Math.Sqrt(vx * vx + vy * vy + vz * vz);
            if (speed > maxSpeed) { double f = maxSpeed / speed; vx *= f; vy *= f; vz *= f; }
            w.VelX[i] = (float)vx; w.VelY[i] = (float)vy; w.VelZ[i] = (float)vz;
        }
    }

    internal readonly record struct Vector3D(double X, double Y, double Z);

    /// <summary>A unit quaternion in double precision (the reference path's frames).</summary>
    internal readonly struct QuatD
    {
        public readonly double X, Y, Z, W;
        public QuatD(double x, double y, double z, double w) { X = x; Y = y; Z = z; W = w; }
        public QuatD(Quaternion q) : this(q.X, q.Y, q.Z, q.W) { }

        /// <summary>v' = v + 2w(q×v) + 2q×(q×v).</summary>
        public void Rotate(double vx, double vy, double vz, out double ox, out double oy, out double oz)
        {
            double cx = Y * vz - Z * vy, cy = Z * vx - X * vz, cz = X * vy - Y * vx;
            double ccx = Y * cz - Z * cy, ccy = Z * cx - X * cz, ccz = X * cy - Y * cx;
            ox = vx + 2 * (W * cx + ccx); oy = vy + 2 * (W * cy + ccy); oz = vz + 2 * (W * cz + ccz);
        }

        /// <summary>this ∘ o (o first).</summary>
        public QuatD Mul(QuatD o) => new QuatD(
            W * o.X + X * o.W + Y * o.Z - Z * o.Y,
            W * o.Y - X * o.Z + Y * o.W + Z * o.X,
            W * o.Z + X * o.Y - Y * o.X + Z * o.W,
            W * o.W - X * o.X - Y * o.Y - Z * o.Z).Normalized();

        public QuatD Normalized()
        {
            double l = Math.Sqrt(X * X + Y * Y + Z * Z + W * W);
            return new QuatD(X / l, Y / l, Z / l, W / l);
        }

        /// <summary>The smallest rotation taking unit a onto unit b; identity when they are opposite (no unique one).</summary>
        public static QuatD FromTo(double ax, double ay, double az, double bx, double by, double bz)
        {
            double d = ax * bx + ay * by + az * bz;
            if (d < -0.9999) return new QuatD(0, 0, 0, 1);
            double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
            return new QuatD(cx, cy, cz, 1 + d).Normalized();
        }
    }
}
