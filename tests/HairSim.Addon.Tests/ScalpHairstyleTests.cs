using System.Numerics;
using HairSheet.Logic;
using HairSim;
using HairSim.IO;
using HairSim.Meshes;

namespace HairSheet.Addon.Tests;

/// <summary>
/// A haircut of hair grown on a Scalp Mesh kept in a Hairstyle resource, as HairSystem3D does it: the key of what it
/// was styled on (<see cref="ScalpGrowth.StyleKey"/>), and the style applied again to hair grown anew from the same
/// inputs, which must be the same strands.
/// </summary>
public class ScalpHairstyleTests
{
    private static readonly TriangleMesh Head = ScalpGrowth.HeadSpaceMesh([ScalpGrowthTests.AsGodotSurface(ProceduralHead.CreateLowPoly())], Matrix4x4.Identity);

    private static HairNodeSettings Groom() => new() { Sheets = 30, StrandsPerSheet = 6, ParticlesPerStrand = 8, StrandLength = 0.15f, ScalpCellSize = 0.0025f };

    [Fact]
    public void The_style_key_follows_what_decides_the_strands_and_nothing_else()
    {
        var mask = ScalpMask.Pack(ScalpPaint.FromVertexColours(Head, 0.5f).Triangles);
        string key = ScalpGrowth.StyleKey(Groom(), "scalp-a", mask);
        Assert.Equal(key, ScalpGrowth.StyleKey(Groom(), "scalp-a", (byte[])mask.Clone()));
        // Simulation values do not change which strands grow where: a haircut survives them.
        var sim = Groom(); sim.Substeps = 9; sim.Damping = 2f;
        Assert.Equal(key, ScalpGrowth.StyleKey(sim, "scalp-a", mask));
        // Everything that does is in it.
        var changed = new List<HairNodeSettings>();
        foreach (Action<HairNodeSettings> change in new Action<HairNodeSettings>[]
                 {
                     g => g.Seed = 7, g => g.Sheets = 31, g => g.StrandsPerSheet = 7, g => g.ParticlesPerStrand = 9,
                     g => g.StrandLength = 0.16f, g => g.ScalpMaskThreshold = 0.4f, g => g.ScalpRootLift = 0.003f,
                     g => g.ScalpDrape = 0.5f, g => g.ScalpCellSize = 0.003f,
                 })
        {
            var g = Groom(); change(g);
            Assert.NotEqual(key, ScalpGrowth.StyleKey(g, "scalp-a", mask));
        }
        Assert.NotEqual(key, ScalpGrowth.StyleKey(Groom(), "scalp-b", mask));
        Assert.NotEqual(key, ScalpGrowth.StyleKey(Groom(), "scalp-a", null));
        var other = (byte[])mask.Clone(); other[0] ^= 1;
        Assert.NotEqual(key, ScalpGrowth.StyleKey(Groom(), "scalp-a", other));
    }

    [Fact]
    public void A_haircut_saved_from_scalp_grown_hair_applies_again_to_the_same_hair_grown_anew()
    {
        var settings = Groom();
        var field = ScalpGrowth.BakeField(Head, settings);
        var styled = ScalpGrowth.Grow(Head, field, settings);
        var w = styled.World;
        // A haircut: every third strand cut to 4 of its 8 particles.
        for (int s = 0; s < w.StrandCount; s += 3) w.StrandParticleCount[s] = 4;
        w.MarkEdited();
        using var stream = new MemoryStream();
        HairstyleFile.Save(styled, stream);
        var record = HairstyleRecord.FromGroom(settings.ToGroom(), stream.ToArray()) with { ScalpStyleKey = ScalpGrowth.StyleKey(settings, "scalp", null) };
        Assert.True(record.IsScalpStyle && record.HasStyle);

        // The node grows the hair again (a reopened scene) and applies the style it finds under the same key.
        var regrown = ScalpGrowth.Grow(Head, ScalpGrowth.BakeField(Head, settings), settings);
        Assert.Equal(record.ScalpStyleKey, ScalpGrowth.StyleKey(settings, "scalp", null));
        HairstyleFile.LoadInto(regrown, record.StyleData);
        var r = regrown.World;
        Assert.Equal(w.StrandCount, r.StrandCount);
        for (int s = 0; s < w.StrandCount; s++)
        {
            Assert.Equal(w.StrandParticleCount[s], r.StrandParticleCount[s]);
            for (int k = 0; k < w.StrandParticleCount[s]; k++)
            {
                int i = w.StrandFirst[s] + k;
                Assert.Equal(w.GetPosition(i), r.GetPosition(i));
                Assert.Equal(w.RestLength[i], r.RestLength[i]);
            }
        }
        // An ellipsoid groom's record is not a scalp haircut.
        Assert.False(HairstyleRecord.FromGroom(settings.ToGroom()).IsScalpStyle);
    }
}
