using System.Numerics;
using HairSheet.Logic;
using HairSim;

namespace HairSheet.Addon.Tests;

public class SettingsTests
{
    [Fact]
    public void Inspector_defaults_are_the_reference_scene()
    {
        var s = new HairNodeSettings();
        Assert.Empty(s.Validate());
        var g = s.ToGroom();
        var r = GroomSettings.Reference();
        Assert.Equal((r.SheetCount, r.StrandsPerSheet, r.ParticlesPerStrand, r.StrandLength), (g.SheetCount, g.StrandsPerSheet, g.ParticlesPerStrand, g.StrandLength));
        var sim = s.ToSimulation();
        Assert.Equal(s.Stiffness, sim.Alpha);
        // The inspector's defaults are the library's: the same look from Godot as from the library.
        var lib = new SimulationSettings();
        Assert.Equal((lib.Bend, lib.Sag, lib.BendDamping, lib.Damping), (sim.Bend, sim.Sag, sim.BendDamping, sim.Damping));
        Assert.Equal(s.Substeps, sim.Substeps);
        Assert.Equal(s.Gravity, sim.Gravity);
        Assert.Equal(s.RenderDensity, s.ToRender().StrandsPerGap);
    }

    [Fact]
    public void Every_bad_value_is_reported_by_its_inspector_name()
    {
        var s = new HairNodeSettings
        {
            StrandsPerSheet = 0, StrandLength = float.NaN, Stiffness = 1.5f, Substeps = 0, Sag = -1f,
            Gravity = new Vector3(0, float.PositiveInfinity, 0), RenderDensity = -1, TipColor = new Vector4(1, 1, 1, 2),
            RootWidth = 0.001f, TipWidth = 0.002f, StepsPerSecond = 0,
        };
        var problems = s.Validate();
        foreach (var name in new[] { "Strands Per Sheet", "Strand Length", "Stiffness", "Sag", "Substeps", "Gravity", "Render Density", "Tip Color", "Tip Width", "Steps Per Second" })
            Assert.Contains(problems, p => p.StartsWith(name, StringComparison.Ordinal));
        var e = Assert.Throws<HairSettingsException>(() => s.ToSimulation());
        Assert.Equal(problems.Count, e.Problems.Count);
        Assert.Contains("Stiffness", e.Message);
        Assert.Throws<HairSettingsException>(() => s.ToGroom());
        Assert.Throws<HairSettingsException>(() => s.ToRender());
    }

    [Fact]
    public void Hair_volume_is_off_by_default_and_carries_the_library_s_defaults_when_on()
    {
        var s = new HairNodeSettings();
        Assert.Null(s.ToVolume());
        s.HairVolume = true;
        var v = s.ToVolume()!;
        var lib = new VolumeSettings();
        Assert.Equal((lib.Stiffness, lib.Friction, lib.Density, lib.MaxStep), (v.Stiffness, v.Friction, v.Density, v.MaxStep));
        s.VolumeDensity = 0.5f;
        Assert.Equal(0.5f, s.ToVolume()!.Density);
        s.VolumeFriction = float.NaN; s.VolumeMaxStep = 0f; s.VolumeStiffness = -1f; s.VolumeDensity = 0f;
        var problems = s.Validate();
        foreach (var name in new[] { "Volume Stiffness", "Volume Friction", "Volume Max Step", "Volume Density" })
            Assert.Contains(problems, p => p.StartsWith(name, StringComparison.Ordinal));
        Assert.Throws<HairSettingsException>(() => s.ToVolume());
    }

    [Fact]
    public void Strand_contacts_are_off_by_default_and_carry_the_library_s_defaults_when_on()
    {
        var s = new HairNodeSettings();
        Assert.Null(s.ToContacts());
        s.StrandContacts = true;
        var c = s.ToContacts()!;
        var lib = new StrandContactSettings();
        Assert.Equal((lib.Thickness, lib.Friction), (c.Thickness, c.Friction));
        s.ContactThickness = 0f; s.ContactFriction = float.NaN;
        var problems = s.Validate();
        foreach (var name in new[] { "Contact Thickness", "Contact Friction" })
            Assert.Contains(problems, p => p.StartsWith(name, StringComparison.Ordinal));
        Assert.Throws<HairSettingsException>(() => s.ToContacts());
    }

    [Fact]
    public void Too_many_particles_is_refused_before_anything_is_allocated()
    {
        var s = new HairNodeSettings { Sheets = 100_000, StrandsPerSheet = 4096, ParticlesPerStrand = 16 };
        Assert.Contains(s.Validate(), p => p.Contains("particles", StringComparison.Ordinal));
    }

    [Fact]
    public void Hairstyle_record_reopens_the_identical_groom()
    {
        var g = GroomSettings.Reference();
        g.SheetCount = 12; g.StrandsPerSheet = 5; g.ParticlesPerStrand = 9; g.Seed = 77; g.StrandLength = 0.31f;
        var record = HairstyleRecord.FromGroom(g, [1, 2, 3]);
        Assert.True(record.HasStyle);
        var a = GroomBuilder.Build(g);
        var b = GroomBuilder.Build(record.ToGroom());
        Assert.True(a.BitEquals(b));
    }

    [Fact]
    public void A_corrupt_hairstyle_record_gives_a_clear_error()
    {
        var record = HairstyleRecord.FromGroom(GroomSettings.Reference()) with { ParticlesPerStrand = 1 };
        var e = Assert.Throws<InvalidDataException>(() => record.ToGroom());
        Assert.Contains("Particles per strand", e.Message);
    }
}
