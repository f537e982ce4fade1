namespace HairSim.Editing;

/// <summary>
/// Undo and redo of edits, bounded by memory: when the commands held exceed <see cref="MaxBytes"/>, the oldest
/// undo steps are forgotten (a single edit larger than the bound is applied but cannot be undone).
/// Can be stored on a scene with scene.SetComponent(history), so tools and the pipeline find it.
/// </summary>
public sealed class EditHistory
{
    public const long DefaultMaxBytes = 256L * 1024 * 1024;

    private readonly LinkedList<EditCommand> _undo = new();
    private readonly Stack<EditCommand> _redo = new();

    public EditHistory(long maxBytes = DefaultMaxBytes)
    {
        if (maxBytes < 0) throw new ArgumentOutOfRangeException(nameof(maxBytes), maxBytes, "The memory bound must not be negative.");
        MaxBytes = maxBytes;
    }

    public long MaxBytes { get; }
    public int UndoCount => _undo.Count;
    public int RedoCount => _redo.Count;
    public bool CanUndo => _undo.Count > 0;
    public bool CanRedo => _redo.Count > 0;
    /// <summary>Bytes held by all undo and redo steps.</summary>
    public long MemoryBytes { get; private set; }
    /// <summary>Undo steps forgotten so far to stay within the bound.</summary>
    public int Forgotten { get; private set; }

    /// <summary>Applies a command and records it. A command that changes no strand is not recorded (returns false).</summary>
    public bool Do(EditCommand command)
    {
        ArgumentNullException.ThrowIfNull(command);
        if (command.Strands.Count == 0) return false;
        command.Apply();
        while (_redo.Count > 0) MemoryBytes -= _redo.Pop().MemoryBytes;
        _undo.AddLast(command);
        MemoryBytes += command.MemoryBytes;
        while (MemoryBytes > MaxBytes && _undo.Count > 0)
        {
            MemoryBytes -= _undo.First!.Value.MemoryBytes;
            _undo.RemoveFirst();
            Forgotten++;
        }
        return true;
    }

    public bool Undo()
    {
        if (_undo.Count == 0) return false;
        var c = _undo.Last!.Value;
        _undo.RemoveLast();
        c.Revert();
        _redo.Push(c);
        return true;
    }

    public bool Redo()
    {
        if (_redo.Count == 0) return false;
        var c = _redo.Pop();
        c.Apply();
        _undo.AddLast(c);
        return true;
    }

    public void Clear()
    {
        _undo.Clear(); _redo.Clear(); MemoryBytes = 0;
    }
}
