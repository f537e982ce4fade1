using System.Globalization;
using System.Security;
using System.Text;

namespace HairSim.Measurement;

/// <summary>A small hand-written SVG writer: a log–log scatter plot with a Pareto front, and a heat-map grid.</summary>
public static class SvgPlot
{
    /// <summary>One point of a scatter plot; <paramref name="Series"/> picks its colour, <paramref name="Label"/> is drawn beside it if set.</summary>
    public readonly record struct Point(double X, double Y, string Series, string? Label = null);

    private static readonly string[] Palette = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#7f7f7f"];

    /// <summary>
    /// Scatter on log–log axes. Points with a non-finite or non-positive coordinate are left out (the table lists
    /// them). <paramref name="front"/> (indices, sorted by x) is joined by a line; <paramref name="highlight"/> gets a ring.
    /// </summary>
    public static string Scatter(string title, string xLabel, string yLabel, IReadOnlyList<Point> points, IReadOnlyList<int> front, int highlight, int width = 960, int height = 600)
    {
        const int left = 80, right = 200, bottom = 60;
        var titleLines = TitleLines(title, width);
        int top = 40 + TitleExtra(titleLines);
        height += TitleExtra(titleLines);
        double pw = width - left - right, ph = height - top - bottom;
        var ok = new List<int>();
        for (int i = 0; i < points.Count; i++)
            if (double.IsFinite(points[i].X) && double.IsFinite(points[i].Y) && points[i].X > 0 && points[i].Y > 0) ok.Add(i);
        double x0 = 1, x1 = 10, y0 = 1e-4, y1 = 10;
        if (ok.Count > 0)
        {
            x0 = double.MaxValue; x1 = double.MinValue; y0 = double.MaxValue; y1 = double.MinValue;
            foreach (int i in ok) { x0 = Math.Min(x0, points[i].X); x1 = Math.Max(x1, points[i].X); y0 = Math.Min(y0, points[i].Y); y1 = Math.Max(y1, points[i].Y); }
        }
        double lx0 = Math.Floor(Math.Log10(x0)), lx1 = Math.Max(lx0 + 1, Math.Ceiling(Math.Log10(x1)));
        double ly0 = Math.Floor(Math.Log10(y0)), ly1 = Math.Max(ly0 + 1, Math.Ceiling(Math.Log10(y1)));
        double Px(double x) => left + (Math.Log10(x) - lx0) / (lx1 - lx0) * pw;
        double Py(double y) => top + ph - (Math.Log10(y) - ly0) / (ly1 - ly0) * ph;

        var sb = new StringBuilder();
        Header(sb, width, height, titleLines);
        sb.Append(F($"<rect x='{left}' y='{top}' width='{pw}' height='{ph}' fill='none' stroke='#444'/>\n"));
        for (double e = lx0; e <= lx1; e++)
        {
            double x = Px(Math.Pow(10, e));
            sb.Append(F($"<line x1='{x:F1}' y1='{top}' x2='{x:F1}' y2='{top + ph}' stroke='#ddd'/><text x='{x:F1}' y='{top + ph + 18}' text-anchor='middle'>{Tick(e)}</text>\n"));
        }
        for (double e = ly0; e <= ly1; e++)
        {
            double y = Py(Math.Pow(10, e));
            sb.Append(F($"<line x1='{left}' y1='{y:F1}' x2='{left + pw}' y2='{y:F1}' stroke='#ddd'/><text x='{left - 6}' y='{y + 4:F1}' text-anchor='end'>{Tick(e)}</text>\n"));
        }
        sb.Append(F($"<text x='{left + pw / 2}' y='{height - 15}' text-anchor='middle'>{Esc(xLabel)}</text>\n"));
        sb.Append(F($"<text transform='translate(20,{top + ph / 2}) rotate(-90)' text-anchor='middle'>{Esc(yLabel)}</text>\n"));

        var series = new List<string>();
        foreach (var p in points) if (!series.Contains(p.Series)) series.Add(p.Series);
        var frontOk = new List<int>();
        foreach (int i in front) if (ok.Contains(i)) frontOk.Add(i);
        if (frontOk.Count > 1)
        {
            sb.Append("<polyline fill='none' stroke='#000' stroke-width='1.5' stroke-dasharray='5,3' points='");
            foreach (int i in frontOk) sb.Append(F($"{Px(points[i].X):F1},{Py(points[i].Y):F1} "));
            sb.Append("'/>\n");
        }
        foreach (int i in ok)
        {
            var p = points[i];
            string c = Palette[series.IndexOf(p.Series) % Palette.Length];
            bool onFront = frontOk.Contains(i);
            sb.Append(F($"<circle cx='{Px(p.X):F1}' cy='{Py(p.Y):F1}' r='{(onFront ? 5 : 3.5)}' fill='{c}' fill-opacity='{(onFront ? 1 : 0.55)}'><title>{Esc(p.Label ?? p.Series)}</title></circle>\n"));
            if (onFront && p.Label != null)
                sb.Append(F($"<text x='{Px(p.X) + 7:F1}' y='{Py(p.Y) - 6:F1}' font-size='10'>{Esc(p.Label)}</text>\n"));
        }
        if (highlight >= 0 && ok.Contains(highlight))
        {
            var p = points[highlight];
            sb.Append(F($"<circle cx='{Px(p.X):F1}' cy='{Py(p.Y):F1}' r='10' fill='none' stroke='#000' stroke-width='2'/>\n"));
        }
        for (int k = 0; k < series.Count; k++)
        {
            double y = top + 10 + 18 * k;
            sb.Append(F($"<circle cx='{left + pw + 20}' cy='{y}' r='5' fill='{Palette[k % Palette.Length]}'/><text x='{left + pw + 30}' y='{y + 4}'>{Esc(series[k])}</text>\n"));
        }
        double ly = top + 18 * series.Count + 20;
        sb.Append(F($"<line x1='{left + pw + 12}' y1='{ly}' x2='{left + pw + 28}' y2='{ly}' stroke='#000' stroke-dasharray='5,3'/><text x='{left + pw + 30}' y='{ly + 4}'>Pareto front</text>\n"));
        sb.Append(F($"<circle cx='{left + pw + 20}' cy='{ly + 20}' r='8' fill='none' stroke='#000' stroke-width='2'/><text x='{left + pw + 30}' y='{ly + 24}'>defaults</text>\n"));
        sb.Append("</svg>\n");
        return sb.ToString();
    }

    /// <summary>One heat-map cell: fill colour and a short text (for example the worst stretch).</summary>
    public readonly record struct Cell(string Fill, string Text, string? Tooltip = null);

    /// <summary>
    /// A grid with <paramref name="rowLabels"/> down the side and <paramref name="columnLabels"/> along the top;
    /// cells[row, column].
    /// </summary>
    public static string HeatMap(string title, string rowAxis, IReadOnlyList<string> rowLabels, string columnAxis, IReadOnlyList<string> columnLabels, Cell[,] cells, IReadOnlyList<(string Fill, string Meaning)> legend)
    {
        int rows = rowLabels.Count, cols = columnLabels.Count;
        if (cells.GetLength(0) != rows || cells.GetLength(1) != cols) throw new ArgumentException("The cell grid does not match the labels.", nameof(cells));
        // Cells as wide as the longest column label or cell text (about 7 px a character at this font size).
        int longest = 8;
        foreach (var c in columnLabels) longest = Math.Max(longest, c.Length);
        foreach (var c in cells) longest = Math.Max(longest, c.Text.Length);
        int cw = 12 + 7 * longest;
        const int ch = 30, left = 150;
        int width = Math.Max(left + cols * cw + 20, left + 460);
        var titleLines = TitleLines(title, width);
        int top = 70 + TitleExtra(titleLines);
        int height = top + rows * ch + 30 + 20 * legend.Count;
        var sb = new StringBuilder();
        Header(sb, width, height, titleLines);
        sb.Append(F($"<text x='{left + cols * cw / 2}' y='{top - 32}' text-anchor='middle'>{Esc(columnAxis)}</text>\n"));
        sb.Append(F($"<text x='10' y='{top - 10}'>{Esc(rowAxis)} ↓</text>\n"));
        for (int c = 0; c < cols; c++)
            sb.Append(F($"<text x='{left + c * cw + cw / 2}' y='{top - 10}' text-anchor='middle'>{Esc(columnLabels[c])}</text>\n"));
        for (int r = 0; r < rows; r++)
        {
            sb.Append(F($"<text x='{left - 8}' y='{top + r * ch + ch / 2 + 4}' text-anchor='end'>{Esc(rowLabels[r])}</text>\n"));
            for (int c = 0; c < cols; c++)
            {
                var cell = cells[r, c];
                int x = left + c * cw, y = top + r * ch;
                sb.Append(F($"<rect x='{x}' y='{y}' width='{cw}' height='{ch}' fill='{cell.Fill}' stroke='#fff'>"));
                if (cell.Tooltip != null) sb.Append(F($"<title>{Esc(cell.Tooltip)}</title>"));
                sb.Append(F($"</rect><text x='{x + cw / 2}' y='{y + ch / 2 + 4}' text-anchor='middle' font-size='11'>{Esc(cell.Text)}</text>\n"));
            }
        }
        for (int k = 0; k < legend.Count; k++)
        {
            int y = top + rows * ch + 16 + 20 * k;
            sb.Append(F($"<rect x='{left}' y='{y}' width='14' height='14' fill='{legend[k].Fill}'/><text x='{left + 20}' y='{y + 11}'>{Esc(legend[k].Meaning)}</text>\n"));
        }
        sb.Append("</svg>\n");
        return sb.ToString();
    }

    /// <summary>
    /// Grouped horizontal bars on a linear axis from 0: one group per <paramref name="groupLabels"/> entry, one bar per
    /// series in each (values[series][group], drawn with its value). Non-finite or negative values draw no bar.
    /// </summary>
    public static string Bars(string title, string valueLabel, IReadOnlyList<string> groupLabels, IReadOnlyList<string> seriesLabels, double[][] values)
    {
        if (values.Length != seriesLabels.Count) throw new ArgumentException("One row of values per series.", nameof(values));
        foreach (var row in values)
            if (row.Length != groupLabels.Count) throw new ArgumentException("One value per group in every series.", nameof(values));
        const int left = 190, right = 60, bar = 14, gap = 12, width = 860;
        var titleLines = TitleLines(title, width);
        int top = 40 + TitleExtra(titleLines);
        int groupHeight = seriesLabels.Count * bar + gap;
        int height = top + groupLabels.Count * groupHeight + 50 + 18 * seriesLabels.Count;
        double pw = width - left - right, max = 0;
        foreach (var row in values) foreach (double v in row) if (double.IsFinite(v)) max = Math.Max(max, v);
        max = max > 0 ? NiceCeiling(max) : 1;
        double Px(double v) => left + v / max * pw;

        var sb = new StringBuilder();
        Header(sb, width, height, titleLines);
        double axisY = top + groupLabels.Count * groupHeight;
        for (int k = 0; k <= 5; k++)
        {
            double v = max * k / 5, x = Px(v);
            sb.Append(F($"<line x1='{x:F1}' y1='{top}' x2='{x:F1}' y2='{axisY}' stroke='#ddd'/><text x='{x:F1}' y='{axisY + 16}' text-anchor='middle'>{v:0.##}</text>\n"));
        }
        sb.Append(F($"<text x='{left + pw / 2}' y='{axisY + 34}' text-anchor='middle'>{Esc(valueLabel)}</text>\n"));
        for (int g = 0; g < groupLabels.Count; g++)
        {
            double y0 = top + g * groupHeight;
            sb.Append(F($"<text x='{left - 8}' y='{y0 + seriesLabels.Count * bar / 2.0 + 4:F1}' text-anchor='end'>{Esc(groupLabels[g])}</text>\n"));
            for (int k = 0; k < seriesLabels.Count; k++)
            {
                double v = values[k][g];
                if (!double.IsFinite(v) || v < 0) continue;
                double y = y0 + k * bar;
                sb.Append(F($"<rect x='{left}' y='{y:F1}' width='{Px(v) - left:F1}' height='{bar - 2}' fill='{Palette[k % Palette.Length]}'><title>{Esc(seriesLabels[k])}: {v:0.###}</title></rect>"));
                sb.Append(F($"<text x='{Px(v) + 4:F1}' y='{y + bar - 4:F1}' font-size='10'>{v:0.##}</text>\n"));
            }
        }
        for (int k = 0; k < seriesLabels.Count; k++)
        {
            double y = axisY + 48 + 18 * k;
            sb.Append(F($"<rect x='{left}' y='{y - 10}' width='14' height='12' fill='{Palette[k % Palette.Length]}'/><text x='{left + 20}' y='{y}'>{Esc(seriesLabels[k])}</text>\n"));
        }
        sb.Append("</svg>\n");
        return sb.ToString();
    }

    /// <summary>The smallest of 1, 2, 2.5, 5 × 10^k at or above <paramref name="v"/> (v &gt; 0).</summary>
    private static double NiceCeiling(double v)
    {
        double p = Math.Pow(10, Math.Floor(Math.Log10(v)));
        foreach (double m in new[] { 1, 2, 2.5, 5, 10 }) if (m * p >= v) return m * p;
        return 10 * p;
    }

    // The title is 15 px bold sans-serif, about 9 px a character at most; lines are 18 px apart.
    private const double TitleCharWidth = 9;
    private const int TitleLineHeight = 18;

    /// <summary>The title broken at spaces into lines that fit the picture's width (a centred line wider than the picture is clipped at both ends).</summary>
    internal static List<string> TitleLines(string title, int width)
    {
        int fit = Math.Max(10, (int)((width - 20) / TitleCharWidth));
        var lines = new List<string>();
        var line = new StringBuilder();
        foreach (string word in title.Split(' ', StringSplitOptions.RemoveEmptyEntries))
        {
            if (line.Length > 0 && line.Length + 1 + word.Length > fit) { lines.Add(line.ToString()); line.Clear(); }
            if (line.Length > 0) line.Append(' ');
            line.Append(word);
        }
        lines.Add(line.ToString());
        return lines;
    }

    /// <summary>How far a wrapped title pushes the chart down.</summary>
    private static int TitleExtra(List<string> titleLines) => (titleLines.Count - 1) * TitleLineHeight;

    private static void Header(StringBuilder sb, int width, int height, List<string> titleLines)
    {
        sb.Append(F($"<svg xmlns='http://www.w3.org/2000/svg' width='{width}' height='{height}' viewBox='0 0 {width} {height}' font-family='sans-serif' font-size='12'>\n"));
        sb.Append(F($"<rect width='{width}' height='{height}' fill='#fff'/>\n"));
        for (int i = 0; i < titleLines.Count; i++)
            sb.Append(F($"<text x='{width / 2}' y='{20 + i * TitleLineHeight}' text-anchor='middle' font-size='15' font-weight='bold'>{Esc(titleLines[i])}</text>\n"));
    }

    private static string Tick(double exponent) => exponent switch
    {
        >= 0 and <= 5 => Math.Pow(10, exponent).ToString("0", CultureInfo.InvariantCulture),
        < 0 and >= -3 => Math.Pow(10, exponent).ToString("0.###", CultureInfo.InvariantCulture),
        _ => F($"1e{exponent:0}"),
    };

    private static string Esc(string s) => SecurityElement.Escape(s) ?? "";

    private static string F(FormattableString s) => s.ToString(CultureInfo.InvariantCulture);
}
