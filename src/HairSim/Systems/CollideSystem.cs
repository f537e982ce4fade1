namespace HairSim;

/// <summary>
/// Head collision (SPEC A.4, Algorithm 1) against ellipsoids, spheres and capsules: a particle found
/// inside goes back to the surface, its inward velocity is removed and the rest is kept (scaled by
/// ContactSlide), so hair slides along the head. With <see cref="SimulationSettings.StaticFriction"/> or
/// <see cref="SimulationSettings.KineticFriction"/> set, Coulomb friction in position-based form (Macklin et al.
/// 2014, "Unified particle physics for real-time applications", §6.1) also holds the particle along the surface.
/// </summary>
public sealed class CollideSystem : IHairSystem, IStrandResetListener, IStrandMovedListener
{
    public const string SystemName = "Collide";
    public string Name => SystemName;
    public SystemPhase Phase => SystemPhase.Substep;

    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var st = ctx.Settings;
        if (st.StaticFriction > 0f || st.KineticFriction > 0f) { RunWithFriction(scene, ctx, substep, begin, end); return; }
        var w = scene.World;
        _starts.Forget(w, begin, end);
        var colliders = ctx.CollidersAt(substep);
        double slide = st.ContactSlide;
        for (int s = begin; s < end; s++)
        {
            int first = w.StrandFirst[s], last = first + w.StrandParticleCount[s];
            for (int i = first; i < last; i++)
            {
                if (w.InvMass[i] == 0f) continue;
                for (int c = 0; c < colliders.Length; c++)
                {
                    if (!colliders[c].Resolve(w.GetPosition(i), out var surface, out var normal, out _)) continue;
                    w.PutPosition(i, surface);
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

    private readonly FrictionStarts _starts = new();

    /// <summary>A strand put back at its rest pose: the start positions stored for it are stale.</summary>
    void IStrandResetListener.StrandReset(HairWorld world, int strand) => _starts.Forget(world, strand, strand + 1);
    void IStrandMovedListener.StrandMoved(HairWorld world, int strand) => _starts.Moved(world, strand);

    /// <summary>
    /// As <see cref="Run"/>, with friction. Per contact: the particle's displacement over the substep, from its position
    /// at the start of the substep x_start to the surface point, has a tangential part Δx_t (w.r.t. the contact normal).
    /// If |Δx_t| &lt; μs·d (d the depth pushed out) all of it is taken back (static: the particle stays where it was along
    /// the surface), else μk·d of its length (kinetic), and the velocity loses the same Δx_t/h. Then the frictionless
    /// response (inward velocity removed, the rest scaled by ContactSlide). Colliders move with the head: for simplicity
    /// the displacement is taken in world space, not relative to the moving surface, so a head moving under resting hair
    /// drags it along (what friction looks like). x_start: see <see cref="FrictionStarts"/>.
    /// </summary>
    private void RunWithFriction(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var w = scene.World;
        var colliders = ctx.CollidersAt(substep);
        double slide = ctx.Settings.ContactSlide;
        double muS = ctx.Settings.StaticFriction, muK = ctx.Settings.KineticFriction;
        double h = ctx.H;
        var starts = _starts.Ensure(w);
        for (int s = begin; s < end; s++)
        {
            int first = w.StrandFirst[s], last = first + w.StrandParticleCount[s];
            bool stored = starts.Holds(w, ctx, substep, s);
            for (int i = first; i < last; i++)
            {
                if (w.InvMass[i] == 0f) continue;
                double x0, y0, z0;
                if (stored) { x0 = starts.X[i]; y0 = starts.Y[i]; z0 = starts.Z[i]; }
                else { x0 = w.PosX[i] - h * w.VelX[i]; y0 = w.PosY[i] - h * w.VelY[i]; z0 = w.PosZ[i] - h * w.VelZ[i]; }
                for (int c = 0; c < colliders.Length; c++)
                {
                    if (!colliders[c].Resolve(w.GetPosition(i), out var surface, out var normal, out float depth)) continue;
                    // Displacement over the substep, start to pushed-out position, and its tangential part.
                    double dx = surface.X - x0, dy = surface.Y - y0, dz = surface.Z - z0;
                    double dn = dx * normal.X + dy * normal.Y + dz * normal.Z;
                    double tx = dx - dn * normal.X, ty = dy - dn * normal.Y, tz = dz - dn * normal.Z;
                    double len = Math.Sqrt(tx * tx + ty * ty + tz * tz);
                    double take = len < muS * depth ? 1.0 : len > 0 ? Math.Min(muK * depth / len, 1.0) : 0.0;
                    tx *= take; ty *= take; tz *= take;
                    w.PosX[i] = (float)(surface.X - tx); w.PosY[i] = (float)(surface.Y - ty); w.PosZ[i] = (float)(surface.Z - tz);
                    double vx = w.VelX[i] - tx / h, vy = w.VelY[i] - ty / h, vz = w.VelZ[i] - tz / h;
                    double vn = vx * normal.X + vy * normal.Y + vz * normal.Z;
                    if (vn < 0) { vx = (vx - vn * normal.X) * slide; vy = (vy - vn * normal.Y) * slide; vz = (vz - vn * normal.Z) * slide; }
                    w.VelX[i] = (float)vx; w.VelY[i] = (float)vy; w.VelZ[i] = (float)vz;
                }
                starts.X[i] = w.PosX[i]; starts.Y[i] = w.PosY[i]; starts.Z[i] = w.PosZ[i];
            }
            starts.Wrote(w, ctx, substep, s);
        }
    }
}

/// <summary>
/// Where each particle was at the start of the substep, for friction: the collide system runs last in a substep, so
/// the positions it leaves are the next substep's start; it keeps them here (allocated once per world size, on the
/// first friction frame). Not x − h·v: under follow-the-leader the velocity carries the length pass's damping term
/// (−s·Δx_{i+1}/h, Müller 2012) that is not in the positions, so x − h·v is off by s·Δx_{i+1}, the same size as the
/// contact depth, and a strand on a slope creeps down whatever the friction. x − h·v is the fallback where nothing is
/// stored yet: a strand's first friction substep, the first substep after a frame without friction, an edit
/// (<see cref="HairWorld.EditStamp"/>) or a teleport. A stale start can do little harm: the correction is at most
/// max(μs, μk)·d long. Per strand, so threads stepping different strands never share a flag.
/// </summary>
internal sealed class FrictionStarts
{
    private const int EndOfFrame = -1, Unset = -2;
    private readonly object _gate = new();
    private Buffers? _buffers;

    public sealed class Buffers
    {
        public readonly float[] X, Y, Z;
        /// <summary>Per strand: the substep whose end the stored positions are (EndOfFrame: a frame's last), or Unset.</summary>
        private readonly int[] _substep, _stamp;

        public Buffers(int particles, int strands)
        {
            X = new float[particles]; Y = new float[particles]; Z = new float[particles];
            _substep = new int[strands]; _stamp = new int[strands];
            Array.Fill(_substep, Unset);
        }

        public bool Fits(HairWorld w) => X.Length == w.ParticleCount && _substep.Length == w.StrandCount;

        /// <summary>Whether the stored positions of strand s are its positions at the start of this substep.</summary>
        public bool Holds(HairWorld w, FrameContext ctx, int substep, int s) =>
            substep == 0 ? _substep[s] == EndOfFrame && _stamp[s] == w.EditStamp && !ctx.Teleported : _substep[s] == substep - 1;

        public void Wrote(HairWorld w, FrameContext ctx, int substep, int s)
        {
            _substep[s] = substep == ctx.Substeps - 1 ? EndOfFrame : substep;
            _stamp[s] = w.EditStamp;
        }

        /// <summary>Strand s was moved after its last substep: if its end-of-frame positions are stored, the new ones replace them.</summary>
        public void Moved(HairWorld w, int s)
        {
            if (_substep[s] != EndOfFrame) return;
            int first = w.StrandFirst[s], n = w.StrandCapacity[s];
            w.PosX.AsSpan(first, n).CopyTo(X.AsSpan(first, n));
            w.PosY.AsSpan(first, n).CopyTo(Y.AsSpan(first, n));
            w.PosZ.AsSpan(first, n).CopyTo(Z.AsSpan(first, n));
        }

        /// <summary>A frictionless pass over strands [begin, end): what was stored is stale from now on.</summary>
        public void Forget(int begin, int end) => _substep.AsSpan(begin, end - begin).Fill(Unset);
    }

    /// <summary>The buffers for this world, made on first use (under a lock: threads may arrive together).</summary>
    public Buffers Ensure(HairWorld w)
    {
        var b = Volatile.Read(ref _buffers);
        if (b != null && b.Fits(w)) return b;
        lock (_gate)
        {
            b = _buffers;
            if (b == null || !b.Fits(w)) Volatile.Write(ref _buffers, b = new Buffers(w.ParticleCount, w.StrandCount));
            return b;
        }
    }

    /// <summary>Strand s moved outside the substeps (see <see cref="IStrandMovedListener"/>); costs nothing until friction has been used.</summary>
    public void Moved(HairWorld w, int s)
    {
        var b = Volatile.Read(ref _buffers);
        if (b != null && b.Fits(w)) b.Moved(w, s);
    }

    /// <summary>Called by frictionless passes; costs nothing until friction has been used.</summary>
    public void Forget(HairWorld w, int begin, int end)
    {
        var b = Volatile.Read(ref _buffers);
        if (b != null && b.Fits(w)) b.Forget(begin, end);
    }
}
