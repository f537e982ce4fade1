namespace HairSim.Cli.Studio;

/// <summary>The grooms the studio offers by name: the reference scene and lighter ones for slower machines.</summary>
public static class StudioGrooms
{
    public const string Default = "reference";

    /// <summary>Name, what it is (shown in the page), and how to build it.</summary>
    public static readonly IReadOnlyList<(string Name, string Description, Func<GroomSettings> Build)> All =
    [
        ("reference", "reference scene: 17,400 strands × 16 particles, 25 cm", GroomSettings.Reference),
        ("medium", "5,220 strands × 16 particles, 25 cm", () => new GroomSettings { StrandsPerSheet = 12 }),
        ("long", "6,960 strands × 24 particles, 45 cm", () => new GroomSettings { StrandsPerSheet = 16, ParticlesPerStrand = 24, StrandLength = 0.45f }),
        ("short", "8,700 strands × 8 particles, 10 cm", () => new GroomSettings { StrandsPerSheet = 20, ParticlesPerStrand = 8, StrandLength = 0.1f }),
        ("small", "960 strands × 12 particles, 25 cm (for slow machines and tests)", () => new GroomSettings { SheetCount = 120, StrandsPerSheet = 8, ParticlesPerStrand = 12 }),
        (MeshHead, "6,000 strands × 16 particles grown on a mesh head with ears, nose and neck (distance-field collision)",
            () => new GroomSettings { SheetCount = 300, StrandsPerSheet = 20 }),
    ];

    /// <summary>The groom grown on <see cref="HairSim.Meshes.ProceduralHead"/> instead of the ellipsoid.</summary>
    public const string MeshHead = "mesh head";

    /// <summary>
    /// The named groom's scene: on the ellipsoid head, or for <see cref="MeshHead"/> on <paramref name="head"/> (a user's
    /// head from `studio --head file`), else the project's mesh head.
    /// </summary>
    public static HairScene BuildScene(string name, int? strandsPerSheet = null, HairSim.Meshes.TriangleMesh? head = null)
    {
        var g = Create(name, strandsPerSheet);
        if (!IsMesh(name)) return GroomBuilder.BuildScene(g);
        var mesh = head ?? HairSim.Meshes.ProceduralHead.Create();
        var field = HairSim.Meshes.SignedDistanceField.Bake(mesh, 0.0025f);
        return HairSim.Meshes.MeshScalp.BuildScene(mesh, field, MeshSettings(g));
    }

    /// <summary>Whether the named groom grows on a mesh (and so can be painted and grown again on a painted scalp).</summary>
    public static bool IsMesh(string name) => string.Equals(name, MeshHead, StringComparison.OrdinalIgnoreCase);

    /// <summary>A vertex whose colour is at least this red is scalp (the mesh head's own mask, where painting starts).</summary>
    public const float ScalpMaskThreshold = 0.5f;

    /// <summary>How a mesh groom grows: the groom's strands, density and length on the mesh's vertex-colour scalp.</summary>
    public static HairSim.Meshes.MeshGroomSettings MeshSettings(GroomSettings g) => new()
    {
        SheetCount = g.SheetCount, StrandsPerSheet = g.StrandsPerSheet, ParticlesPerStrand = g.ParticlesPerStrand,
        StrandLength = g.StrandLength, ScalpMaskThreshold = ScalpMaskThreshold,
    };

    /// <summary>The named groom, with its strands per sheet (the density) overridden when given.</summary>
    public static GroomSettings Create(string name, int? strandsPerSheet = null)
    {
        foreach (var g in All)
        {
            if (!string.Equals(g.Name, name, StringComparison.OrdinalIgnoreCase)) continue;
            var settings = g.Build();
            if (strandsPerSheet is int n)
            {
                if (n < 1 || n > 64) throw new ArgumentOutOfRangeException(nameof(strandsPerSheet), n, "Density must be 1 … 64 strands per sheet.");
                settings.StrandsPerSheet = n;
            }
            settings.Validate();
            return settings;
        }
        throw new ArgumentException($"Unknown groom '{name}'; choose one of: {string.Join(", ", All.Select(g => g.Name))}.");
    }
}
