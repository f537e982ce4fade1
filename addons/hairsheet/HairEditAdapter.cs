// The ONE place the addon touches HairSim's editing API (branch `edit`). Every other addon file uses only
// the wrapper types below (HairEdit, HairEditSession, HairStyleIO), so aligning names at merge means
// editing this file alone. Assumed API:
//   HairSim.Editing.StrokeCamera.Perspective(Matrix4x4 view, Matrix4x4 projection, Vector2 viewport)
//   new HairSim.Editing.Stroke(IReadOnlyList<Vector2> points, StrokeCamera camera)
//   HairSim.Editing.HairEditor.Cut(HairScene, Stroke, CutOptions) -> IEditCommand
//   HairSim.Editing.Selection.FromScreenArea(HairScene, IReadOnlyList<Vector2> area, StrokeCamera)
//   HairSim.Editing.HairEditor.Fit(HairScene, Selection, Stroke, FitOptions) -> IEditCommand
//   new HairSim.Editing.EditHistory(HairScene); EditHistory.Do(IEditCommand) / Undo() / Redo() -> bool
//   HairSim.Editing.HairstyleFile.Write(HairScene, Stream) / Read(Stream, HairScene)
using System.Collections.Generic;
using System.IO;
using System.Numerics;
using HairSheet.Logic;
using HairSim;
using HairSim.Editing;

namespace HairSheet;

/// <summary>An edit computed from a stroke, not yet applied: applying goes through a <see cref="HairEditSession"/>.</summary>
public sealed class HairEdit
{
    internal HairEdit(string name, IEditCommand command) { Name = name; Command = command; }
    public string Name { get; }
    internal IEditCommand Command { get; }
}

/// <summary>Builds edits from strokes with the library's stroke and camera code (nothing is re-implemented here).</summary>
public static class HairEditAdapter
{
    public static HairEdit Cut(HairScene scene, IReadOnlyList<Vector2> stroke, in CameraMatrices camera)
    {
        var cam = StrokeCamera.Perspective(camera.View, camera.Projection, camera.Viewport);
        return new HairEdit("Cut hair", HairEditor.Cut(scene, new Stroke(stroke, cam), new CutOptions()));
    }

    public static HairEdit Fit(HairScene scene, IReadOnlyList<Vector2> area, IReadOnlyList<Vector2> stroke, in CameraMatrices camera)
    {
        var cam = StrokeCamera.Perspective(camera.View, camera.Projection, camera.Viewport);
        var selection = Selection.FromScreenArea(scene, area, cam);
        return new HairEdit("Fit hair", HairEditor.Fit(scene, selection, new Stroke(stroke, cam), new FitOptions()));
    }
}

/// <summary>The undo history of one hair node's scene.</summary>
public sealed class HairEditSession
{
    private readonly EditHistory _history;

    public HairEditSession(HairScene scene) => _history = new EditHistory(scene);

    public void Do(HairEdit edit) => _history.Do(edit.Command);
    public bool Undo() => _history.Undo();
    public bool Redo() => _history.Redo();
}

/// <summary>The styled state (cuts, fitted rest shapes) as bytes in HairSim's versioned hairstyle format.</summary>
public static class HairStyleIO
{
    public static byte[] Save(HairScene scene)
    {
        using var stream = new MemoryStream();
        HairstyleFile.Write(scene, stream);
        return stream.ToArray();
    }

    /// <summary>Applies saved style bytes; a corrupt blob throws (InvalidDataException) and leaves the scene unchanged.</summary>
    public static void Load(HairScene scene, byte[] data)
    {
        using var stream = new MemoryStream(data, writable: false);
        HairstyleFile.Read(stream, scene);
    }
}
