using System.Diagnostics;
using System.Reflection;
using HairSim;

namespace HairSim.Tests.Core;

/// <summary>
/// The library is compiled with the JIT optimiser on in every configuration (Godot's editor builds it in Debug, its
/// exports in ExportDebug and ExportRelease): this test runs against the Debug build that `dotnet test` makes, and
/// .ci/run checks an ExportRelease build the same way (.ci/jit-optimised.fsx).
/// </summary>
public class SimulationAssemblyTests
{
    [Fact]
    public void TheLibraryIsBuiltWithTheJitOptimiserOn()
    {
        var debuggable = typeof(HairWorld).Assembly.GetCustomAttribute<DebuggableAttribute>();
        Assert.False(debuggable?.IsJITOptimizerDisabled ?? false, "HairSim.dll was built with the JIT optimiser disabled");
        // The test assembly itself is a plain Debug build: the attribute is read, not assumed.
        Assert.True(typeof(SimulationAssemblyTests).Assembly.GetCustomAttribute<DebuggableAttribute>()?.IsJITOptimizerDisabled);
    }
}
