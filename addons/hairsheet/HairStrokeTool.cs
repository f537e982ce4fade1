using System;
using System.Collections.Generic;
using Godot;
using HairSheet.Logic;

namespace HairSheet;

public enum HairToolKind { None, Cut, Fit }

/// <summary>
/// Run-time stroke tool: mouse and touch input in the running game → the same strokes and edits as the
/// editor tools, applied to a HairSystem3D (undo with <see cref="Undo"/>). For players, and for AR users who
/// cut and shape hair with a finger. Unhandled input only, so UI buttons keep working. Draws the stroke with
/// a Line2D overlay.
/// </summary>
[GlobalClass]
public partial class HairStrokeTool : Node
{
    [Signal] public delegate void MessageEventHandler(string text);
    [Signal] public delegate void EditAppliedEventHandler(string name);

    private readonly StrokeCapture _capture = new(minSpacing: 4f, minLength: 8f);
    private readonly CutTool _cut = new();
    private readonly FitTool _fit = new();
    private HairToolKind _kind = HairToolKind.Cut;
    private Line2D? _strokeLine, _areaLine;
    private Color _strokeColor = new(1f, 0.85f, 0.2f);

    [Export] public HairSystem3D? Hair { get; set; }
    /// <summary>The camera strokes are seen through; empty = the viewport's current camera.</summary>
    [Export] public Camera3D? Camera { get; set; }
    [Export] public HairToolKind Tool { get => _kind; set { _kind = value; _capture.Cancel(); _fit.Reset(); Redraw(); EmitHint(); } }
    /// <summary>Colour of the stroke being drawn (the fit area at 60 % opacity); a change recolours the lines at once.</summary>
    [Export] public Color StrokeColor { get => _strokeColor; set { _strokeColor = value; Recolor(); } }

    public override void _Ready()
    {
        _strokeLine = new Line2D { Width = 3f, Antialiased = true };
        _areaLine = new Line2D { Width = 2f, Antialiased = true, Closed = true };
        Recolor();
        AddChild(_strokeLine);
        AddChild(_areaLine);
    }

    private void Recolor()
    {
        if (_strokeLine != null) _strokeLine.DefaultColor = _strokeColor;
        if (_areaLine != null) _areaLine.DefaultColor = _strokeColor with { A = 0.6f };
    }

    public override void _UnhandledInput(InputEvent e)
    {
        if (_kind == HairToolKind.None || Hair == null || !PointerInput.TryConvert(e, out var sample)) return;
        var result = _capture.Handle(sample);
        if (result == StrokeEvent.Ignored) return;
        GetViewport().SetInputAsHandled();
        if (result == StrokeEvent.Completed) Commit();
        Redraw();
    }

    /// <summary>Undoes the last run-time edit.</summary>
    public void Undo() => Hair?.UndoEdit();

    private void Commit()
    {
        var camera = Camera ?? GetViewport().GetCamera3D();
        if (Hair?.Scene == null || camera == null) return;
        IHairStrokeTool tool = _kind == HairToolKind.Fit ? _fit : _cut;
        try
        {
            var cam = GodotConvert.StrokeCamera(camera, GetViewport().GetVisibleRect().Size);
            var edit = tool.Complete(Hair.Scene, _capture.Completed, cam);
            if (edit == null) { EmitHint(); return; }
            Hair.ApplyEdit(edit);
            EmitSignal(SignalName.EditApplied, edit.Name);
            EmitHint();
        }
        catch (ArgumentException ex)
        {
            tool.Reset();
            EmitSignal(SignalName.Message, ex.Message);
        }
    }

    private void EmitHint()
    {
        if (!IsInsideTree()) return;
        string text = _kind switch { HairToolKind.Cut => _cut.Hint, HairToolKind.Fit => _fit.Hint, _ => "" };
        EmitSignal(SignalName.Message, text);
    }

    private void Redraw()
    {
        if (_strokeLine == null || _areaLine == null) return;
        _strokeLine.Points = ToGodot(_capture.Points);
        _areaLine.Points = _kind == HairToolKind.Fit ? ToGodot(_fit.PendingArea) : Array.Empty<Vector2>();
    }

    private static Vector2[] ToGodot(IReadOnlyList<System.Numerics.Vector2> pts)
    {
        var a = new Vector2[pts.Count];
        for (int i = 0; i < a.Length; i++) a[i] = pts[i].ToGodot();
        return a;
    }
}
