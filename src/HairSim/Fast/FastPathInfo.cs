using System.Numerics;
using System.Runtime.Intrinsics;
using System.Runtime.Intrinsics.X86;

namespace HairSim.Fast;

/// <summary>What the fast path can use on this CPU.</summary>
public static class FastPathInfo
{
    /// <summary>
    /// True when the 16-lane (AVX-512) paths of shape matching, integrate, length and collide are used by default: 512-bit
    /// vectors run natively and <see cref="Vector{T}"/> is 8 floats wide (the 8-lane code they mirror). Strand chunks
    /// (<see cref="HairPipeline.UsesStrandChunks"/>) need it too.
    /// </summary>
    public static bool Avx512 => Vector512.IsHardwareAccelerated && Avx512F.IsSupported && Avx.IsSupported && Vector<float>.Count == 8;
}
