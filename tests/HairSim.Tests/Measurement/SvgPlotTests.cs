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
}
