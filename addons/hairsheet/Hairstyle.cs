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
    // Fields with initializers (Godot's generator takes the defaults from them) and setters that emit Changed, so
    // a HairSystem3D regrows when the groom is edited in the inspector. StyleData does not emit: the node writes it
    // after every edit, and regrowing from it would undo nothing but loop.
    private int _sheets = 435;
    private int _strandsPerSheet = 40;
    private int _particlesPerStrand = 16;
    private float _strandLength = 0.25f;
    private Vector3 _headRadii = new Vector3(0.078f, 0.1f, 0.095f);
    private Vector3 _headCenter = new Vector3(0f, 0f, 0f);
    private float _rootJitter = 0.5f;
    private int _pinnedPerStrand = 2;
    private long _seed = 2009;
    [Export(PropertyHint.Range, "1,100000,1")] public int Sheets { get => _sheets; set { _sheets = value; EmitChanged(); } }
    [Export(PropertyHint.Range, "1,4096,1")] public int StrandsPerSheet { get => _strandsPerSheet; set { _strandsPerSheet = value; EmitChanged(); } }
    [Export(PropertyHint.Range, "3,4096,1")] public int ParticlesPerStrand { get => _particlesPerStrand; set { _particlesPerStrand = value; EmitChanged(); } }
    [Export(PropertyHint.Range, "0.001,10,0.001,suffix:m")] public float StrandLength { get => _strandLength; set { _strandLength = value; EmitChanged(); } }
    [Export] public Vector3 HeadRadii { get => _headRadii; set { _headRadii = value; EmitChanged(); } }
    [Export] public Vector3 HeadCenter { get => _headCenter; set { _headCenter = value; EmitChanged(); } }
    [Export(PropertyHint.Range, "0,1,0.01")] public float RootJitter { get => _rootJitter; set { _rootJitter = value; EmitChanged(); } }
    [Export(PropertyHint.Range, "1,8,1")] public int PinnedPerStrand { get => _pinnedPerStrand; set { _pinnedPerStrand = value; EmitChanged(); } }
    /// <summary>Groom seed (Godot exports 64-bit integers as long).</summary>
    [Export] public long Seed { get => _seed; set { _seed = value; EmitChanged(); } }
    /// <summary>The styled state; empty = the groom as grown.</summary>
    [Export] public byte[] StyleData { get; set; } = [];
    /// <summary>
    /// For a haircut of hair grown on a Scalp Mesh: the scalp, mask and groom values it was styled on (Logic/ScalpGrowth.StyleKey),
    /// written by the hair node; the groom numbers above are then not used. Empty: a groom grown on the Head Radii ellipsoid.
    /// </summary>
    [Export] public string ScalpStyleKey { get; set; } = "";

    public HairstyleRecord ToRecord() => new(Sheets, StrandsPerSheet, ParticlesPerStrand, StrandLength,
        HeadRadii.ToNumerics(), HeadCenter.ToNumerics(), RootJitter, PinnedPerStrand, unchecked((ulong)Seed), StyleData ?? [])
        { ScalpStyleKey = ScalpStyleKey ?? "" };

    public void SetFrom(HairstyleRecord r)
    {
        Sheets = r.Sheets; StrandsPerSheet = r.StrandsPerSheet; ParticlesPerStrand = r.ParticlesPerStrand;
        StrandLength = r.StrandLength; HeadRadii = r.HeadRadii.ToGodot(); HeadCenter = r.HeadCenter.ToGodot();
        RootJitter = r.RootJitter; PinnedPerStrand = r.PinnedPerStrand; Seed = unchecked((long)r.Seed);
        StyleData = r.StyleData;
        ScalpStyleKey = r.ScalpStyleKey;
        EmitChanged();
    }

    /// <summary>Grows the groom (validated: a corrupt resource throws InvalidDataException) and applies the style.</summary>
    public HairScene BuildScene(SimulationSettings settings)
    {
        var record = ToRecord();
        if (record.IsScalpStyle)
            throw new System.IO.InvalidDataException("This Hairstyle holds a haircut of hair grown on a Scalp Mesh: set the hair node's Scalp Mesh to the mesh it was styled on.");
        var scene = GroomBuilder.BuildScene(record.ToGroom(), settings);
        if (record.HasStyle) HairStyleIO.Load(scene, record.StyleData);
        return scene;
    }
}
