using System.Globalization;
using System.Reflection;
using System.Text;

namespace HairSheet.Logic;

/// <summary>
/// The hair a node has grown, one generation per growth, each with its own edit history. Changing a groom or
/// simulation value regrows the hair as a new generation. The editor's undo entries for hair edits carry the
/// generation they were made in, and the generations that hold edits are kept (the newest <see cref="MaxKept"/>):
/// undoing the value change puts the old values back, <see cref="TryRestore"/> finds the generation grown from them,
/// and that hair comes back with its history, so the earlier entries undo and redo again. An entry whose generation is
/// not live does nothing, and <see cref="Explain"/> says why, instead of acting on hair it was not made on.
/// </summary>
public sealed class HairGenerations<T> where T : class
{
    private sealed record Kept(int Generation, string Key, T State);

    private readonly List<Kept> _kept = new();
    private int _last;

    public HairGenerations(int maxKept = 2)
    {
        if (maxKept < 0) throw new ArgumentOutOfRangeException(nameof(maxKept), maxKept, "The number of kept generations must not be negative.");
        MaxKept = maxKept;
    }

    /// <summary>How many earlier generations are kept (each holds a whole grown scene).</summary>
    public int MaxKept { get; }
    /// <summary>The live generation; 0 before the first growth.</summary>
    public int Current { get; private set; }
    /// <summary>The key of the inputs the live generation was grown from.</summary>
    public string? CurrentKey { get; private set; }
    public T? Live { get; private set; }
    /// <summary>Kept generations, oldest first.</summary>
    public IReadOnlyList<int> KeptGenerations => _kept.ConvertAll(k => k.Generation);

    public bool IsLive(int generation) => generation > 0 && generation == Current;

    /// <summary>
    /// Makes the kept generation grown from <paramref name="key"/> live again, if there is one. The live generation is
    /// kept first when <paramref name="keepLive"/> (it holds edits an undo entry may come back to).
    /// </summary>
    public bool TryRestore(string key, bool keepLive, out T? state)
    {
        int i = _kept.FindIndex(k => k.Key == key);
        if (i < 0) { state = null; return false; }
        var found = _kept[i];
        _kept.RemoveAt(i);
        RetireLive(keepLive);
        (Current, CurrentKey, Live) = (found.Generation, found.Key, found.State);
        state = found.State;
        return true;
    }

    /// <summary>
    /// Newly grown hair becomes live as a new generation. A kept generation of the same inputs is dropped: the new hair
    /// replaces it (a reset to the groom as grown).
    /// </summary>
    public int Adopt(string key, T state, bool keepLive)
    {
        ArgumentNullException.ThrowIfNull(key);
        ArgumentNullException.ThrowIfNull(state);
        RetireLive(keepLive);
        _kept.RemoveAll(k => k.Key == key);
        (Current, CurrentKey, Live) = (++_last, key, state);
        return Current;
    }

    private void RetireLive(bool keep)
    {
        if (Live == null || !keep || MaxKept == 0) return;
        _kept.Add(new Kept(Current, CurrentKey!, Live));
        while (_kept.Count > MaxKept) _kept.RemoveAt(0); // the longest retired goes first
    }

    /// <summary>Why an undo entry of <paramref name="generation"/> does nothing now; null when it is live.</summary>
    public string? Explain(int generation, string editName, bool undo)
    {
        if (IsLive(generation)) return null;
        string what = $"{(undo ? "Undo" : "Redo")} of \"{editName}\" skipped";
        if (generation <= 0 || generation > _last)
            return $"{what}: it names hair generation {generation}, which this node never grew (the hair shown is generation {Current}).";
        if (_kept.Exists(k => k.Generation == generation))
            return $"{what}: it was made on the hair as grown before a groom or simulation value changed (generation {generation}; " +
                   $"the hair shown is generation {Current}). Undo or redo that value change first: the hair comes back with its edits.";
        return $"{what}: it was made on hair that has been regrown since (generation {generation}) and is no longer kept " +
               $"(the last {MaxKept} styled growths are); the hair shown (generation {Current}) is unchanged.";
    }
}

/// <summary>The inputs a hair node grows its hair from, as a key: equal keys grow the same hair.</summary>
public static class GrowthKey
{
    // Every settable value regrows the hair except the colours, which the node pushes to the renderer as they change:
    // a colour change between two growths must not make the earlier hair unreachable.
    private static readonly PropertyInfo[] Inputs = typeof(HairNodeSettings)
        .GetProperties(BindingFlags.Public | BindingFlags.Instance)
        .Where(p => p.CanRead && p.CanWrite && p.Name is not (nameof(HairNodeSettings.RootColor) or nameof(HairNodeSettings.TipColor)))
        .OrderBy(p => p.Name, StringComparer.Ordinal)
        .ToArray();

    /// <summary>
    /// The key of <paramref name="settings"/>, plus the groom of an assigned hairstyle resource and that resource's
    /// identity (two resources with the same groom hold different styles). The style data is left out: the node writes
    /// it after every edit, so it follows the hair rather than choosing it. <paramref name="scalp"/> is the scalp mesh's
    /// key (<see cref="ScalpGrowth.Key"/>) when the hair grows on a mesh: then the Scalp values count too.
    /// </summary>
    public static string Of(HairNodeSettings settings, HairstyleRecord? style = null, ulong styleId = 0, string? scalp = null)
    {
        ArgumentNullException.ThrowIfNull(settings);
        var sb = new StringBuilder();
        foreach (var p in Inputs)
        {
            // The scalp values grow nothing without a scalp mesh: changing them must not regrow the ellipsoid groom.
            if (scalp == null && p.Name.StartsWith("Scalp", StringComparison.Ordinal)) continue;
            sb.Append(p.Name).Append('=').Append(Text(p.GetValue(settings))).Append(';');
        }
        if (scalp != null) sb.Append("scalp:").Append(scalp).Append(';');
        if (style != null)
            sb.Append("style#").Append(styleId).Append(':')
              .Append(style.Sheets).Append(',').Append(style.StrandsPerSheet).Append(',').Append(style.ParticlesPerStrand).Append(',')
              .Append(Text(style.StrandLength)).Append(',').Append(Text(style.HeadRadii)).Append(',').Append(Text(style.HeadCenter)).Append(',')
              .Append(Text(style.RootJitter)).Append(',').Append(style.PinnedPerStrand).Append(',').Append(style.Seed);
        return sb.ToString();
    }

    // Invariant and round-trip ("G" is the shortest round-trip text for floats): two values differ in the key exactly
    // when they differ.
    private static string Text(object? value) => value is IFormattable f ? f.ToString(null, CultureInfo.InvariantCulture) : value?.ToString() ?? "";
}
