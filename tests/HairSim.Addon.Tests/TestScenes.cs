using System.Numerics;
using HairSim;

namespace HairSheet.Addon.Tests;

/// <summary>Small grooms for tests (the reference scene is for the bench).</summary>
internal static class TestScenes
{
    public static GroomSettings SmallGroom(int sheets = 6, int strands = 4, int particles = 8) => new()
    {
        SheetCount = sheets, StrandsPerSheet = strands, ParticlesPerStrand = particles, StrandLength = 0.2f,
    };

    /// <summary>A simulated scene with render output, stepped a few frames so strands have moved.</summary>
    public static HairScene SteppedScene(int strandsPerGap = 1, int frames = 3)
    {
        var scene = GroomBuilder.BuildScene(SmallGroom());
        scene.Render = new RenderSettings { StrandsPerGap = strandsPerGap };
        var sim = new HairSimulation(scene);
        for (int f = 0; f < frames; f++) sim.Step(1f / 60f);
        return scene;
    }

    public static void AssertClose(Vector3 expected, Vector3 actual, float tol = 1e-5f)
    {
        Assert.True(Vector3.Distance(expected, actual) <= tol, $"expected {expected}, got {actual} (|Δ| = {Vector3.Distance(expected, actual)})");
    }

    public static void AssertClose(Vector2 expected, Vector2 actual, float tol = 1e-3f)
    {
        Assert.True(Vector2.Distance(expected, actual) <= tol, $"expected {expected}, got {actual}");
    }
}
