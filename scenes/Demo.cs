using System;
using Godot;
using HairSheet;
using HairSheet.Logic;

namespace HairSheet.Scenes;

/// <summary>
/// Demo: the reference groom (435 sheets × 40 strands × 16 particles) on a head, an orbit camera
/// (right-drag or one-finger drag in Orbit mode, wheel to zoom), Cut / Fit / Undo / Reset / Save / Load
/// buttons, an optional head shake to show the roots following the head, and a readout of frame and hair time.
/// demo.tscn: the head mesh is a unit SphereMesh scaled by GroomSettings.HeadRadii (0.078, 0.1, 0.095), the collider
/// ellipsoid. mesh_head.tscn: the project's procedural head (head.obj, scalp painted in its vertex colours) is the
/// hair node's Scalp Mesh: the hair grows on it and collides with its distance field (Save and Load say why they
/// are not available for hair grown on a mesh).
/// </summary>
public partial class Demo : Node3D
{
    private const string SavePath = "user://hairstyle.tres";
    private readonly OrbitCamera _orbit = new() { Target = new System.Numerics.Vector3(0f, -0.02f, 0f), Distance = 0.75f, Pitch = 0.15f };
    private HairSystem3D _hair = null!;
    private HairStrokeTool _tool = null!;
    private Camera3D _camera = null!;
    private Node3D _head = null!;
    private Label _readout = null!, _hint = null!;
    private CheckButton _shake = null!;
    private bool _orbiting;
    private double _frameMs, _shakeTime;

    public override void _Ready()
    {
        _hair = GetNode<HairSystem3D>("Head/Hair");
        _tool = GetNode<HairStrokeTool>("StrokeTool");
        _camera = GetNode<Camera3D>("Camera");
        _head = GetNode<Node3D>("Head");
        _readout = GetNode<Label>("UI/Readout");
        _hint = GetNode<Label>("UI/Hint");
        _shake = GetNode<CheckButton>("UI/Bar/Shake");
        GetNode<Button>("UI/Bar/Cut").Pressed += () => SetTool(HairToolKind.Cut);
        GetNode<Button>("UI/Bar/Fit").Pressed += () => SetTool(HairToolKind.Fit);
        GetNode<Button>("UI/Bar/Orbit").Pressed += () => SetTool(HairToolKind.None);
        GetNode<Button>("UI/Bar/Undo").Pressed += () => _tool.Undo();
        GetNode<Button>("UI/Bar/Reset").Pressed += () => _hair.ResetStyle();
        GetNode<Button>("UI/Bar/Save").Pressed += () => Try(() => { _hair.SaveHairstyle(SavePath); _hint.Text = $"Saved to {SavePath}."; });
        GetNode<Button>("UI/Bar/Load").Pressed += () => Try(() => { _hair.LoadHairstyle(SavePath); _hint.Text = $"Loaded {SavePath}."; });
        _tool.Message += text => _hint.Text = text;
        SetTool(HairToolKind.Cut);
        PlaceCamera();
    }

    public override void _Process(double delta)
    {
        _frameMs = delta * 1000.0;
        var sim = _hair.Simulation;
        _readout.Text = sim == null
            ? "hair: not built (see the Output panel)"
            : $"frame {_frameMs,6:F2} ms   hair step {_hair.LastStepMilliseconds,6:F2} ms   sim time {sim.Time,7:F2} s   frame #{sim.Frame}";
    }

    public override void _PhysicsProcess(double delta)
    {
        if (!_shake.ButtonPressed) return;
        // A head shaking "no" while bobbing: the roots and colliders follow, the hair swings.
        _shakeTime += delta;
        float yaw = 0.7f * MathF.Sin(2f * MathF.PI * 0.8f * (float)_shakeTime);
        _head.Transform = new Transform3D(new Basis(Vector3.Up, yaw), new Vector3(0f, 0.02f * MathF.Sin(2f * MathF.PI * 1.1f * (float)_shakeTime), 0f));
    }

    public override void _UnhandledInput(InputEvent e)
    {
        switch (e)
        {
            case InputEventMouseButton { ButtonIndex: MouseButton.Right } b:
                _orbiting = b.Pressed;
                break;
            case InputEventMouseButton { ButtonIndex: MouseButton.WheelUp, Pressed: true }:
                _orbit.Zoom(1f); PlaceCamera();
                break;
            case InputEventMouseButton { ButtonIndex: MouseButton.WheelDown, Pressed: true }:
                _orbit.Zoom(-1f); PlaceCamera();
                break;
            case InputEventMouseMotion m when _orbiting || (_tool.Tool == HairToolKind.None && (m.ButtonMask & MouseButtonMask.Left) != 0):
                _orbit.Orbit(m.Relative.ToNumerics()); PlaceCamera();
                break;
            case InputEventScreenDrag d when _tool.Tool == HairToolKind.None:
                _orbit.Orbit(d.Relative.ToNumerics()); PlaceCamera();
                break;
        }
    }

    private void SetTool(HairToolKind kind)
    {
        _tool.Tool = kind;
        if (kind == HairToolKind.None) _hint.Text = "Orbit: drag to turn the view, wheel to zoom.";
    }

    private void PlaceCamera()
    {
        var (x, y, z) = _orbit.Basis;
        _camera.GlobalTransform = new Transform3D(new Basis(x.ToGodot(), y.ToGodot(), z.ToGodot()), _orbit.Eye.ToGodot());
    }

    private void Try(Action action)
    {
        try { action(); }
        catch (Exception e) when (e is System.IO.IOException or System.IO.InvalidDataException or ArgumentException or InvalidOperationException)
        {
            _hint.Text = e.Message;
        }
    }
}
