using Godot;
using HairSheet.Logic;

namespace HairSheet;

/// <summary>Godot mouse and touch events → engine-neutral pointer samples, so mouse and touch make the same strokes.</summary>
public static class PointerInput
{
    public static bool TryConvert(InputEvent e, out PointerSample sample)
    {
        switch (e)
        {
            // Godot's mouse copy of a touch (emulate_mouse_from_touch, on so that GUI buttons work on touch screens):
            // the touch itself arrives as ScreenTouch/ScreenDrag, so the copy would draw every stroke twice.
            case InputEventMouse m when m.Device == InputEvent.DeviceIdEmulation:
                sample = default;
                return false;
            case InputEventMouseButton { ButtonIndex: MouseButton.Left } b:
                sample = new PointerSample(b.Pressed ? PointerPhase.Down : PointerPhase.Up, StrokeCapture.MousePointer, b.Position.ToNumerics());
                return true;
            case InputEventMouseButton { ButtonIndex: MouseButton.Right, Pressed: true } r:
                sample = new PointerSample(PointerPhase.Cancel, StrokeCapture.MousePointer, r.Position.ToNumerics());
                return true;
            case InputEventMouseMotion m when (m.ButtonMask & MouseButtonMask.Left) != 0:
                sample = new PointerSample(PointerPhase.Move, StrokeCapture.MousePointer, m.Position.ToNumerics());
                return true;
            case InputEventScreenTouch t:
                var phase = t.Canceled ? PointerPhase.Cancel : t.Pressed ? PointerPhase.Down : PointerPhase.Up;
                sample = new PointerSample(phase, t.Index, t.Position.ToNumerics());
                return true;
            case InputEventScreenDrag d:
                sample = new PointerSample(PointerPhase.Move, d.Index, d.Position.ToNumerics());
                return true;
            case InputEventKey { Pressed: true, Keycode: Key.Escape }:
                sample = new PointerSample(PointerPhase.Cancel, StrokeCapture.MousePointer, default);
                return true;
            default:
                sample = default;
                return false;
        }
    }
}
