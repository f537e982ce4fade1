using System.Numerics;
using HairSheet.Logic;
using HairSim;
using HairSim.Editing;

namespace HairSheet.Addon.Tests;

/// <summary>
/// The editor's undo entries for hair edits name the hair generation they were made on (HairSystem3D.RedoEditIn /
/// UndoEditIn); these tests play the editor's undo sequences against HairGenerations with real scenes and histories.
/// </summary>
public class HairGenerationsTests
{
    private sealed record Hair(HairScene Scene, EditHistory History);

    private static GroomSettings SmallGroom(float strandLength = 0.25f, ulong seed = 2009) =>
        new() { SheetCount = 12, StrandsPerSheet = 4, ParticlesPerStrand = 8, StrandLength = strandLength, Seed = seed };

    private static Hair Grow(GroomSettings groom)
    {
        var scene = GroomBuilder.BuildScene(groom);
        var history = new EditHistory();
        scene.SetComponent(history);
        return new Hair(scene, history);
    }

    /// <summary>Cuts every strand to half its particles (a plain edit the history can undo).</summary>
    private static void CutAll(Hair hair)
    {
        var camera = StrokeCamera.LookAtPerspective(new Vector3(0, 0, 0.8f), Vector3.Zero, Vector3.UnitY, 0.8f, new Vector2(800, 800));
        var cut = HairEditor.Cut(hair.Scene, new Stroke([new(0, 420), new(799, 420)], camera), new CutOptions { Reach = CutReach.AllThrough });
        Assert.True(hair.History.Do(cut), "the stroke cut nothing: move it");
    }

    private static int LiveParticles(Hair hair)
    {
        int n = 0;
        foreach (int count in hair.Scene.World.StrandParticleCount) n += count;
        return n;
    }

    [Fact]
    public void UndoingTheValueChangeBringsBackTheHairItsEntriesWereMadeOn()
    {
        var gens = new HairGenerations<Hair>(maxKept: 2);
        var a = Grow(SmallGroom());
        int g1 = gens.Adopt("A", a, keepLive: false);
        int full = LiveParticles(a);
        CutAll(a);                                       // entry "Cut" in g1
        int cut = LiveParticles(a);
        Assert.True(cut < full);

        // A value change regrows: new hair, new generation; the cut entry is not live any more and says so.
        var b = Grow(SmallGroom(strandLength: 0.3f));
        int g2 = gens.Adopt("B", b, keepLive: a.History.CanUndo);
        Assert.NotEqual(g1, g2);
        Assert.False(gens.IsLive(g1));
        Assert.Contains("Undo or redo that value change first", gens.Explain(g1, "Cut hair", undo: true));

        // Undoing the value change puts inputs "A" back: the kept hair returns, still cut, and its entry undoes the cut.
        Assert.True(gens.TryRestore("A", keepLive: b.History.CanUndo || b.History.CanRedo, out var back));
        Assert.Same(a, back);
        Assert.True(gens.IsLive(g1));
        Assert.Null(gens.Explain(g1, "Cut hair", undo: true));
        Assert.Equal(cut, LiveParticles(back!));
        Assert.True(back!.History.Undo());
        Assert.Equal(full, LiveParticles(back));
        Assert.True(back.History.Redo());
        Assert.Equal(cut, LiveParticles(back));
    }

    [Fact]
    public void RedoingTheValueChangeBringsBackTheLaterHairAndItsRedo()
    {
        var gens = new HairGenerations<Hair>(maxKept: 2);
        var a = Grow(SmallGroom());
        gens.Adopt("A", a, keepLive: false);
        CutAll(a);
        var b = Grow(SmallGroom(seed: 7));
        int g2 = gens.Adopt("B", b, keepLive: true);
        CutAll(b);
        int bCut = LiveParticles(b);
        Assert.True(b.History.Undo());                   // undo "Cut" in g2, then undo the value change
        Assert.True(gens.TryRestore("A", keepLive: b.History.CanRedo, out _));
        Assert.False(gens.IsLive(g2));
        // Redo the value change, then redo the cut: g2 is back with its redo step.
        Assert.True(gens.TryRestore("B", keepLive: a.History.CanUndo, out var again));
        Assert.True(gens.IsLive(g2));
        Assert.True(again!.History.Redo());
        Assert.Equal(bCut, LiveParticles(again));
    }

    [Fact]
    public void HairWithoutEditsIsNotKeptAndTheBoundForgetsTheOldest()
    {
        var gens = new HairGenerations<string>(maxKept: 2);
        gens.Adopt("A", "hair A", keepLive: true);       // g1, edited
        gens.Adopt("B", "hair B", keepLive: true);       // g2, not edited: keepLive false when leaving it
        gens.Adopt("C", "hair C", keepLive: false);
        Assert.Equal([1], gens.KeptGenerations);
        Assert.False(gens.TryRestore("B", keepLive: false, out _)); // the caller grows "B" anew
        gens.Adopt("D", "hair D", keepLive: true);       // keeps g3
        gens.Adopt("E", "hair E", keepLive: true);       // keeps g4, forgets g1 (the bound is 2)
        Assert.Equal([3, 4], gens.KeptGenerations);
        string? why = gens.Explain(1, "Fit hair", undo: false);
        Assert.NotNull(why);
        Assert.Contains("no longer kept", why);
        Assert.Contains("\"Fit hair\"", why);
        Assert.StartsWith("Redo", why);
        Assert.False(gens.TryRestore("A", keepLive: true, out _));
        Assert.Contains("never grew", gens.Explain(99, "Cut hair", undo: true));
    }

    [Fact]
    public void RegrowingFromTheSameInputsReplacesTheKeptHair()
    {
        // A reset regrows the live inputs: the hair it replaces is not kept under the same key.
        var gens = new HairGenerations<string>(maxKept: 2);
        gens.Adopt("A", "styled A", keepLive: true);
        gens.Adopt("A", "fresh A", keepLive: true);
        Assert.Empty(gens.KeptGenerations);
        Assert.Equal("fresh A", gens.Live);
        Assert.Equal(2, gens.Current);
    }

    [Fact]
    public void TheKeyChangesWithEveryValueThatRegrowsAndNotWithColours()
    {
        var baseKey = GrowthKey.Of(new HairNodeSettings());
        Assert.Equal(baseKey, GrowthKey.Of(new HairNodeSettings()));
        var changes = new (string Name, Action<HairNodeSettings> Change)[]
        {
            ("Sheets", s => s.Sheets++), ("StrandsPerSheet", s => s.StrandsPerSheet++), ("ParticlesPerStrand", s => s.ParticlesPerStrand++),
            ("StrandLength", s => s.StrandLength = MathF.BitIncrement(s.StrandLength)), ("Bend", s => s.Bend = BendModel.Limp),
            ("Sag", s => s.Sag *= 2), ("BendDamping", s => s.BendDamping += 0.1f), ("Stiffness", s => s.Stiffness = 0.5f),
            ("Damping", s => s.Damping = 0), ("Substeps", s => s.Substeps++), ("StaticFriction", s => s.StaticFriction = 0.5f),
            ("KineticFriction", s => s.KineticFriction = 0.4f), ("Gravity", s => s.Gravity = new Vector3(0, -9.80f, 0)),
            ("RenderDensity", s => s.RenderDensity = 0), ("RootWidth", s => s.RootWidth *= 2), ("TipWidth", s => s.TipWidth = 0),
            ("StepsPerSecond", s => s.StepsPerSecond = 120), ("HeadRadii", s => s.HeadRadii *= 1.1f), ("Seed", s => s.Seed++),
            ("HairVolume", s => s.HairVolume = true), ("VolumeStiffness", s => s.VolumeStiffness = 9f), ("VolumeFriction", s => s.VolumeFriction = 4f),
            ("VolumeDensity", s => s.VolumeDensity = 0.5f),
            ("VolumeMaxStep", s => s.VolumeMaxStep = 0.03f), ("StrandContacts", s => s.StrandContacts = true),
            ("ContactThickness", s => s.ContactThickness = 0.5f), ("ContactFriction", s => s.ContactFriction = 0.6f),
        };
        foreach (var (name, change) in changes)
        {
            var s = new HairNodeSettings();
            change(s);
            Assert.True(GrowthKey.Of(s) != baseKey, $"changing {name} leaves the growth key as it was");
        }
        var colours = new HairNodeSettings { RootColor = Vector4.One, TipColor = Vector4.Zero };
        Assert.Equal(baseKey, GrowthKey.Of(colours));
    }

    [Fact]
    public void TheKeyFollowsTheHairstyleGroomAndIdentityButNotItsStyleData()
    {
        var settings = new HairNodeSettings();
        var record = HairstyleRecord.FromGroom(SmallGroom());
        string key = GrowthKey.Of(settings, record, styleId: 5);
        Assert.NotEqual(GrowthKey.Of(settings), key);
        Assert.Equal(key, GrowthKey.Of(settings, record with { StyleData = [1, 2, 3] }, styleId: 5));
        Assert.NotEqual(key, GrowthKey.Of(settings, record, styleId: 6));
        Assert.NotEqual(key, GrowthKey.Of(settings, record with { Sheets = record.Sheets + 1 }, styleId: 5));
        Assert.NotEqual(key, GrowthKey.Of(settings, record with { HeadCenter = new Vector3(0, 0.01f, 0) }, styleId: 5));
    }
}
