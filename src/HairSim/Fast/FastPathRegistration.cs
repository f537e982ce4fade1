using HairSim.Fast;

namespace HairSim;

/// <summary>Supplies the fast implementation of each core system (see <see cref="SolverPath.Fast"/>).</summary>
internal static partial class FastPathRegistration
{
    static partial void ApplyFast(PipelineBuilder builder, bool allowWide)
    {
        foreach (var f in builder.Factories.ToArray())
        {
            Func<HairScene, IHairSystem>? fast = f.Name switch
            {
                HeadFollowSystem.SystemName => s => new FastHeadFollowSystem(s.World),
                ShapeMatchSystem.SystemName => s => new FastShapeMatchSystem(s.World.MaxStrandCapacity, allowWide, s.World),
                IntegrateSystem.SystemName => _ => new FastIntegrateSystem(allowWide),
                BendSystem.SystemName => s => new FastBendSystem(s.World, allowWide),
                LengthSystem.SystemName => s => new FastLengthSystem(s.World.MaxStrandCapacity, allowWide),
                CollideSystem.SystemName => _ => new FastCollideSystem(allowWide),
                Meshes.MeshCollideSystem.SystemName => s => new FastMeshCollideSystem(s),
                SegmentCollideSystem.SystemName => _ => new FastSegmentCollideSystem(),
                InterpolateSystem.SystemName => s => new FastInterpolateSystem(s),
                VolumeSystem.SystemName => _ => new FastVolumeSystem(),
                _ => null,
            };
            if (fast != null) builder.Replace(f with { CreateFast = fast });
        }
    }
}

public static partial class ThreadDispatchers
{
    static partial void CreateParallel(ref IDisposableDispatcher? dispatcher) =>
        dispatcher = new ParallelDispatcher(Environment.ProcessorCount);
}
