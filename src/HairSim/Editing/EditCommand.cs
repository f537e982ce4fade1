namespace HairSim.Editing;

/// <summary>
/// One edit of a world (cut, fit, reset, regrow). Created with its plan already computed and validated, so
/// applying it cannot fail half-way. The first <see cref="Apply"/> snapshots the affected strands before and
/// after; undo and redo restore those snapshots, so both are bit-exact.
/// </summary>
public abstract class EditCommand
{
    private StrandSnapshot? _before, _after;
    private readonly int[] _strands;

    protected EditCommand(HairWorld world, string name, int[] strands)
    {
        World = world ?? throw new ArgumentNullException(nameof(world));
        Name = name;
        _strands = strands;
    }

    public HairWorld World { get; }
    public string Name { get; }
    /// <summary>Strands this edit changes, ascending.</summary>
    public IReadOnlyList<int> Strands => _strands;
    public bool IsApplied { get; private set; }
    /// <summary>Memory the command holds for undo/redo (0 before the first apply).</summary>
    public long MemoryBytes => (_before?.Bytes ?? 0) + (_after?.Bytes ?? 0) + 4L * _strands.Length + PlanBytes;
    protected virtual long PlanBytes => 0;

    public void Apply()
    {
        if (IsApplied) throw new InvalidOperationException($"The {Name} edit is already applied.");
        if (_after == null)
        {
            _before = StrandSnapshot.Capture(World, _strands);
            try { Execute(World); }
            catch
            {
                _before.Restore(World); // never leave a half-applied edit behind
                _before = null;
                throw;
            }
            World.MarkEdited();
            _after = StrandSnapshot.Capture(World, _strands);
        }
        else _after.Restore(World);
        IsApplied = true;
    }

    public void Revert()
    {
        if (!IsApplied || _before == null) throw new InvalidOperationException($"The {Name} edit is not applied.");
        _before.Restore(World);
        IsApplied = false;
    }

    /// <summary>Changes the world for the first time (only the strands in <see cref="Strands"/>).</summary>
    protected abstract void Execute(HairWorld world);
}
