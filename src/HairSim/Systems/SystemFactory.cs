namespace HairSim;

/// <summary>
/// How a system joins a pipeline: it is created only if <see cref="IsNeeded"/> says the scene has its data.
/// <see cref="CreateFast"/> is the optimised implementation, if the system has one.
/// </summary>
public sealed record SystemFactory(
    string Name,
    SystemPhase Phase,
    int Order,
    Func<HairScene, bool> IsNeeded,
    Func<HairScene, IHairSystem> CreateReference,
    Func<HairScene, IHairSystem>? CreateFast = null);
