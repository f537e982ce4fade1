using System.Numerics;
using System.Runtime.CompilerServices;
using System.Runtime.Intrinsics;

namespace HairSim.Fast;

public sealed partial class FastCollideSystem
{
    /// <summary>
    /// A plane (<see cref="ColliderKind.Plane"/>): a particle below it goes straight up to it along the normal, then the
    /// shared response; the depth is the height below it. Same arithmetic on 8 and 16 lanes (same bits), as
    /// <see cref="Collider.Resolve"/> does in double.
    /// </summary>
    private readonly struct PlaneKernel : IWideParticleKernel
    {
        private readonly Vector<float> _px, _py, _pz, _nx, _ny, _nz, _slide;
        private readonly Vector512<float> _px16, _py16, _pz16, _nx16, _ny16, _nz16, _slide16;
        private readonly FrictionLanes _friction;

        public PlaneKernel(in Collider c, float slide, in FrictionLanes friction)
        {
            _friction = friction;
            var n = c.Normal;
            _px = new(c.Center.X); _py = new(c.Center.Y); _pz = new(c.Center.Z);
            _nx = new(n.X); _ny = new(n.Y); _nz = new(n.Z); _slide = new(slide);
            _px16 = Vector512.Create(c.Center.X); _py16 = Vector512.Create(c.Center.Y); _pz16 = Vector512.Create(c.Center.Z);
            _nx16 = Vector512.Create(n.X); _ny16 = Vector512.Create(n.Y); _nz16 = Vector512.Create(n.Z); _slide16 = Vector512.Create(slide);
        }

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public void Chunk(ref float px, ref float py, ref float pz, ref float vx, ref float vy, ref float vz,
                          ref float invMass, ref float rx, ref float ry, ref float rz)
        {
            var x = Simd.Ld(ref px, 0); var y = Simd.Ld(ref py, 0); var z = Simd.Ld(ref pz, 0);
            var d = (x - _px) * _nx + (y - _py) * _ny + (z - _pz) * _nz;
            var hit = Vector.LessThan(d, Vector<float>.Zero) & ~Vector.Equals(Simd.Ld(ref invMass, 0), Vector<float>.Zero);
            if (Vector.EqualsAll(hit, Vector<int>.Zero)) return;
            var wx = x - d * _nx; var wy = y - d * _ny; var wz = z - d * _nz;
            if (_friction.On)
                PushOutWithFriction(hit, x, y, z, wx, wy, wz, _nx, _ny, _nz, -d, in _friction, ref px, ref py, ref pz, ref vx, ref vy, ref vz, ref rx, ref ry, ref rz);
            else
            {
                Simd.St(ref px, 0, Simd.Sel(hit, wx, x));
                Simd.St(ref py, 0, Simd.Sel(hit, wy, y));
                Simd.St(ref pz, 0, Simd.Sel(hit, wz, z));
            }
            Respond(hit, _nx, _ny, _nz, _slide, ref vx, ref vy, ref vz);
        }

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public void Chunk16(ref float px, ref float py, ref float pz, ref float vx, ref float vy, ref float vz,
                            ref float invMass, ref float rx, ref float ry, ref float rz)
        {
            var x = Vector512.LoadUnsafe(ref px); var y = Vector512.LoadUnsafe(ref py); var z = Vector512.LoadUnsafe(ref pz);
            var d = (x - _px16) * _nx16 + (y - _py16) * _ny16 + (z - _pz16) * _nz16;
            var hit = Vector512.LessThan(d, Vector512<float>.Zero) & ~Vector512.Equals(Vector512.LoadUnsafe(ref invMass), Vector512<float>.Zero);
            if (hit == Vector512<float>.Zero) return;
            var wx = x - d * _nx16; var wy = y - d * _ny16; var wz = z - d * _nz16;
            if (_friction.On)
                PushOutWithFriction16(hit, x, y, z, wx, wy, wz, _nx16, _ny16, _nz16, -d, in _friction, ref px, ref py, ref pz, ref vx, ref vy, ref vz, ref rx, ref ry, ref rz);
            else
            {
                Vector512.ConditionalSelect(hit, wx, x).StoreUnsafe(ref px);
                Vector512.ConditionalSelect(hit, wy, y).StoreUnsafe(ref py);
                Vector512.ConditionalSelect(hit, wz, z).StoreUnsafe(ref pz);
            }
            Respond16(hit, _nx16, _ny16, _nz16, _slide16, ref vx, ref vy, ref vz);
        }
    }
}
