#if TOOLS
using System;
using System.Collections.Generic;
using Godot;
using HairSheet.Logic;

namespace HairSheet;

/// <summary>
/// Editor plugin: collider gizmos, and when a HairSystem3D is selected a 3D-toolbar with the Cut and Fit
/// stroke tools. Strokes are drawn over the 3D viewport (_Forward3DGuiInput + overlay drawing); every edit
/// is an EditorUndoRedoManager action, so Ctrl+Z / Ctrl+Shift+Z undo and redo it with the rest of the scene.
/// </summary>
[Tool]
public partial class HairSheetPlugin : EditorPlugin
{
    private readonly StrokeCapture _capture = new(minSpacing: 4f, minLength: 8f);
    private readonly CutTool _cut = new();
    private readonly FitTool _fit = new();
    private IHairStrokeTool? _tool;
    private HairSystem3D? _edited;
    private HBoxContainer? _toolbar;
    private Button? _cutButton, _fitButton;
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
        _cutButton.Toggled += OnCutToggled;
        _fitButton.Toggled += OnFitToggled;
        _hint = new Label();
        _toolbar.AddChild(_cutButton);
        _toolbar.AddChild(_fitButton);
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
        if (_toolbar != null)
        {
            RemoveControlFromContainer(CustomControlContainer.SpatialEditorMenu, _toolbar);
            _toolbar.QueueFree();
        }
        _toolbar = null; _cutButton = null; _fitButton = null; _hint = null;
        Follow(null);
        _tool = null;
    }

    public override bool _Handles(GodotObject @object) => @object is HairSystem3D;

    public override void _Edit(GodotObject? @object)
    {
        Follow(@object as HairSystem3D);
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
        if (_edited == null || _tool == null || !PointerInput.TryConvert(@event, out var sample))
            return (int)AfterGuiInput.Pass;
        var result = _capture.Handle(sample);
        if (result == StrokeEvent.Ignored) return (int)AfterGuiInput.Pass;
        if (result == StrokeEvent.Completed) Commit(viewportCamera);
        UpdateOverlays();
        return (int)AfterGuiInput.Stop;
    }

    public override void _Forward3DDrawOverViewport(Control viewportControl)
    {
        if (_tool == null) return;
        var color = new Color(1f, 0.85f, 0.2f);
        var area = _tool.PendingArea;
        if (area.Count > 2)
        {
            var closed = ToGodot(area, close: true);
            viewportControl.DrawPolyline(closed, color with { A = 0.6f }, 2f, true);
        }
        if (_capture.Points.Count > 1) viewportControl.DrawPolyline(ToGodot(_capture.Points, close: false), color, 3f, true);
    }

    private void Commit(Camera3D camera)
    {
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

    private void OnCutToggled(bool on) => SelectTool(on ? _cut : (_tool == _cut ? null : _tool));
    private void OnFitToggled(bool on) => SelectTool(on ? _fit : (_tool == _fit ? null : _tool));

    private void SelectTool(IHairStrokeTool? tool)
    {
        _tool = tool;
        _capture.Cancel();
        _fit.Reset();
        _cutButton?.SetPressedNoSignal(tool == _cut);
        _fitButton?.SetPressedNoSignal(tool == _fit);
        ShowHint();
        UpdateOverlays();
    }

    private void ShowHint()
    {
        if (_hint != null) _hint.Text = _tool?.Hint ?? "";
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
