using Godot;
using HairSheet.Logic;
using HairSim;

namespace HairSheet;

/// <summary>
/// A groom saved in the scene: the settings that grow the base hair plus the styled state (cuts, fitted rest
/// shapes) as bytes in HairSim's hairstyle format. Assign it to a HairSystem3D; a styled haircut is saved with
/// the scene (.tscn/.tres) and reopens identical. Conversion and validation live in Logic/HairstyleRecord.
/// </summary>
[Tool]
[GlobalClass]
public partial class Hairstyle : Resource
{
    [Export(PropertyHint.Range, "1,100000,1")] public int Sheets { get; set; } = 435;
    [Export(PropertyHint.Range, "1,4096,1")] public int StrandsPerSheet { get; set; } = 40;
    [Export(PropertyHint.Range, "3,4096,1")] public int ParticlesPerStrand { get; set; } = 16;
    [Export(PropertyHint.Range, "0.001,10,0.001,suffix:m")] public float StrandLength { get; set; } = 0.25f;
    [Export] public Vector3 HeadRadii { get; set; } = new(0.078f, 0.1f, 0.095f);
    [Export] public Vector3 HeadCenter { get; set; } = Vector3.Zero;
    [Export(PropertyHint.Range, "0,1,0.01")] public float RootJitter { get; set; } = 0.5f;
    [Export(PropertyHint.Range, "1,8,1")] public int PinnedPerStrand { get; set; } = 2;
    /// <summary>Groom seed (Godot exports 64-bit integers as long).</summary>
    [Export] public long Seed { get; set; } = 2009;
    /// <summary>The styled state; empty = the groom as grown.</summary>
    [Export] public byte[] StyleData { get; set; } = [];

    public HairstyleRecord ToRecord() => new(Sheets, StrandsPerSheet, ParticlesPerStrand, StrandLength,
        HeadRadii.ToNumerics(), HeadCenter.ToNumerics(), RootJitter, PinnedPerStrand, unchecked((ulong)Seed), StyleData ?? []);

    public void SetFrom(HairstyleRecord r)
    {
        Sheets = r.Sheets; StrandsPerSheet = r.StrandsPerSheet; ParticlesPerStrand = r.ParticlesPerStrand;
        StrandLength = r.StrandLength; HeadRadii = r.HeadRadii.ToGodot(); HeadCenter = r.HeadCenter.ToGodot();
        RootJitter = r.RootJitter; PinnedPerStrand = r.PinnedPerStrand; Seed = unchecked((long)r.Seed);
        StyleData = r.StyleData;
        EmitChanged();
    }

    /// <summary>Grows the groom (validated: a corrupt resource throws InvalidDataException) and applies the style.</summary>
    public HairScene BuildScene(SimulationSettings settings)
    {
        var record = ToRecord();
        var scene = GroomBuilder.BuildScene(record.ToGroom(), settings);
        if (record.HasStyle) HairStyleIO.Load(scene, record.StyleData);
        return scene;
    }
}
