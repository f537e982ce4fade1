using System.Runtime.CompilerServices;
using System.Numerics;

namespace HairSim.Fast;

/// <summary>
/// Fast <see cref="HeadFollowSystem"/>: pinned particles go to head·rest with zero velocity (SIMD, masked by
/// InvMass == 0); on a teleport frame the block's particles (every slot, live or cut) are first carried rigidly.
/// </summary>
public sealed class FastHeadFollowSystem : IHairSystem
{
    public string Name => HeadFollowSystem.SystemName;
    public SystemPhase Phase => SystemPhase.Substep;

    public void Run(HairScene scene, FrameContext ctx, int substep, int begin, int end)
    {
        if (begin >= end) return;
        var w = scene.World;
        if (substep == 0 && ctx.Teleported) CarryRigidly(w, ctx.TeleportDelta, begin, end);
        var kernel = new PinKernel(new PoseLanes(ctx.HeadAt(substep)));
        ParticleRuns.ForEachLive(w, begin, end, ref kernel);
    }

    private static void CarryRigidly(HairWorld w, in RigidTransform delta, int begin, int end)
    {
        var pose = new PoseLanes(delta);
        int i = w.StrandFirst[begin], stop = w.StrandFirst[end - 1] + w.StrandCapacity[end - 1];
        int width = Vector<float>.Count;
        ref float px = ref Simd.At(w.PosX, 0), py = ref Simd.At(w.PosY, 0), pz = ref Simd.At(w.PosZ, 0);
        ref float vx = ref Simd.At(w.VelX, 0), vy = ref Simd.At(w.VelY, 0), vz = ref Simd.At(w.VelZ, 0);
        for (; i <= stop - width; i += width)
        {
            pose.Point(Simd.Ld(ref px, i), Simd.Ld(ref py, i), Simd.Ld(ref pz, i), out var x, out var y, out var z);
            Simd.St(ref px, i, x); Simd.St(ref py, i, y); Simd.St(ref pz, i, z);
            pose.Direction(Simd.Ld(ref vx, i), Simd.Ld(ref vy, i), Simd.Ld(ref vz, i), out x, out y, out z);
            Simd.St(ref vx, i, x); Simd.St(ref vy, i, y); Simd.St(ref vz, i, z);
        }
        for (; i < stop; i++)
        {
            w.SetPosition(i, pose.Point(w.GetPosition(i)));
            w.SetVelocity(i, pose.Direction(w.GetVelocity(i)));
        }
    }

    private readonly struct PinKernel : IParticleKernel
    {
        private readonly PoseLanes _head;
        public PinKernel(PoseLanes head) => _head = head;

        [MethodImpl(MethodImplOptions.AggressiveInlining)]
        public void Chunk(ref float px, ref float py, ref float pz, ref float vx, ref float vy, ref float vz,
                          ref float invMass, ref float rx, ref float ry, ref float rz)
        {
            var pinned = Vector.Equals(Simd.Ld(ref invMass, 0), Vector<float>.Zero);
            if (Vector.EqualsAll(pinned, Vector<int>.Zero)) return;
            _head.Point(Simd.Ld(ref rx, 0), Simd.Ld(ref ry, 0), Simd.Ld(ref rz, 0), out var gx, out var gy, out var gz);
            Simd.St(ref px, 0, Simd.Sel(pinned, gx, Simd.Ld(ref px, 0)));
            Simd.St(ref py, 0, Simd.Sel(pinned, gy, Simd.Ld(ref py, 0)));
            Simd.St(ref pz, 0, Simd.Sel(pinned, gz, Simd.Ld(ref pz, 0)));
            Simd.St(ref vx, 0, Simd.Sel(pinned, Vector<float>.Zero, Simd.Ld(ref vx, 0)));
            Simd.St(ref vy, 0, Simd.Sel(pinned, Vector<float>.Zero, Simd.Ld(ref vy, 0)));
            Simd.St(ref vz, 0, Simd.Sel(pinned, Vector<float>.Zero, Simd.Ld(ref vz, 0)));
        }
    }
}
