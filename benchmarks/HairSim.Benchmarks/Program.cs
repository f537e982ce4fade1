using BenchmarkDotNet.Running;

// dotnet run -c Release --project benchmarks/HairSim.Benchmarks -- --filter '*'
BenchmarkSwitcher.FromAssembly(typeof(HairSim.Benchmarks.FrameBenchmarks).Assembly).Run(args);
