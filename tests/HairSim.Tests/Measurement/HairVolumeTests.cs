using System.Numerics;
using HairSim.Measurement;
using Xunit;

namespace HairSim.Tests.Measurement;

public sealed class HairVolumeTests
{
    [Fact]
    public void OuterLayerIsTheFarthestParticleAboveTheScalpPerDirection()
    {
        // Two strands standing straight up from the top of a unit sphere head, 2 cm and 5 cm tall, in the same bin,
        // and one lying on the side of the head 1 cm out: bins (top, side) → outer layers 5 cm and 1 cm.
        var radii = new Vector3(0.1f);
        var w = new HairWorld(1, 3, 2);
        w.SetStrand(0, [new Vector3(0, 0.1f, 0), new Vector3(0, 0.12f, 0)], pinned: 1);
        w.SetStrand(1, [new Vector3(0, 0.1f, 0), new Vector3(0, 0.15f, 0)], pinned: 1);
        w.SetStrand(2, [new Vector3(0.1f, 0.001f, 0), new Vector3(0.11f, 0.001f, 0)], pinned: 1);
        w.ResetToRest();
        double thickness = HairVolume.OuterLayerThickness(w, Vector3.Zero, radii);
        // Bins: the top (0.05 m outer, the root 0 m shares it), the side (0.01 m); roots on the head are 0 in their own bins.
        Assert.Equal((0.05 + 0.01) / 2, thickness, 4);
    }

    [Fact]
    public void TheReferenceGroomStandsOffTheScalpAndSettlingFlattensIt()
    {
        var g = new GroomSettings { SheetCount = 80, StrandsPerSheet = 10 };
        var scene = GroomBuilder.BuildScene(g);
        double grown = HairVolume.OuterLayerThickness(scene.World, g.HeadCenter, g.HeadRadii);
        var sim = new HairSimulation(scene);
        for (int f = 0; f < 60; f++) sim.Step(1f / 60f);
        double settled = HairVolume.OuterLayerThickness(scene.World, g.HeadCenter, g.HeadRadii);
        Assert.InRange(grown, 0.001, 0.1);
        Assert.InRange(settled, 0.0, grown * 1.5);
    }
}
