// One class per tool. A tool gets pointer events (CSS pixels from the canvas's top-left) while it is active and
// draws its feedback on the overlay; strokes go to the server with the camera they were drawn with, and the
// library's own stroke, cut, select and fit code does the work.
import { command } from './api.js';

class Tool {
  constructor(studio) { this.studio = studio; this.points = null; }
  get drawing() { return true; }
  down(p) { this.points = [p]; }
  move(p) {
    if (!this.points) return;
    const last = this.points[this.points.length - 1];
    if (Math.hypot(p[0] - last[0], p[1] - last[1]) >= 2) this.points.push(p);
  }
  async up(p) {
    if (!this.points) return;
    this.move(p);
    const points = this.points;
    this.points = null;
    this.studio.drawOverlay();   // the stroke disappears as soon as it is sent, however slowly the view redraws
    await this.finish(points);
  }
  cancel() { this.points = null; }
  draw() {}
  async finish() {}
  flat(points) { return points.flat(); }
}

/** Orbit the camera; the overlay lets the pointer through to the orbit controls. */
export class ViewTool extends Tool {
  get drawing() { return false; }
}

/** A line drawn across hair cuts every strand it crosses there. */
export class CutTool extends Tool {
  draw(g) { if (this.points) polyline(g, this.points, '#ff6b5a'); }
  async finish(points) {
    if (points.length < 2) return;
    await this.studio.run(() => command('cut', {
      points: this.flat(points), camera: this.studio.view.strokeCamera(), visibleOnly: this.studio.options.visibleOnly,
    }));
  }
}

/** Rectangle, lasso or brush; shift adds to the selection, alt takes away. */
export class SelectTool extends Tool {
  down(p, e) { super.down(p); this.mode = e.shiftKey ? 'add' : e.altKey || e.ctrlKey ? 'subtract' : 'replace'; }
  get shape() { return this.studio.options.selectShape; }
  get colour() { return '#ffb35a'; }
  draw(g) {
    if (!this.points) return;
    const shape = this.shape, colour = this.colour;
    if (shape === 'rectangle') {
      const [a, b] = [this.points[0], this.points[this.points.length - 1]];
      g.strokeStyle = colour; g.setLineDash([6, 4]); g.strokeRect(a[0], a[1], b[0] - a[0], b[1] - a[1]); g.setLineDash([]);
    } else if (shape === 'lasso') {
      polyline(g, [...this.points, this.points[0]], colour);
    } else {
      g.fillStyle = `${colour}33`;
      for (const q of this.points) { g.beginPath(); g.arc(q[0], q[1], this.studio.options.brushRadius, 0, 2 * Math.PI); g.fill(); }
    }
  }
  /** The stroke as the server reads it (a rectangle is its two corners), or null when it is too short to send. */
  strokePoints(points) {
    const shape = this.shape;
    if (shape === 'rectangle') points = [points[0], points[points.length - 1]];
    if (shape === 'lasso' && points.length < 3) return null;
    return this.flat(points);
  }
  async finish(points) {
    const flat = this.strokePoints(points);
    if (!flat) return;
    await this.studio.run(() => command('select', {
      shape: this.shape, mode: this.mode, points: flat, radius: this.studio.options.brushRadius,
      rootsOnly: this.studio.options.rootsOnly, visibleOnly: this.studio.options.visibleOnly,
      camera: this.studio.view.strokeCamera(),
    }));
  }
}

/**
 * Paints where hair grows on a head mesh (or erases it), with the same rectangle, lasso and brush strokes as Select;
 * Alt erases and Shift paints whatever the panel's mode. The server's ScalpPaint marks the triangles the stroke
 * covers that face the camera and are not hidden by the mesh; Grow on scalp puts the hair there.
 */
export class PaintTool extends SelectTool {
  down(p, e) { Tool.prototype.down.call(this, p); this.mode = e.altKey ? 'erase' : e.shiftKey ? 'add' : this.studio.options.paintMode; }
  get shape() { return this.studio.options.paintShape; }
  get colour() { return this.mode === 'erase' ? '#7fd0ff' : '#ff5a4a'; }
  async finish(points) {
    const flat = this.strokePoints(points);
    if (!flat) { this.studio.say('A lasso needs at least three points: draw around the area to paint.', true); return; }
    await this.studio.run(() => command('scalp/paint', {
      shape: this.shape, mode: this.mode, points: flat, radius: this.studio.options.brushRadius,
      camera: this.studio.view.strokeCamera(),
    }));
  }
}

/** A stroke from the selected strands' roots outwards: the strands take its shape, which becomes their rest shape. */
export class FitTool extends Tool {
  draw(g) { if (this.points) polyline(g, this.points, '#7fd0ff'); }
  async finish(points) {
    if (points.length < 2) return;
    await this.studio.run(() => command('fit', { points: this.flat(points), camera: this.studio.view.strokeCamera() }));
  }
}

/** Drag moves the head in the screen's plane; shift-drag turns it. */
export class HeadTool extends Tool {
  down(p, e) { super.down(p); this.turn = e.shiftKey; this.last = p; }
  move(p) {
    if (!this.points) return;
    const [dx, dy] = [p[0] - this.last[0], p[1] - this.last[1]];
    this.last = p;
    const head = this.studio.head;
    if (this.turn) {
      head.yaw += dx * 0.01;
      head.pitch += dy * 0.01;
    } else {
      // Pixels to metres at the head's distance from the camera.
      const view = this.studio.view, cam = view.camera;
      const distance = cam.position.distanceTo(view.controls.target);
      const metresPerPixel = 2 * distance * Math.tan(cam.fov * Math.PI / 360) / view.canvas.clientHeight;
      const right = [cam.matrixWorld.elements[0], cam.matrixWorld.elements[1], cam.matrixWorld.elements[2]];
      const up = [cam.matrixWorld.elements[4], cam.matrixWorld.elements[5], cam.matrixWorld.elements[6]];
      for (let i = 0; i < 3; i++) head.position[i] += metresPerPixel * (dx * right[i] - dy * up[i]);
    }
    this.studio.sendHead();
  }
  async finish() {}
}

function polyline(g, points, colour) {
  g.strokeStyle = colour; g.lineWidth = 2; g.lineJoin = 'round';
  g.beginPath();
  points.forEach((q, i) => (i ? g.lineTo(q[0], q[1]) : g.moveTo(q[0], q[1])));
  g.stroke();
}
