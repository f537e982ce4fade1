#if TOOLS
using System;
using System.Collections.Generic;
using Godot;
using HairSheet.Logic;

namespace HairSheet;

/// <summary>
/// Editor plugin: collider gizmos, and when a HairSystem3D is selected a 3D-toolbar with the Cut and Fit
/// stroke tools and the Paint scalp / Erase scalp brushes (hair grown on a Scalp Mesh grows where it is painted).
/// Strokes are drawn over the 3D viewport (_Forward3DGuiInput + overlay drawing); every edit and every paint stroke
/// is an EditorUndoRedoManager action, so Ctrl+Z / Ctrl+Shift+Z undo and redo it with the rest of the scene.
/// </summary>
[Tool]
public partial class HairSheetPlugin : EditorPlugin
{
    private readonly StrokeCapture _capture = new(minSpacing: 4f, minLength: 8f);
    private readonly CutTool _cut = new();
    private readonly FitTool _fit = new();
    private IHairStrokeTool? _tool;
    // A scalp brush instead of a hair tool: Add paints, Remove erases (null: no brush).
    private HairSim.Meshes.ScalpPaintMode? _brush;
    private HairSystem3D? _edited;
    private HBoxContainer? _toolbar;
    private Button? _cutButton, _fitButton, _paintButton, _eraseButton;
    private SpinBox? _brushSize;
    private Label? _hint;
    private HairColliderGizmoPlugin? _gizmos;

    public override void _EnterTree()
    {
        _gizmos = new HairColliderGizmoPlugin();
        AddNode3DGizmoPlugin(_gizmos);

        _toolbar = new HBoxContainer();
        _toolbar.AddChild(new VSeparator());
        _cutButton = new Button { Text = "Cut", ToggleMode = true, TooltipText = "Draw a line across strands to cut them (Esc cancels)." };
        _fitButton = new Button { Text = "Fit", ToggleMode = true, TooltipText = "Loop around strands, then draw the shape they should follow." };
        _paintButton = new Button { Text = "Paint scalp", ToggleMode = true, TooltipText = "Brush where hair grows on the Scalp Mesh (front faces under the brush that the head does not hide)." };
        _eraseButton = new Button { Text = "Erase scalp", ToggleMode = true, TooltipText = "Brush away where hair grows on the Scalp Mesh." };
        _brushSize = new SpinBox { MinValue = 2, MaxValue = 200, Step = 1, Value = 24, Suffix = "px", TooltipText = "Scalp brush radius in screen pixels." };
        _cutButton.Toggled += OnCutToggled;
        _fitButton.Toggled += OnFitToggled;
        _paintButton.Toggled += OnPaintToggled;
        _eraseButton.Toggled += OnEraseToggled;
        _hint = new Label();
        _toolbar.AddChild(_cutButton);
        _toolbar.AddChild(_fitButton);
        _toolbar.AddChild(new VSeparator());
        _toolbar.AddChild(_paintButton);
        _toolbar.AddChild(_eraseButton);
        _toolbar.AddChild(_brushSize);
        _toolbar.AddChild(_hint);
        _toolbar.Hide();
        AddControlToContainer(CustomControlContainer.SpatialEditorMenu, _toolbar);
    }

    public override void _ExitTree()
    {
        // Disconnect and free everything: the editor unloads this assembly on rebuild (godot #78513).
        if (_gizmos != null) RemoveNode3DGizmoPlugin(_gizmos);
        _gizmos = null;
        if (_cutButton != null) _cutButton.Toggled -= OnCutToggled;
        if (_fitButton != null) _fitButton.Toggled -= OnFitToggled;
        if (_paintButton != null) _paintButton.Toggled -= OnPaintToggled;
        if (_eraseButton != null) _eraseButton.Toggled -= OnEraseToggled;
        if (_toolbar != null)
        {
            RemoveControlFromContainer(CustomControlContainer.SpatialEditorMenu, _toolbar);
            _toolbar.QueueFree();
        }
        _toolbar = null; _cutButton = null; _fitButton = null; _paintButton = null; _eraseButton = null; _brushSize = null; _hint = null;
        if (_brush != null && _edited != null && IsInstanceValid(_edited)) _edited.ShowScalpMask(false);
        _brush = null;
        Follow(null);
        _tool = null;
    }

    public override bool _Handles(GodotObject @object) => @object is HairSystem3D;

    public override void _Edit(GodotObject? @object)
    {
        if (_brush != null && _edited != null && IsInstanceValid(_edited)) _edited.ShowScalpMask(false);
        Follow(@object as HairSystem3D);
        if (_brush != null) _edited?.ShowScalpMask(true);
        _capture.Cancel();
        _fit.Reset();
    }

    /// <summary>Edits the given hair node, showing in the toolbar why an undo or redo of one of its edits did nothing.</summary>
    private void Follow(HairSystem3D? hair)
    {
        if (_edited != null && IsInstanceValid(_edited)) _edited.EditSkipped -= OnEditSkipped;
        _edited = hair;
        if (_edited != null) _edited.EditSkipped += OnEditSkipped;
    }

    private void OnEditSkipped(string message)
    {
        if (_hint != null) _hint.Text = message;
    }

    public override void _MakeVisible(bool visible)
    {
        if (_toolbar != null) _toolbar.Visible = visible;
        if (!visible) SelectTool(null);
    }

    public override int _Forward3DGuiInput(Camera3D viewportCamera, InputEvent @event)
    {
        if (_edited == null || (_tool == null && _brush == null) || !PointerInput.TryConvert(@event, out var sample))
            return (int)AfterGuiInput.Pass;
        var result = _capture.Handle(sample);
        if (result == StrokeEvent.Ignored) return (int)AfterGuiInput.Pass;
        if (result == StrokeEvent.Completed) Commit(viewportCamera);
        UpdateOverlays();
        return (int)AfterGuiInput.Stop;
    }

    public override void _Forward3DDrawOverViewport(Control viewportControl)
    {
        if (_tool == null && _brush == null) return;
        var color = _brush == null ? new Color(1f, 0.85f, 0.2f) : new Color(1f, 0.3f, 0.2f);
        var area = _tool?.PendingArea ?? [];
        if (area.Count > 2)
        {
            var closed = ToGodot(area, close: true);
            viewportControl.DrawPolyline(closed, color with { A = 0.6f }, 2f, true);
        }
        if (_capture.Points.Count > 1) viewportControl.DrawPolyline(ToGodot(_capture.Points, close: false), color, 3f, true);
    }

    private void Commit(Camera3D camera)
    {
        if (_brush is { } brush) { CommitPaint(camera, brush); return; }
        if (_edited == null || _tool == null) return;
        // Read first: it applies a pending regrow, so the edit is computed on the hair this generation names.
        int generation = _edited.Generation;
        if (_edited.Scene == null) return;
        try
        {
            var cam = GodotConvert.StrokeCamera(camera, camera.GetViewport().GetVisibleRect().Size);
            var edit = _tool.Complete(_edited.Scene, _capture.Completed, cam);
            if (edit == null) { ShowHint(); return; }
            // The do-method applies the staged edit on commit and redoes it later; the undo-method reverts it. Both
            // name the hair generation: after a regrow an entry acts only once its hair is back (Logic/HairGenerations).
            _edited.StageEdit(edit);
            var undo = GetUndoRedo();
            undo.CreateAction(edit.Name, UndoRedo.MergeMode.Disable, _edited);
            undo.AddDoMethod(_edited, nameof(HairSystem3D.RedoEditIn), generation, edit.Name);
            undo.AddUndoMethod(_edited, nameof(HairSystem3D.UndoEditIn), generation, edit.Name);
            undo.CommitAction();
            ShowHint();
        }
        catch (ArgumentException e)
        {
            _tool.Reset();
            if (_hint != null) _hint.Text = e.Message;
        }
    }

    /// <summary>
    /// One scalp brush stroke as an undo action: the node computes the mask before and after (nothing changes yet), the
    /// do-method sets the after, the undo-method the before (none: the vertex colours decide again). Setting the mask
    /// regrows the hair; undoing brings the earlier hair back from the node's kept generations.
    /// </summary>
    private void CommitPaint(Camera3D camera, HairSim.Meshes.ScalpPaintMode brush)
    {
        if (_edited == null) return;
        var cam = GodotConvert.StrokeCamera(camera, camera.GetViewport().GetVisibleRect().Size);
        float radius = (float)(_brushSize?.Value ?? 24.0);
        var stroke = _edited.PaintScalp(_capture.Completed, cam, radius, brush == HairSim.Meshes.ScalpPaintMode.Remove, out string? why);
        if (stroke == null) { if (_hint != null) _hint.Text = why ?? ""; return; }
        var undo = GetUndoRedo();
        undo.CreateAction(brush == HairSim.Meshes.ScalpPaintMode.Add ? "Paint scalp" : "Erase scalp", UndoRedo.MergeMode.Disable, _edited);
        undo.AddDoMethod(_edited, nameof(HairSystem3D.SetScalpMask), stroke.After, stroke.TriangleCount, stroke.ScalpKey);
        undo.AddUndoMethod(_edited, nameof(HairSystem3D.SetScalpMask), stroke.Before ?? [], stroke.TriangleCount, stroke.ScalpKey);
        undo.CommitAction();
        if (_hint != null) _hint.Text = $"{HintForBrush()} {ScalpMaskText(stroke.After, stroke.TriangleCount)}";
    }

    private static string ScalpMaskText(byte[] mask, int triangles) =>
        $"Scalp: {ScalpMask.Count(mask)} of {triangles} triangles.";

    private void OnCutToggled(bool on) => SelectTool(on ? _cut : (_tool == _cut ? null : _tool), null);
    private void OnFitToggled(bool on) => SelectTool(on ? _fit : (_tool == _fit ? null : _tool), null);
    private void OnPaintToggled(bool on) => SelectTool(null, on ? HairSim.Meshes.ScalpPaintMode.Add : null);
    private void OnEraseToggled(bool on) => SelectTool(null, on ? HairSim.Meshes.ScalpPaintMode.Remove : null);

    private void SelectTool(IHairStrokeTool? tool, HairSim.Meshes.ScalpPaintMode? brush = null)
    {
        bool wasBrush = _brush != null;
        _tool = tool;
        _brush = brush;
        _capture.Cancel();
        _fit.Reset();
        _cutButton?.SetPressedNoSignal(tool == _cut);
        _fitButton?.SetPressedNoSignal(tool == _fit);
        _paintButton?.SetPressedNoSignal(brush == HairSim.Meshes.ScalpPaintMode.Add);
        _eraseButton?.SetPressedNoSignal(brush == HairSim.Meshes.ScalpPaintMode.Remove);
        // The painted scalp is drawn over the head while a brush is active.
        if (_edited != null && IsInstanceValid(_edited) && wasBrush != (brush != null)) _edited.ShowScalpMask(brush != null);
        ShowHint();
        UpdateOverlays();
    }

    private string HintForBrush() => _brush == HairSim.Meshes.ScalpPaintMode.Add
        ? "Paint scalp: brush over the Scalp Mesh where hair should grow."
        : "Erase scalp: brush over the Scalp Mesh where no hair should grow.";

    private void ShowHint()
    {
        if (_hint != null) _hint.Text = _brush != null ? HintForBrush() : _tool?.Hint ?? "";
    }

    private static Vector2[] ToGodot(IReadOnlyList<System.Numerics.Vector2> pts, bool close)
    {
        var a = new Vector2[pts.Count + (close ? 1 : 0)];
        for (int i = 0; i < pts.Count; i++) a[i] = pts[i].ToGodot();
        if (close) a[^1] = a[0];
        return a;
    }
}
#endif
