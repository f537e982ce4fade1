using System.Numerics;
using Xunit;

namespace HairSim.Tests.Core;

/// <summary>
/// The scene the moving-collider tests sweep a bar through: 64 limp strands of 16 particles (chunk-sized) hanging
/// from a row of roots along x, pinned at the root; the bar's depth per frame (behind the hair, then through it at
/// 5 cm a frame, 3 m/s, then held in front), and how many strands it has not moved.
/// </summary>
internal static class SweptCurtain
{
    public const int Strands = 64, N = 16;
    public const float Spacing = 0.015f;
    /// <summary>The frame the bar reaches its place in front of the hair.</summary>
    public const int Arrival = 13;

    public static HairScene Build(SolverPath path)
    {
        var w = new HairWorld(1, Strands, N);
        var pts = new Vector3[N];
        for (int s = 0; s < Strands; s++)
        {
            for (int k = 0; k < N; k++) pts[k] = new Vector3(-0.08f + 0.16f * s / (Strands - 1), -Spacing * k, 0.001f * (s % 3));
            w.SetStrand(s, pts, pinned: 1);
        }
        return new HairScene(w, new SimulationSettings { Path = path, Bend = BendModel.Limp });
    }

    /// <summary>The bar's depth at frame f.</summary>
    public static float BarZ(int f) => -0.075f + 0.05f * Math.Clamp(f - 10, 0, 3);

    /// <summary>Strands the bar has not moved: every particle within 5 mm of the roots' plane z ≈ 0.</summary>
    public static int StrandsUntouched(HairWorld w)
    {
        int untouched = 0;
        for (int s = 0; s < Strands; s++)
        {
            float moved = 0f;
            for (int k = 0; k < N; k++) moved = MathF.Max(moved, MathF.Abs(w.GetPosition(w.StrandFirst[s] + k).Z - 0.001f * (s % 3)));
            if (moved < 5e-3f) untouched++;
        }
        return untouched;
    }

    /// <summary>
    /// Steps 40 frames at 60 Hz with <paramref name="place"/> moving the bar to frame f's depth before each, and returns
    /// the deepest a particle ended a frame inside it (<paramref name="inside"/>); checks that the bar has pushed every
    /// strand by <see cref="Arrival"/>, that the pipeline was never rebuilt and that everything stays finite.
    /// </summary>
    public static float Sweep(HairScene scene, Action<int> place, Func<HairWorld, float> inside)
    {
        var sim = new HairSimulation(scene);
        var pipeline = sim.Pipeline;
        float deepest = 0f;
        for (int f = 1; f <= 40; f++)
        {
            place(f);
            sim.Step(1f / 60f);
            deepest = MathF.Max(deepest, inside(scene.World));
            if (f == Arrival) Assert.Equal(0, StrandsUntouched(scene.World));
        }
        Assert.Same(pipeline, sim.Pipeline);
        Assert.Equal(0, scene.World.CountNonFinite());
        return deepest;
    }
}
