using BenchmarkDotNet.Running;

// dotnet run -c Release --project benchmarks/HairSim.Editing.Benchmarks -- --filter '*' [--job short]
BenchmarkSwitcher.FromAssembly(typeof(HairSim.Editing.Benchmarks.CutBenchmarks).Assembly).Run(args);
