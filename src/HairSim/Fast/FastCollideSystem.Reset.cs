namespace HairSim.Fast;

public sealed partial class FastCollideSystem : IStrandResetListener, IStrandMovedListener
{
    /// <summary>A strand put back at its rest pose by the pipeline: the friction start positions stored for it are stale.</summary>
    void IStrandResetListener.StrandReset(HairWorld world, int strand) => _starts.Forget(world, strand, strand + 1);
    void IStrandMovedListener.StrandMoved(HairWorld world, int strand) => _starts.Moved(world, strand);
}
