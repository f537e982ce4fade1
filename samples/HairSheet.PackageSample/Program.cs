// A game-side program that takes HairSim as a NuGet package, not as a project (README, "Use HairSim in your own
// project"). The code below is the example in src/HairSim/PACKAGE.md, the package's README (PackageTests checks it).
// Build it: dotnet pack src/HairSim -c Release -o artifacts/packages && dotnet run --project samples/HairSheet.PackageSample
using System.Numerics;
using HairSim;

var scene = GroomBuilder.BuildScene(new GroomSettings { SheetCount = 100, StrandsPerSheet = 10 });
using var threads = ThreadDispatchers.CreateDefault();      // dispose it: no worker thread outlives it
var sim = new HairSimulation(scene, dispatcher: threads);
for (int frame = 1; frame <= 120; frame++)                   // 2 s at 60 Hz while the head turns
    sim.Step(1f / 60f, new RigidTransform(Vector3.Zero, Quaternion.CreateFromYawPitchRoll(0.4f * MathF.Sin(frame / 12f), 0, 0)));
var metrics = WorldMetrics.Measure(scene);                 // stretch, penetration, non-finite values
Console.WriteLine(metrics);
return metrics.NonFinite == 0 ? 0 : 3;
