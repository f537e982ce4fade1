using System.Runtime.CompilerServices;
using System.Numerics;
using System.Runtime.Intrinsics;

namespace HairSim.Fast;

/// <summary>
/// Fast <see cref="CollideSystem"/>: one SIMD pass per collider (particles are independent, so this equals the
/// reference's per-particle loop over colliders). Ellipsoid: radial projection as in <see cref="Collider.Resolve"/>;
/// sphere and capsule share one kernel (a sphere is a capsule with both ends at its centre). Friction (see
/// FastCollideSystem.Friction.cs) runs in the same kernels on the 8- and 16-lane paths; chunks decline friction frames.
/// </summary>
public sealed partial class FastCollideSystem : IHairSystem, IStrandChunkSystem
{
    private readonly bool _wide;

    /// <param name="allowWide">Use 16-lane chunks where the CPU has AVX-512 (same bits either way).</param>
    public FastCollideSystem(bool allowWide = true) => _wide = allowWide && ParticleRuns.WideAvailable;

    /// <summary>Whether this instance runs 16-lane chunks.</summary>
    internal bool UsesWide => _wide;

    public string Name => CollideSystem.SystemName;
    public SystemPhase Phase => SystemPhase.Substep;

    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var st = ctx.Settings;
        if (st.StaticFriction > 0f || st.KineticFriction > 0f) ResolveWithFriction(ctx, substep, scene.World, begin, end);
        else
        {
            _starts.Forget(scene.World, begin, end);
            Resolve(ctx, substep, scene.World, begin, end);
        }
    }

    bool IStrandChunkSystem.SupportsChunks => _wide;
    bool IStrandChunkSystem.TakesCutStrands => true;

    // This frame's kernel of each (substep, collider), built once for all chunks; the slot of the other kind is unused.
    private EllipsoidKernel[] _chunkEllipsoids = [];
    private CapsuleKernel[] _chunkCapsules = [];
    private PlaneKernel[] _chunkPlanes = [];

    /// <summary>A chunk's frictionless frame leaves the stored friction starts of its strands stale.</summary>
    void IStrandChunkSystem.PrepareChunk(HairWorld w, int s0, scoped in StrandChunk chunk) => _starts.Forget(w, s0, s0 + StrandChunk.Lanes);

    bool IStrandChunkSystem.BeginChunkFrame(FrameContext ctx)
    {
        // Friction needs each particle's start-of-substep position, which a chunk has no rows for: step system by system.
        if (ctx.Settings.StaticFriction > 0f || ctx.Settings.KineticFriction > 0f) return false;
        int n = ctx.Substeps * ctx.ColliderCount;
        if (_chunkEllipsoids.Length < n) { _chunkEllipsoids = new EllipsoidKernel[n]; _chunkCapsules = new CapsuleKernel[n]; _chunkPlanes = new PlaneKernel[n]; }
        float slide = ctx.Settings.ContactSlide;
        var friction = default(FrictionLanes); // off (friction frames do not run on chunks)
        for (int s = 0; s < ctx.Substeps; s++)
        {
            var colliders = ctx.CollidersAt(s);
            for (int c = 0; c < colliders.Length; c++)
            {
                int i = s * colliders.Length + c;
                if (colliders[c].Kind == ColliderKind.Ellipsoid) _chunkEllipsoids[i] = new EllipsoidKernel(colliders[c], slide, friction);
                else if (colliders[c].Kind == ColliderKind.Plane) _chunkPlanes[i] = new PlaneKernel(colliders[c], slide, friction);
                else _chunkCapsules[i] = new CapsuleKernel(colliders[c], slide, friction);
            }
        }
        return true;
    }

    /// <summary>
    /// Whether the frame's chunks may take the far rows the bend sweep found (<see cref="StrandChunk.FarRows"/>): one
    /// ellipsoid, whose kernel leaves 16 lanes as they are when each is outside its far sphere (<see cref="FarSphere"/>)
    /// or pinned, is the only collider.
    /// </summary>
    internal static bool TakesFarRows(FrameContext ctx)
    {
        if (ctx.ColliderCount != 1) return false;
        for (int s = 0; s < ctx.Substeps; s++) if (ctx.CollidersAt(s)[0].Kind != ColliderKind.Ellipsoid) return false;
        return true;
    }

    /// <summary>
    /// The ellipsoid kernel's far test, as the bend sweep repeats it: a particle p is far when |p − centre|², summed
    /// x, y then z, is over <paramref name="outer2"/> (the largest radius squared, with room for the roundings of the
    /// rotation and of q·q).
    /// </summary>
    internal static void FarSphere(in Collider c, out Vector3 centre, out float outer2)
    {
        float r = MathF.Max(c.Radii.X, MathF.Max(c.Radii.Y, c.Radii.Z));
        centre = c.Center;
        outer2 = r * r * 1.0001f;
    }

    bool IStrandChunkSystem.RunChunk(HairScene scene, FrameContext ctx, int substep, scoped in StrandChunk chunk)
    {
        var colliders = ctx.CollidersAt(substep);
        if (chunk.FarRows != 0)
        {
            // The sweep just before found the rows with a free lane inside the far sphere; the kernel leaves the rest as they are.
            ulong rows;
            unsafe { rows = *(ulong*)chunk.FarRows; }
#if DEBUG
            CheckFarRows(chunk, colliders[0], rows);
#endif
            chunk.ForEachCellOfRows(ref _chunkEllipsoids[substep], rows);
            return true;
        }
        for (int c = 0; c < colliders.Length; c++)
        {
            int i = substep * colliders.Length + c;
            if (colliders[c].Kind == ColliderKind.Ellipsoid) chunk.ForEachCell(ref _chunkEllipsoids[i]);
            else if (colliders[c].Kind == ColliderKind.Plane) chunk.ForEachCell(ref _chunkPlanes[i]);
            else chunk.ForEachCell(ref _chunkCapsules[i]);
        }
        return true;
    }

#if DEBUG
    /// <summary>Debug builds: every live row the sweep left out is one the ellipsoid kernel would leave as it is (every free lane far).</summary>
    private static void CheckFarRows(scoped in StrandChunk chunk, in Collider c, ulong rows)
    {
        FarSphere(c, out var centre, out float outer2);
        for (int k = 0; k < chunk.LiveRows; k++)
        {
            if ((rows >> k & 1) != 0) continue;
            for (int l = 0; l < StrandChunk.Lanes; l++)
            {
                if (Unsafe.Add(ref chunk.Row(StrandChunk.InvMass, k), l) == 0f) continue; // pinned: never pushed
                float dx = Unsafe.Add(ref chunk.Row(StrandChunk.X, k), l) - centre.X, dy = Unsafe.Add(ref chunk.Row(StrandChunk.Y, k), l) - centre.Y,
                    dz = Unsafe.Add(ref chunk.Row(StrandChunk.Z, k), l) - centre.Z;
                if (!(dx * dx + dy * dy + dz * dz > outer2))
                    throw new InvalidOperationException($"The bend sweep left out row {k} of the chunk from strand {chunk.FirstStrand}, whose free lane {l} is inside the collider's far sphere.");
            }
        }
    }
#endif

    /// <summary>Every collider of the substep, over strands [begin, end).</summary>
    private void Resolve(FrameContext ctx, int substep, HairWorld w, int begin, int end)
    {
        var colliders = ctx.CollidersAt(substep);
        float slide = ctx.Settings.ContactSlide;
        var friction = default(FrictionLanes); // off: the frictionless kernels
        for (int c = 0; c < colliders.Length; c++)
        {
            var col = colliders[c];
            if (col.Kind == ColliderKind.Ellipsoid)
            {
                var k = new EllipsoidKernel(col, slide, friction);
                ParticleRuns.ForEachLiveWide(w, begin, end, ref k, _wide);
            }
            else if (col.Kind == ColliderKind.Plane)
            {
                var k = new PlaneKernel(col, slide, friction);
                ParticleRuns.ForEachLiveWide(w, begin, end, ref k, _wide);
            }
            else
            {
                var k = new CapsuleKernel(col, slide, friction);
                ParticleRuns.ForEachLiveWide(w, begin, end, ref k, _wide);
            }
        }
    }

    /// <summary>Velocity response shared by all kinds: drop the inward normal part, keep ContactSlide of the rest.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Respond(Vector<int> hit, Vector<float> nx, Vector<float> ny, Vector<float> nz, Vector<float> slide,
                                ref float vx, ref float vy, ref float vz)
    {
        var x = Simd.Ld(ref vx, 0); var y = Simd.Ld(ref vy, 0); var z = Simd.Ld(ref vz, 0);
        var vn = x * nx + y * ny + z * nz;
        var m = hit & Vector.LessThan(vn, Vector<float>.Zero);
        if (Vector.EqualsAll(m, Vector<int>.Zero)) return;
        Simd.St(ref vx, 0, Simd.Sel(m, (x - vn * nx) * slide, x));
        Simd.St(ref vy, 0, Simd.Sel(m, (y - vn * ny) * slide, y));
        Simd.St(ref vz, 0, Simd.Sel(m, (z - vn * nz) * slide, z));
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Respond16(Vector512<float> hit, Vector512<float> nx, Vector512<float> ny, Vector512<float> nz, Vector512<float> slide,
                                  ref float vx, ref float vy, ref float vz)
    {
        var x = Vector512.LoadUnsafe(ref vx); var y = Vector512.LoadUnsafe(ref vy); var z = Vector512.LoadUnsafe(ref vz);
        var vn = x * nx + y * ny + z * nz;
        var m = hit & Vector512.LessThan(vn, Vector512<float>.Zero);
        if (m == Vector512<float>.Zero) return;
        Vector512.ConditionalSelect(m, (x - vn * nx) * slide, x).StoreUnsafe(ref vx);
        Vector512.ConditionalSelect(m, (y - vn * ny) * slide, y).StoreUnsafe(ref vy);
        Vector512.ConditionalSelect(m, (z - vn * nz) * slide, z).StoreUnsafe(ref vz);
    }

    private readonly struct EllipsoidKernel : IWideParticleKernel
    {
        private readonly PoseLanes _toLocal, _toWorld;
        private readonly Vector<float> _cx, _cy, _cz, _invRx, _invRy, _invRz, _invRx2, _invRy2, _invRz2, _ry, _slide;
        private readonly W16 _w;
        private readonly FrictionLanes _friction;

        /// <summary>The 16-lane copies of the constants.</summary>
        private readonly struct W16(PoseLanes toLocal, PoseLanes toWorld, in Collider c, float slide)
        {
            public readonly PoseLanes16 ToLocal = new(toLocal), ToWorld = new(toWorld);
            public readonly Vector512<float> Cx = Vector512.Create(c.Center.X), Cy = Vector512.Create(c.Center.Y), Cz = Vector512.Create(c.Center.Z),
                InvRx = Vector512.Create(1f / c.Radii.X), InvRy = Vector512.Create(1f / c.Radii.Y), InvRz = Vector512.Create(1f / c.Radii.Z),
                InvRx2 = Vector512.Create(1f / (c.Radii.X * c.Radii.X)), InvRy2 = Vector512.Create(1f / (c.Radii.Y * c.Radii.Y)),
                InvRz2 = Vector512.Create(1f / (c.Radii.Z * c.Radii.Z)), Ry = Vector512.Create(c.Radii.Y), Slide = Vector512.Create(slide),
                Outer2 = Vector512.Create(Outer(c));
            public readonly Vector<float> Outer8 = new(Outer(c));

            private static float Outer(in Collider c) { FarSphere(c, out _, out float outer2); return outer2; }
        }

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public void Chunk16(ref float px, ref float py, ref float pz, ref float vx, ref float vy, ref float vz,
                            ref float invMass, ref float rx, ref float ry, ref float rz)
        {
            ref readonly W16 k = ref _w;
            var x = Vector512.LoadUnsafe(ref px); var y = Vector512.LoadUnsafe(ref py); var z = Vector512.LoadUnsafe(ref pz);
            var dx = x - k.Cx; var dy = y - k.Cy; var dz = z - k.Cz;
            // Every lane outside the sphere round the ellipsoid (most rows of hanging hair): no hit, without the
            // rotation and the root; the lanes it lets through get the same test as before, so the same bits.
            if (Vector512.GreaterThanAll(dx * dx + dy * dy + dz * dz, k.Outer2)) return;
            k.ToLocal.Direction(dx, dy, dz, out var lx, out var ly, out var lz);
            var qx = lx * k.InvRx; var qy = ly * k.InvRy; var qz = lz * k.InvRz;
            // Inside is decided on s = r², not r = √s: s < 1 exactly where √s < 1 (EllipsoidInsideTests), and the branch
            // then does not wait for the root (wanted only by the rows with a lane inside).
            var s = qx * qx + qy * qy + qz * qz;
            var r = Vector512.Sqrt(s);
            var hit = Vector512.LessThan(s, Vector512<float>.One) & ~Vector512.Equals(Vector512.LoadUnsafe(ref invMass), Vector512<float>.Zero);
            if (hit == Vector512<float>.Zero) return;
            var centre = Vector512.LessThan(r, Vector512.Create(1e-12f));
            var inv = Vector512<float>.One / Vector512.ConditionalSelect(centre, Vector512<float>.One, r);
            var sx = Vector512.ConditionalSelect(centre, Vector512<float>.Zero, lx * inv);
            var sy = Vector512.ConditionalSelect(centre, k.Ry, ly * inv);
            var sz = Vector512.ConditionalSelect(centre, Vector512<float>.Zero, lz * inv);
            var nx = sx * k.InvRx2; var ny = sy * k.InvRy2; var nz = sz * k.InvRz2;
            var nInv = Vector512<float>.One / Vector512.Sqrt(nx * nx + ny * ny + nz * nz);
            k.ToWorld.Point(sx, sy, sz, out var wx, out var wy, out var wz);
            k.ToWorld.Direction(nx * nInv, ny * nInv, nz * nInv, out var wnx, out var wny, out var wnz);
            if (_friction.On)
            {
                var ex = sx - lx; var ey = sy - ly; var ez = sz - lz;
                PushOutWithFriction16(hit, x, y, z, wx, wy, wz, wnx, wny, wnz, Vector512.Sqrt(ex * ex + ey * ey + ez * ez), in _friction,
                    ref px, ref py, ref pz, ref vx, ref vy, ref vz, ref rx, ref ry, ref rz);
            }
            else
            {
                Vector512.ConditionalSelect(hit, wx, x).StoreUnsafe(ref px);
                Vector512.ConditionalSelect(hit, wy, y).StoreUnsafe(ref py);
                Vector512.ConditionalSelect(hit, wz, z).StoreUnsafe(ref pz);
            }
            Respond16(hit, wnx, wny, wnz, k.Slide, ref vx, ref vy, ref vz);
        }

        public EllipsoidKernel(in Collider c, float slide, in FrictionLanes friction)
        {
            _friction = friction;
            _toLocal = PoseLanes.InverseRotation(c.Rotation);
            _toWorld = new PoseLanes(c.Rotation, c.Center);
            _cx = new(c.Center.X); _cy = new(c.Center.Y); _cz = new(c.Center.Z);
            _invRx = new(1f / c.Radii.X); _invRy = new(1f / c.Radii.Y); _invRz = new(1f / c.Radii.Z);
            _invRx2 = new(1f / (c.Radii.X * c.Radii.X)); _invRy2 = new(1f / (c.Radii.Y * c.Radii.Y)); _invRz2 = new(1f / (c.Radii.Z * c.Radii.Z));
            _ry = new(c.Radii.Y);
            _slide = new(slide);
            _w = new W16(_toLocal, _toWorld, c, slide);
        }

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public void Chunk(ref float px, ref float py, ref float pz, ref float vx, ref float vy, ref float vz,
                          ref float invMass, ref float rx, ref float ry, ref float rz)
        {
            var x = Simd.Ld(ref px, 0); var y = Simd.Ld(ref py, 0); var z = Simd.Ld(ref pz, 0);
            var dx = x - _cx; var dy = y - _cy; var dz = z - _cz;
            // As Chunk16: every lane outside the sphere round the ellipsoid, no hit.
            if (Vector.GreaterThanAll(dx * dx + dy * dy + dz * dz, _w.Outer8)) return;
            _toLocal.Direction(dx, dy, dz, out var lx, out var ly, out var lz);
            var qx = lx * _invRx; var qy = ly * _invRy; var qz = lz * _invRz;
            // As Chunk16: inside decided on s = r² (exactly where r < 1).
            var s = qx * qx + qy * qy + qz * qz;
            var r = Vector.SquareRoot(s);
            var hit = Vector.LessThan(s, Vector<float>.One) & ~Vector.Equals(Simd.Ld(ref invMass, 0), Vector<float>.Zero);
            if (Vector.EqualsAll(hit, Vector<int>.Zero)) return;
            // A particle at the centre is pushed along local +Y, as the reference does.
            var centre = Vector.LessThan(r, new Vector<float>(1e-12f));
            var inv = Vector<float>.One / Simd.Sel(centre, Vector<float>.One, r);
            var sx = Simd.Sel(centre, Vector<float>.Zero, lx * inv);
            var sy = Simd.Sel(centre, _ry, ly * inv);
            var sz = Simd.Sel(centre, Vector<float>.Zero, lz * inv);
            var nx = sx * _invRx2; var ny = sy * _invRy2; var nz = sz * _invRz2;
            var nInv = Vector<float>.One / Vector.SquareRoot(nx * nx + ny * ny + nz * nz);
            _toWorld.Point(sx, sy, sz, out var wx, out var wy, out var wz);
            _toWorld.Direction(nx * nInv, ny * nInv, nz * nInv, out var wnx, out var wny, out var wnz);
            if (_friction.On)
            {
                // Depth pushed out, measured in the local frame as the reference does (a rotation keeps lengths).
                var ex = sx - lx; var ey = sy - ly; var ez = sz - lz;
                PushOutWithFriction(hit, x, y, z, wx, wy, wz, wnx, wny, wnz, Vector.SquareRoot(ex * ex + ey * ey + ez * ez), in _friction,
                    ref px, ref py, ref pz, ref vx, ref vy, ref vz, ref rx, ref ry, ref rz);
            }
            else
            {
                Simd.St(ref px, 0, Simd.Sel(hit, wx, x));
                Simd.St(ref py, 0, Simd.Sel(hit, wy, y));
                Simd.St(ref pz, 0, Simd.Sel(hit, wz, z));
            }
            Respond(hit, wnx, wny, wnz, _slide, ref vx, ref vy, ref vz);
        }
    }

    private readonly struct CapsuleKernel : IWideParticleKernel
    {
        private readonly Vector<float> _ax, _ay, _az, _abx, _aby, _abz, _invLen2, _radius, _slide, _fx, _fy, _fz;
        private readonly bool _segment;
        private readonly FrictionLanes _friction;
        private readonly Vector512<float> _ax16, _ay16, _az16, _abx16, _aby16, _abz16, _invLen216, _radius16, _slide16, _fx16, _fy16, _fz16;

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public void Chunk16(ref float px, ref float py, ref float pz, ref float vx, ref float vy, ref float vz,
                            ref float invMass, ref float rx, ref float ry, ref float rz)
        {
            var x = Vector512.LoadUnsafe(ref px); var y = Vector512.LoadUnsafe(ref py); var z = Vector512.LoadUnsafe(ref pz);
            var cx = _ax16; var cy = _ay16; var cz = _az16;
            if (_segment)
            {
                var t = ((x - _ax16) * _abx16 + (y - _ay16) * _aby16 + (z - _az16) * _abz16) * _invLen216;
                t = Vector512.Min(Vector512.Max(t, Vector512<float>.Zero), Vector512<float>.One);
                cx += t * _abx16; cy += t * _aby16; cz += t * _abz16;
            }
            var dx = x - cx; var dy = y - cy; var dz = z - cz;
            var dist = Vector512.Sqrt(dx * dx + dy * dy + dz * dz);
            var hit = Vector512.LessThan(dist, _radius16) & ~Vector512.Equals(Vector512.LoadUnsafe(ref invMass), Vector512<float>.Zero);
            if (hit == Vector512<float>.Zero) return;
            var onAxis = Vector512.LessThan(dist, Vector512.Create(1e-12f));
            var inv = Vector512<float>.One / Vector512.ConditionalSelect(onAxis, Vector512<float>.One, dist);
            var nx = Vector512.ConditionalSelect(onAxis, _fx16, dx * inv);
            var ny = Vector512.ConditionalSelect(onAxis, _fy16, dy * inv);
            var nz = Vector512.ConditionalSelect(onAxis, _fz16, dz * inv);
            if (_friction.On)
                PushOutWithFriction16(hit, x, y, z, cx + nx * _radius16, cy + ny * _radius16, cz + nz * _radius16, nx, ny, nz, _radius16 - dist,
                    in _friction, ref px, ref py, ref pz, ref vx, ref vy, ref vz, ref rx, ref ry, ref rz);
            else
            {
                Vector512.ConditionalSelect(hit, cx + nx * _radius16, x).StoreUnsafe(ref px);
                Vector512.ConditionalSelect(hit, cy + ny * _radius16, y).StoreUnsafe(ref py);
                Vector512.ConditionalSelect(hit, cz + nz * _radius16, z).StoreUnsafe(ref pz);
            }
            Respond16(hit, nx, ny, nz, _slide16, ref vx, ref vy, ref vz);
        }

        public CapsuleKernel(in Collider c, float slide, in FrictionLanes friction)
        {
            _friction = friction;
            var ab = c.Kind == ColliderKind.Capsule ? c.End - c.Center : Vector3.Zero;
            float len2 = Vector3.Dot(ab, ab);
            _segment = len2 >= 1e-18f;
            _ax = new(c.Center.X); _ay = new(c.Center.Y); _az = new(c.Center.Z);
            _abx = new(ab.X); _aby = new(ab.Y); _abz = new(ab.Z);
            _invLen2 = new(_segment ? 1f / len2 : 0f);
            _radius = new(c.Radius);
            _slide = new(slide);
            // On the axis itself the reference pushes sideways (perpendicular to the axis); a sphere pushes along +Y.
            var fallback = _segment ? RestShape.AnyPerpendicular(Vector3.Normalize(ab)) : Vector3.UnitY;
            _fx = new(fallback.X); _fy = new(fallback.Y); _fz = new(fallback.Z);
            _ax16 = Vector512.Create(c.Center.X); _ay16 = Vector512.Create(c.Center.Y); _az16 = Vector512.Create(c.Center.Z);
            _abx16 = Vector512.Create(ab.X); _aby16 = Vector512.Create(ab.Y); _abz16 = Vector512.Create(ab.Z);
            _invLen216 = Vector512.Create(_segment ? 1f / len2 : 0f);
            _radius16 = Vector512.Create(c.Radius);
            _slide16 = Vector512.Create(slide);
            _fx16 = Vector512.Create(fallback.X); _fy16 = Vector512.Create(fallback.Y); _fz16 = Vector512.Create(fallback.Z);
        }

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public void Chunk(ref float px, ref float py, ref float pz, ref float vx, ref float vy, ref float vz,
                          ref float invMass, ref float rx, ref float ry, ref float rz)
        {
            var x = Simd.Ld(ref px, 0); var y = Simd.Ld(ref py, 0); var z = Simd.Ld(ref pz, 0);
            var cx = _ax; var cy = _ay; var cz = _az;
            if (_segment)
            {
                var t = ((x - _ax) * _abx + (y - _ay) * _aby + (z - _az) * _abz) * _invLen2;
                t = Vector.Min(Vector.Max(t, Vector<float>.Zero), Vector<float>.One);
                cx += t * _abx; cy += t * _aby; cz += t * _abz;
            }
            var dx = x - cx; var dy = y - cy; var dz = z - cz;
            var dist = Vector.SquareRoot(dx * dx + dy * dy + dz * dz);
            var hit = Vector.LessThan(dist, _radius) & ~Vector.Equals(Simd.Ld(ref invMass, 0), Vector<float>.Zero);
            if (Vector.EqualsAll(hit, Vector<int>.Zero)) return;
            var onAxis = Vector.LessThan(dist, new Vector<float>(1e-12f));
            var inv = Vector<float>.One / Simd.Sel(onAxis, Vector<float>.One, dist);
            var nx = Simd.Sel(onAxis, _fx, dx * inv);
            var ny = Simd.Sel(onAxis, _fy, dy * inv);
            var nz = Simd.Sel(onAxis, _fz, dz * inv);
            if (_friction.On)
                PushOutWithFriction(hit, x, y, z, cx + nx * _radius, cy + ny * _radius, cz + nz * _radius, nx, ny, nz, _radius - dist,
                    in _friction, ref px, ref py, ref pz, ref vx, ref vy, ref vz, ref rx, ref ry, ref rz);
            else
            {
                Simd.St(ref px, 0, Simd.Sel(hit, cx + nx * _radius, x));
                Simd.St(ref py, 0, Simd.Sel(hit, cy + ny * _radius, y));
                Simd.St(ref pz, 0, Simd.Sel(hit, cz + nz * _radius, z));
            }
            Respond(hit, nx, ny, nz, _slide, ref vx, ref vy, ref vz);
        }
    }
}
