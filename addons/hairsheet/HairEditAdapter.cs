// The ONE place the addon edits hair through HairSim's editing API (HairSim.Editing, HairSim.IO). Every other addon file
// uses only the wrapper types below (HairEdit, HairEditSession, HairStyleIO); scalp painting, which edits the scalp
// mask rather than the hair, is engine-free in Logic/ScalpMask (with the stroke camera both share, Logic/StrokeCameras).
using System.Collections.Generic;
using System.IO;
using System.Numerics;
using HairSheet.Logic;
using HairSim;
using HairSim.Editing;
using HairSim.IO;

namespace HairSheet;

/// <summary>An edit computed from a stroke, not yet applied: applying goes through a <see cref="HairEditSession"/>.</summary>
public sealed class HairEdit
{
    internal HairEdit(string name, EditCommand command) { Name = name; Command = command; }
    public string Name { get; }
    internal EditCommand Command { get; }
}

/// <summary>Builds edits from strokes with the library's stroke and camera code (nothing is re-implemented here).</summary>
public static class HairEditAdapter
{
    public static HairEdit Cut(HairScene scene, IReadOnlyList<Vector2> stroke, in CameraMatrices camera)
    {
        var cam = ToStrokeCamera(camera);
        return new HairEdit("Cut hair", HairEditor.Cut(scene, new Stroke(stroke, cam), new CutOptions()));
    }

    public static HairEdit Fit(HairScene scene, IReadOnlyList<Vector2> area, IReadOnlyList<Vector2> stroke, in CameraMatrices camera)
    {
        var cam = ToStrokeCamera(camera);
        var lasso = new Vector2[area.Count];
        for (int i = 0; i < lasso.Length; i++) lasso[i] = area[i];
        var selection = HairEditor.Select(scene, cam, SelectionArea.Lasso(lasso), new SelectionOptions { RootsOnly = true });
        return new HairEdit("Fit hair", HairEditor.Fit(scene, selection, new Stroke(stroke, cam), new FitOptions()));
    }

    private static StrokeCamera ToStrokeCamera(in CameraMatrices camera) => StrokeCameras.From(camera);
}

/// <summary>The undo history of one hair node's scene.</summary>
public sealed class HairEditSession
{
    private readonly EditHistory _history;
    private readonly HairWorld _world;

    public HairEditSession(HairScene scene)
    {
        _world = scene.World;
        _history = new EditHistory();
        scene.SetComponent(_history);
    }

    public void Do(HairEdit edit) => _history.Do(edit.Command);
    public bool Undo() => _history.Undo();
    public bool Redo() => _history.Redo();
    /// <summary>Whether anything can be undone or redone: hair with no entries is not worth keeping after a regrow.</summary>
    public bool HasEntries => _history.CanUndo || _history.CanRedo;
    /// <summary>Whether the edit was computed on this session's hair (an edit applies only to the world it was made on).</summary>
    public bool Owns(HairEdit edit) => edit.Command.World == _world;
}

/// <summary>The styled state (cuts, fitted rest shapes) as bytes in HairSim's versioned hairstyle format.</summary>
public static class HairStyleIO
{
    public static byte[] Save(HairScene scene)
    {
        using var stream = new MemoryStream();
        HairstyleFile.Save(scene, stream);
        return stream.ToArray();
    }

    /// <summary>Applies saved style bytes; a corrupt blob throws (InvalidDataException) and leaves the scene unchanged.</summary>
    public static void Load(HairScene scene, byte[] data)
    {
        HairstyleFile.LoadInto(scene, data);
    }
}
