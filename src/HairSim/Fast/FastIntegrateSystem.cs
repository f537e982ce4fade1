using System.Runtime.CompilerServices;
using System.Numerics;

namespace HairSim.Fast;

/// <summary>Fast <see cref="IntegrateSystem"/>: gravity, damping, speed limit and x += h·v on free particles, in float SIMD.</summary>
public sealed class FastIntegrateSystem : IHairSystem
{
    public string Name => IntegrateSystem.SystemName;
    public SystemPhase Phase => SystemPhase.Substep;

    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        var st = ctx.Settings;
        float h = ctx.H;
        var kernel = new Kernel(h, st.Gravity * h, MathF.Max(0f, 1f - st.Damping * h), st.MaxSpeed);
        ParticleRuns.ForEachLive(scene.World, begin, end, ref kernel);
    }

    private readonly struct Kernel : IParticleKernel
    {
        private readonly Vector<float> _h, _gx, _gy, _gz, _keep, _maxSpeed;
        private readonly bool _limit;

        public Kernel(float h, Vector3 gravityStep, float keep, float maxSpeed)
        {
            _h = new(h); _gx = new(gravityStep.X); _gy = new(gravityStep.Y); _gz = new(gravityStep.Z);
            _keep = new(keep); _maxSpeed = new(maxSpeed); _limit = maxSpeed > 0f;
        }

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public void Chunk(ref float px, ref float py, ref float pz, ref float vx, ref float vy, ref float vz,
                          ref float invMass, ref float rx, ref float ry, ref float rz)
        {
            var pinned = Vector.Equals(Simd.Ld(ref invMass, 0), Vector<float>.Zero);
            var ox = Simd.Ld(ref vx, 0); var oy = Simd.Ld(ref vy, 0); var oz = Simd.Ld(ref vz, 0);
            var x = (ox + _gx) * _keep; var y = (oy + _gy) * _keep; var z = (oz + _gz) * _keep;
            if (_limit)
            {
                var sp = Vector.SquareRoot(x * x + y * y + z * z);
                var over = Vector.GreaterThan(sp, _maxSpeed);
                if (!Vector.EqualsAll(over, Vector<int>.Zero))
                {
                    var f = Simd.Sel(over, _maxSpeed / sp, Vector<float>.One);
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
    }
}
