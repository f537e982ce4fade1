namespace HairSim.Tests.Core;

/// <summary>
/// The crossing sheets at every size and frame rate the docs report (1 cm, 25 cm and 10 m strands at 30, 60 and 240 Hz
/// on the fast path) and 25 cm at 60 Hz on the reference path: shared by the volume's and the contacts' tests.
/// </summary>
public static class CrossingSheetCases
{
    public static TheoryData<SolverPath, int, float> EveryScaleAndRate()
    {
        var d = new TheoryData<SolverPath, int, float>();
        foreach (float scale in new[] { 0.04f, 1f, 40f })
            foreach (int hz in new[] { 30, 60, 240 })
                d.Add(SolverPath.Fast, hz, scale);
        d.Add(SolverPath.Reference, 60, 1f);
        return d;
    }
}
