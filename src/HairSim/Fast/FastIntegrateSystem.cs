using System.Runtime.CompilerServices;
using System.Numerics;
using System.Runtime.Intrinsics;

namespace HairSim.Fast;

/// <summary>
/// Fast <see cref="IntegrateSystem"/>: gravity, damping, speed limit and x += h·v on free particles, in float SIMD
/// (16-lane chunks where the CPU has AVX-512, with the same arithmetic in the same order as the 8-lane chunks).
/// </summary>
public sealed class FastIntegrateSystem : IHairSystem, IStrandChunkSystem
{
    private readonly bool _wide;

    /// <param name="allowWide">Use 16-lane chunks where the CPU has AVX-512 (same bits either way).</param>
    public FastIntegrateSystem(bool allowWide = true) => _wide = allowWide && ParticleRuns.WideAvailable;

    /// <summary>Whether this instance runs 16-lane chunks.</summary>
    internal bool UsesWide => _wide;

    public string Name => IntegrateSystem.SystemName;
    public SystemPhase Phase => SystemPhase.Substep;

    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var kernel = MakeKernel(ctx);
        ParticleRuns.ForEachLiveWide(scene.World, begin, end, ref kernel, _wide);
    }

    private static Kernel MakeKernel(FrameContext ctx)
    {
        var st = ctx.Settings;
        float h = ctx.H;
        return new Kernel(h, st.Gravity * h, MathF.Max(0f, 1f - st.Damping * h), st.MaxSpeed);
    }

    /// <summary>This frame's kernel, built once for all chunks (all substeps share it).</summary>
    private Kernel _chunkKernel;

    bool IStrandChunkSystem.SupportsChunks => _wide;
    bool IStrandChunkSystem.TakesCutStrands => true;

    bool IStrandChunkSystem.BeginChunkFrame(FrameContext ctx)
    {
        _chunkKernel = MakeKernel(ctx);
        return true;
    }

    bool IStrandChunkSystem.RunChunk(HairScene scene, FrameContext ctx, int substep, scoped in StrandChunk chunk)
    {
        chunk.ForEachCell(ref _chunkKernel);
        return true;
    }

    private readonly struct Kernel : IWideParticleKernel
    {
        private readonly Vector<float> _h, _gx, _gy, _gz, _keep, _maxSpeed, _maxSpeedSq;
        private readonly Vector512<float> _h16, _gx16, _gy16, _gz16, _keep16, _maxSpeed16, _maxSpeedSq16;
        private readonly Vector<uint> _speedBound;
        private readonly Vector512<uint> _speedBound16;
        private readonly bool _limit;

        public Kernel(float h, Vector3 gravityStep, float keep, float maxSpeed)
        {
            _h = new(h); _gx = new(gravityStep.X); _gy = new(gravityStep.Y); _gz = new(gravityStep.Z);
            _keep = new(keep); _maxSpeed = new(maxSpeed); _maxSpeedSq = new(maxSpeed * maxSpeed); _limit = maxSpeed > 0f;
            _h16 = Vector512.Create(h); _gx16 = Vector512.Create(gravityStep.X); _gy16 = Vector512.Create(gravityStep.Y); _gz16 = Vector512.Create(gravityStep.Z);
            _keep16 = Vector512.Create(keep); _maxSpeed16 = Vector512.Create(maxSpeed); _maxSpeedSq16 = Vector512.Create(maxSpeed * maxSpeed);
            _speedBound = new(Simd.SpeedBound(maxSpeed)); _speedBound16 = Vector512.Create(Simd.SpeedBound(maxSpeed));
        }

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public void Chunk(ref float px, ref float py, ref float pz, ref float vx, ref float vy, ref float vz,
                          ref float invMass, ref float rx, ref float ry, ref float rz)
        {
            var pinned = Vector.Equals(Simd.Ld(ref invMass, 0), Vector<float>.Zero);
            var ox = Simd.Ld(ref vx, 0); var oy = Simd.Ld(ref vy, 0); var oz = Simd.Ld(ref vz, 0);
            var x = (ox + _gx) * _keep; var y = (oy + _gy) * _keep; var z = (oz + _gz) * _keep;
            if (_limit && !Simd.AllWithin(x, y, z, _speedBound))
            {
                // Squared speeds compared (as the bend sweep's kick does), the root taken only where a lane is over.
                var spSq = x * x + y * y + z * z;
                var over = Vector.GreaterThan(spSq, _maxSpeedSq);
                if (!Vector.EqualsAll(over, Vector<int>.Zero))
                {
                    var f = Simd.Sel(over, _maxSpeed / Vector.SquareRoot(spSq), Vector<float>.One);
                    x *= f; y *= f; z *= f;
                }
            }
            Simd.St(ref vx, 0, Simd.Sel(pinned, ox, x));
            Simd.St(ref vy, 0, Simd.Sel(pinned, oy, y));
            Simd.St(ref vz, 0, Simd.Sel(pinned, oz, z));
            Simd.St(ref px, 0, Simd.Sel(pinned, Simd.Ld(ref px, 0), Simd.Ld(ref px, 0) + _h * x));
            Simd.St(ref py, 0, Simd.Sel(pinned, Simd.Ld(ref py, 0), Simd.Ld(ref py, 0) + _h * y));
            Simd.St(ref pz, 0, Simd.Sel(pinned, Simd.Ld(ref pz, 0), Simd.Ld(ref pz, 0) + _h * z));
        }

        /// <summary>16 particles with AVX-512: the same arithmetic, in the same order, as <see cref="Chunk"/>.</summary>
        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public void Chunk16(ref float px, ref float py, ref float pz, ref float vx, ref float vy, ref float vz,
                            ref float invMass, ref float rx, ref float ry, ref float rz)
        {
            var h = _h16; var keep = _keep16;
            var pinned = Vector512.Equals(Vector512.LoadUnsafe(ref invMass), Vector512<float>.Zero);
            var ox = Vector512.LoadUnsafe(ref vx); var oy = Vector512.LoadUnsafe(ref vy); var oz = Vector512.LoadUnsafe(ref vz);
            var x = (ox + _gx16) * keep; var y = (oy + _gy16) * keep; var z = (oz + _gz16) * keep;
            if (_limit && !Simd.AllWithin(x, y, z, _speedBound16))
            {
                var spSq = x * x + y * y + z * z;
                var over = Vector512.GreaterThan(spSq, _maxSpeedSq16);
                if (over != Vector512<float>.Zero)
                {
                    var f = Vector512.ConditionalSelect(over, _maxSpeed16 / Vector512.Sqrt(spSq), Vector512<float>.One);
                    x *= f; y *= f; z *= f;
                }
            }
            Vector512.ConditionalSelect(pinned, ox, x).StoreUnsafe(ref vx);
            Vector512.ConditionalSelect(pinned, oy, y).StoreUnsafe(ref vy);
            Vector512.ConditionalSelect(pinned, oz, z).StoreUnsafe(ref vz);
            var qx = Vector512.LoadUnsafe(ref px); var qy = Vector512.LoadUnsafe(ref py); var qz = Vector512.LoadUnsafe(ref pz);
            Vector512.ConditionalSelect(pinned, qx, qx + h * x).StoreUnsafe(ref px);
            Vector512.ConditionalSelect(pinned, qy, qy + h * y).StoreUnsafe(ref py);
            Vector512.ConditionalSelect(pinned, qz, qz + h * z).StoreUnsafe(ref pz);
        }
    }
}
