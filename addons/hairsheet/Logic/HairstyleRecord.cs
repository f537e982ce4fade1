using System.Numerics;
using HairSim;

namespace HairSheet.Logic;

/// <summary>
/// What the Hairstyle resource stores, engine-free: the groom that grows the base hair, plus the styled
/// state (cuts, fitted rest shapes) as an opaque blob in HairSim's hairstyle file format. The resource keeps
/// these as exported properties so a styled haircut is saved inside the scene and reopens identical.
/// </summary>
public sealed record HairstyleRecord(
    int Sheets, int StrandsPerSheet, int ParticlesPerStrand, float StrandLength,
    Vector3 HeadRadii, Vector3 HeadCenter, float RootJitter, int PinnedPerStrand, ulong Seed, byte[] StyleData)
{
    /// <summary>
    /// For a haircut styled on hair grown on a Scalp Mesh: what it was styled on (<see cref="ScalpGrowth.StyleKey"/>);
    /// the groom numbers above are then not used. Empty: a groom grown on the Head Radii ellipsoid.
    /// </summary>
    public string ScalpStyleKey { get; init; } = "";

    public bool IsScalpStyle => ScalpStyleKey.Length > 0;

    public static HairstyleRecord FromGroom(GroomSettings g, byte[]? styleData = null)
    {
        ArgumentNullException.ThrowIfNull(g);
        g.Validate();
        return new HairstyleRecord(g.SheetCount, g.StrandsPerSheet, g.ParticlesPerStrand, g.StrandLength,
            g.HeadRadii, g.HeadCenter, g.RootJitter, g.PinnedPerStrand, g.Seed, styleData ?? []);
    }

    /// <summary>The groom, validated: a corrupt or hand-edited resource gives a clear error, never a broken world.</summary>
    public GroomSettings ToGroom()
    {
        var g = GroomSettings.Reference();
        g.SheetCount = Sheets;
        g.StrandsPerSheet = StrandsPerSheet;
        g.ParticlesPerStrand = ParticlesPerStrand;
        g.StrandLength = StrandLength;
        g.HeadRadii = HeadRadii;
        g.HeadCenter = HeadCenter;
        g.RootJitter = RootJitter;
        g.PinnedPerStrand = PinnedPerStrand;
        g.Seed = Seed;
        try { g.Validate(); }
        catch (ArgumentException e) { throw new InvalidDataException($"The hairstyle resource holds an invalid groom: {e.Message}", e); }
        return g;
    }

    public bool HasStyle => StyleData.Length > 0;
}
