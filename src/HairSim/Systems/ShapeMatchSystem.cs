using System.Numerics;

namespace HairSim;

/// <summary>
/// Stretch and bend by shape matching (SPEC A.3), reference implementation in double precision.
/// For every interior particle k the triple (k−1, k, k+1) gets goals: its rest shape (see <see cref="RestShape"/>)
/// placed at the triple's centroid along the direction p[k+1] − p[k−1]. Each particle's goal is the mean of
/// the goals it received, and it is pulled there:
///   Muller:       v += α(ḡ − x)/h      (integrate then does v += h·g, x += h·v)
///   LiteralForce: v += h·α(ḡ − x)      (the source's force = gravity + α(ḡ − x))
/// Optionally a global pull to the head-space rest pose, v += β(head·rest − x)/h.
/// </summary>
public sealed class ShapeMatchSystem : IHairSystem
{
    public const string SystemName = "ShapeMatch";
    public string Name => SystemName;
    public SystemPhase Phase => SystemPhase.Substep;

    // Scratch for one strand's goal sums: sized once, so a step allocates nothing. Single-threaded by design.
    private readonly double[] _gx, _gy, _gz;
    private readonly int[] _count;

    public ShapeMatchSystem(int maxStrandCapacity)
    {
        _gx = new double[maxStrandCapacity]; _gy = new double[maxStrandCapacity]; _gz = new double[maxStrandCapacity];
        _count = new int[maxStrandCapacity];
    }

    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var w = scene.World;
        var st = ctx.Settings;
        double h = ctx.H, alpha = st.Alpha, beta = st.GlobalShapeStiffness;
        bool literal = st.Mode == ShapeMatchMode.LiteralForce;
        var head = ctx.HeadAt(substep);
        for (int s = begin; s < end; s++)
        {
            int first = w.StrandFirst[s], n = w.StrandParticleCount[s];
            if (alpha > 0) AccumulateGoals(w, s, head, _gx, _gy, _gz, _count);
            for (int k = 0; k < n; k++)
            {
                int i = first + k;
                if (w.InvMass[i] == 0f) continue;
                double x = w.PosX[i], y = w.PosY[i], z = w.PosZ[i];
                double dvx = 0, dvy = 0, dvz = 0;
                if (alpha > 0 && _count[k] > 0)
                {
                    double m = _count[k];
                    double dx = _gx[k] / m - x, dy = _gy[k] / m - y, dz = _gz[k] / m - z;
                    double f = literal ? h * alpha : alpha / h;
                    dvx += f * dx; dvy += f * dy; dvz += f * dz;
                }
                if (beta > 0)
                {
                    var g = head.TransformPoint(w.GetRest(i));
                    dvx += beta * (g.X - x) / h; dvy += beta * (g.Y - y) / h; dvz += beta * (g.Z - z) / h;
                }
                w.VelX[i] = (float)(w.VelX[i] + dvx);
                w.VelY[i] = (float)(w.VelY[i] + dvy);
                w.VelZ[i] = (float)(w.VelZ[i] + dvz);
            }
        }
    }

    /// <summary>
    /// Sums of the goals each particle of strand s receives, and how many it receives (the source's m).
    /// Public so tests and tools can look at the goals themselves.
    /// </summary>
    public static void AccumulateGoals(HairWorld w, int s, in RigidTransform head, double[] gx, double[] gy, double[] gz, int[] count)
    {
        int first = w.StrandFirst[s], n = w.StrandParticleCount[s];
        Array.Clear(gx, 0, n); Array.Clear(gy, 0, n); Array.Clear(gz, 0, n); Array.Clear(count, 0, n);
        // Rest-to-current rotation carried from the root along the strand (only needed for bent rest shapes).
        var frame = head.Rotation;
        for (int k = 1; k < n - 1; k++)
        {
            int i = first + k;
            frame = TransportFrame(w, i, frame);
            double ax = w.PosX[i - 1], ay = w.PosY[i - 1], az = w.PosZ[i - 1];
            double bx = w.PosX[i], by = w.PosY[i], bz = w.PosZ[i];
            double cx = w.PosX[i + 1], cy = w.PosY[i + 1], cz = w.PosZ[i + 1];
            double ox = (ax + bx + cx) / 3, oy = (ay + by + cy) / 3, oz = (az + bz + cz) / 3;
            double ex = cx - ax, ey = cy - ay, ez = cz - az;
            double len = Math.Sqrt(ex * ex + ey * ey + ez * ez);
            if (len > 1e-12) { ex /= len; ey /= len; ez /= len; }
            else
            {
                // p[k−1] and p[k+1] coincide: the source would divide by zero. Use the rest axis carried by the head.
                var axis = head.TransformDirection(w.GetRest(i + 1) - w.GetRest(i - 1));
                double al = axis.Length();
                if (al > 1e-12) { ex = axis.X / al; ey = axis.Y / al; ez = axis.Z / al; }
                else { ex = 0; ey = -1; ez = 0; }
            }
            double pa = w.ShapePrev[i], pm = w.ShapeMid[i], pn = w.ShapeNext[i], bend = w.ShapeBend[i];
            double nx = 0, ny = 0, nz = 0;
            if (bend != 0)
            {
                // Bend direction: the rest pose's, turned by the frame carried from the root, made perpendicular
                // to the current axis. Taking it from the current triple alone would leave twist free, and a curl
                // would relax into a zigzag whose bends alternate.
                BendDirection(w, i, frame, ex, ey, ez, bx - ox, by - oy, bz - oz, len, out nx, out ny, out nz);
            }
            int j = k - 1;
            gx[j] += ox + pa * ex - 0.5 * bend * nx; gy[j] += oy + pa * ey - 0.5 * bend * ny; gz[j] += oz + pa * ez - 0.5 * bend * nz; count[j]++;
            j = k;
            gx[j] += ox + pm * ex + bend * nx; gy[j] += oy + pm * ey + bend * ny; gz[j] += oz + pm * ez + bend * nz; count[j]++;
            j = k + 1;
            gx[j] += ox + pn * ex - 0.5 * bend * nx; gy[j] += oy + pn * ey - 0.5 * bend * ny; gz[j] += oz + pn * ez - 0.5 * bend * nz; count[j]++;
        }
    }

    /// <summary>
    /// Unit bend direction of triple i: the rest pose's direction (middle particle away from the rest axis),
    /// turned by the rest-to-current frame rotation and made perpendicular to the current axis e. Falls back to the current middle
    /// offset (ux, uy, uz), then to any perpendicular, so it is always finite.
    /// </summary>
    public static void BendDirection(HairWorld w, int i, Quaternion frame, double ex, double ey, double ez,
        double ux, double uy, double uz, double axisLength, out double nx, out double ny, out double nz)
    {
        double ax = w.RestX[i - 1], ay = w.RestY[i - 1], az = w.RestZ[i - 1];
        double bx = w.RestX[i], by = w.RestY[i], bz = w.RestZ[i];
        double cx = w.RestX[i + 1], cy = w.RestY[i + 1], cz = w.RestZ[i + 1];
        double rx = cx - ax, ry = cy - ay, rz = cz - az;
        double rl = Math.Sqrt(rx * rx + ry * ry + rz * rz);
        if (rl > 1e-12) { rx /= rl; ry /= rl; rz /= rl; }
        double mx = bx - (ax + bx + cx) / 3, my = by - (ay + by + cy) / 3, mz = bz - (az + bz + cz) / 3;
        double along = mx * rx + my * ry + mz * rz;
        var rest = Vector3.Transform(new Vector3((float)(mx - along * rx), (float)(my - along * ry), (float)(mz - along * rz)), frame);
        double dx = rest.X, dy = rest.Y, dz = rest.Z;
        double restLength = Math.Sqrt(dx * dx + dy * dy + dz * dz);
        along = dx * ex + dy * ey + dz * ez;
        dx -= along * ex; dy -= along * ey; dz -= along * ez;
        double dl = Math.Sqrt(dx * dx + dy * dy + dz * dz);
        if (dl > 1e-3 * restLength && dl > 1e-15) { nx = dx / dl; ny = dy / dl; nz = dz / dl; return; }
        along = ux * ex + uy * ey + uz * ez;
        ux -= along * ex; uy -= along * ey; uz -= along * ez;
        double ul = Math.Sqrt(ux * ux + uy * uy + uz * uz);
        if (ul > 1e-9 * (axisLength + 1e-12)) { nx = ux / ul; ny = uy / ul; nz = uz / ul; return; }
        var p = RestShape.AnyPerpendicular(new Vector3((float)ex, (float)ey, (float)ez));
        nx = p.X; ny = p.Y; nz = p.Z;
    }

    /// <summary>
    /// Carries the rest-to-current rotation across the segment ending at particle i: the rest segment, turned by
    /// the frame so far, is brought onto the current segment by the smallest rotation (parallel transport).
    /// </summary>
    public static Quaternion TransportFrame(HairWorld w, int i, Quaternion frame)
    {
        var rest = new Vector3(w.RestX[i] - w.RestX[i - 1], w.RestY[i] - w.RestY[i - 1], w.RestZ[i] - w.RestZ[i - 1]);
        var cur = new Vector3(w.PosX[i] - w.PosX[i - 1], w.PosY[i] - w.PosY[i - 1], w.PosZ[i] - w.PosZ[i - 1]);
        float rl = rest.Length(), cl = cur.Length();
        if (rl < 1e-12f || cl < 1e-12f) return frame;
        var a = Vector3.Transform(rest / rl, frame);
        var b = cur / cl;
        float d = Vector3.Dot(a, b);
        if (d < -0.9999f) return frame; // folded back: no unique smallest rotation, keep the frame
        var c = Vector3.Cross(a, b);
        var turn = Quaternion.Normalize(new Quaternion(c, 1f + d));
        return Quaternion.Normalize(turn * frame);
    }
}
