using System.Xml.Linq;
using HairSim.Measurement;

namespace HairSim.Tests.Measurement;

public class SvgPlotTests
{
    private static readonly XNamespace Svg = "http://www.w3.org/2000/svg";

    [Fact]
    public void ScatterIsWellFormedAndDrawsEveryPlottablePoint()
    {
        var points = new List<SvgPlot.Point>
        {
            new(100, 0.5, "a & b", "<first>"), new(1000, 0.01, "a & b", "second"), new(5000, 0.001, "c"),
            new(200, double.NaN, "c"), new(300, 0, "c"),
        };
        var doc = XDocument.Parse(SvgPlot.Scatter("t", "x", "y", points, [0, 1, 2], 1));
        // 3 plottable points + the defaults ring + legend markers (2 series + defaults).
        int circles = doc.Descendants(Svg + "circle").Count();
        Assert.Equal(3 + 1 + 2 + 1, circles);
        Assert.Contains(doc.Descendants(Svg + "title"), e => e.Value == "<first>");
        Assert.Single(doc.Descendants(Svg + "polyline"));
    }

    [Fact]
    public void HeatMapHasACellPerEntryAndChecksItsShape()
    {
        var cells = new SvgPlot.Cell[2, 3];
        for (int r = 0; r < 2; r++) for (int c = 0; c < 3; c++) cells[r, c] = new SvgPlot.Cell("#81c784", $"{r}{c}");
        var doc = XDocument.Parse(SvgPlot.HeatMap("t", "rows", ["a", "b"], "cols", ["x", "y", "z"], cells, [("#81c784", "stable")]));
        // background + 6 cells + 1 legend swatch
        Assert.Equal(1 + 6 + 1, doc.Descendants(Svg + "rect").Count());
        Assert.Throws<ArgumentException>(() => SvgPlot.HeatMap("t", "rows", ["a"], "cols", ["x", "y", "z"], cells, []));
    }

    private const string LongTitle = "Stability of the default bend model: hair length 1 cm to 10 m against the frame time " +
        "from 1/960 to 1/15 s, with guards on, every cell finite";

    /// <summary>
    /// The title's lines as drawn: each must fit the picture (at 9 px a character, the most a 15 px bold sans-serif
    /// character takes) since a centred line wider than the picture is clipped at both ends; together they are the
    /// title; and the chart below starts under the last line.
    /// </summary>
    private static void AssertTitleFits(string svg, string title, Func<XDocument, double> chartTop)
    {
        var doc = XDocument.Parse(svg);
        double width = double.Parse(doc.Root!.Attribute("width")!.Value, System.Globalization.CultureInfo.InvariantCulture);
        var lines = doc.Root.Elements(Svg + "text").Where(t => t.Attribute("font-weight")?.Value == "bold").ToList();
        Assert.True(lines.Count > 1, "a title this long should wrap");
        foreach (var line in lines)
            Assert.True(line.Value.Length * 9.0 <= width - 20, $"title line \"{line.Value}\" ({line.Value.Length} characters) is wider than the {width} px picture");
        Assert.Equal(title, string.Join(" ", lines.Select(l => l.Value)));
        double lastBaseline = lines.Max(l => double.Parse(l.Attribute("y")!.Value, System.Globalization.CultureInfo.InvariantCulture));
        Assert.True(chartTop(doc) > lastBaseline + 4, $"the chart starts at {chartTop(doc)}, over the title's last line at {lastBaseline}");
    }

    private static double Y(XElement e, string attribute) =>
        double.Parse(e.Attribute(attribute)!.Value, System.Globalization.CultureInfo.InvariantCulture);

    [Fact]
    public void LongTitlesWrapInsideEveryChart()
    {
        var points = new List<SvgPlot.Point> { new(100, 0.5, "a"), new(1000, 0.01, "a") };
        // Scatter: the plot frame is the first rect after the background.
        AssertTitleFits(SvgPlot.Scatter(LongTitle, "x", "y", points, [0, 1], 0, width: 600, height: 400), LongTitle,
            d => Y(d.Root!.Elements(Svg + "rect").ElementAt(1), "y"));

        var cells = new SvgPlot.Cell[1, 2];
        cells[0, 0] = new SvgPlot.Cell("#81c784", "ok"); cells[0, 1] = new SvgPlot.Cell("#e57373", "nan");
        // Heat map: the column labels sit above the first row of cells; the chart starts at the highest text after the title.
        AssertTitleFits(SvgPlot.HeatMap(LongTitle, "rows", ["a"], "cols", ["x", "y"], cells, [("#81c784", "stable")]), LongTitle,
            d => d.Root!.Elements(Svg + "text").Where(t => t.Attribute("font-weight") == null).Min(t => Y(t, "y")) - 12);

        // Bars: the grid lines start at the chart's top.
        AssertTitleFits(SvgPlot.Bars(LongTitle + " and then some more words to pass 860 px of width in the bar chart as well",
                "ms", ["g"], ["s"], [[1.0]]), LongTitle + " and then some more words to pass 860 px of width in the bar chart as well",
            d => d.Root!.Elements(Svg + "line").Min(l => Y(l, "y1")));
    }
}
