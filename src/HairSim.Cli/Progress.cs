namespace HairSim.Cli;

/// <summary>A progress line: rewritten in place on a terminal, printed every ~10 % otherwise (CI logs).</summary>
public sealed class Progress
{
    private readonly string _label;
    private readonly long _total;
    private readonly bool _interactive = !Console.IsErrorRedirected;
    private int _lastShown = -1;

    public Progress(string label, long total) { _label = label; _total = Math.Max(1, total); }

    public void Report(long done, string detail = "")
    {
        int pct = (int)(100 * done / _total);
        if (_interactive)
        {
            if (pct == _lastShown && done != _total) return;
            Console.Error.Write($"\r{_label} {pct,3}% {detail}   ");
            if (done >= _total) Console.Error.WriteLine();
        }
        else if (pct / 10 != _lastShown / 10 || done >= _total)
        {
            if (pct / 10 == _lastShown / 10) return;
            Console.Error.WriteLine($"{_label} {pct,3}% {detail}");
        }
        _lastShown = pct;
    }
}
