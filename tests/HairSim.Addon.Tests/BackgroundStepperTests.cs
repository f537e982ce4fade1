using System.Numerics;
using HairSheet.Logic;
using HairSim;

namespace HairSheet.Addon.Tests;

[CollectionDefinition(nameof(BackgroundStepperCollection), DisableParallelization = true)]
public class BackgroundStepperCollection { }

/// <summary>Stepping on a worker with one frame of latency gives the hair of stepping in place, and fails loudly.</summary>
[Collection(nameof(BackgroundStepperCollection))]
public class BackgroundStepperTests
{
    private static HairScene Scene()
    {
        var scene = GroomBuilder.BuildScene(new GroomSettings { SheetCount = 8, StrandsPerSheet = 8, ParticlesPerStrand = 16 }, new SimulationSettings());
        scene.Render = new RenderSettings();
        return scene;
    }

    private static RigidTransform Head(int f) => new(new Vector3(0.02f * MathF.Sin(f * 0.3f), 0, 0), Quaternion.CreateFromYawPitchRoll(0.2f * MathF.Sin(f * 0.2f), 0, 0));

    [Fact]
    public void SteppingOnTheWorkerGivesTheBitsOfSteppingInPlace()
    {
        var a = Scene(); var b = Scene();
        var simA = new HairSimulation(a); var simB = new HairSimulation(b);
        using var stepper = new BackgroundStepper(simB);
        for (int f = 1; f <= 20; f++)
        {
            for (int i = 0; i < 2; i++) simA.Step(1f / 120f, Head(f));
            stepper.Start(1f / 120f, 2, Head(f));
            Assert.True(stepper.Running);
            stepper.Wait();
            Assert.False(stepper.Running);
            Assert.True(a.World.BitEquals(b.World), $"frame {f}");
            Assert.Equal(a.RenderOutput!.Points, b.RenderOutput!.Points);
        }
        Assert.True(stepper.LastStepMilliseconds > 0);
    }

    [Fact]
    public void AStepsErrorIsRethrownByWaitAndTheStepperGoesOn()
    {
        var scene = Scene();
        using var stepper = new BackgroundStepper(new HairSimulation(scene));
        stepper.Start(float.NaN, 1, RigidTransform.Identity); // Step refuses a non-finite frame time
        Assert.Throws<ArgumentOutOfRangeException>(() => stepper.Wait());
        Assert.Throws<InvalidOperationException>(() => { stepper.Start(1f / 60f, 1, RigidTransform.Identity); stepper.Start(1f / 60f, 1, RigidTransform.Identity); });
        stepper.Wait();
        Assert.Equal(0, scene.World.CountNonFinite());
    }

    [Fact]
    public void DisposeJoinsTheWorkerAndLaterStartsAreRefused()
    {
        var stepper = new BackgroundStepper(new HairSimulation(Scene()));
        stepper.Start(1f / 60f, 1, RigidTransform.Identity);
        stepper.Dispose();
        Assert.False(stepper.Running);
        Assert.Throws<ObjectDisposedException>(() => stepper.Start(1f / 60f, 1, RigidTransform.Identity));
    }

    [Fact]
    public void AFrameOnTheWorkerAllocatesNothingOnceWarm()
    {
        // Every step on the worker thread itself (no helper threads), so its own count is the whole step's: exact, where
        // a process-wide count also saw whatever the test runner's threads allocated meanwhile.
        var scene = Scene();
        using var stepper = new BackgroundStepper(new HairSimulation(scene, dispatcher: SequentialDispatcher.Instance));
        stepper.Start(1f / 60f, 1, Head(0));
        stepper.Wait();
        Assert.True(stepper.LastStepAllocatedBytes > 0, "the first step builds the pipeline, and the count sees it");
        for (int f = 1; f <= 30; f++) { stepper.Start(1f / 60f, 1, Head(f)); stepper.Wait(); }
        long bytes = 0;
        for (int f = 31; f <= 60; f++) { stepper.Start(1f / 60f, 1, Head(f)); stepper.Wait(); bytes += stepper.LastStepAllocatedBytes; }
        Assert.Equal(0, bytes);
    }
}
