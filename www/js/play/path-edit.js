// Editable IGSA paths: in the select tool, a pointer on a waypoint handle (drawn by the Rust
// renderer) drags that waypoint; on release the group gets the edited waypoints through
// `Sim.set_group_waypoints` (one undo step) and follows them at once. The core checks the path:
// a segment through an obstacle is drawn red and the page warns. Double-clicking a handle plans
// the path again. Listeners run in the capture phase so a gesture that starts on a handle never
// reaches the editor's own tools.

import { showMessage } from '../core/errors.js';
import { t } from '../core/i18n.js';
import { clientToScene, sceneUnitsPerCssPixel, viewTransform } from '../core/view.js';

/** Pick tolerance for a handle, in CSS px (the handles are 5 device px in radius). */
const HANDLE_TOLERANCE_CSS = 9;

export class PathEditor {
  constructor(app, editor, overlay, canvas) {
    this.app = app;
    this.editor = editor;
    this.overlay = overlay;
    this.canvas = canvas;
    /** Drag in progress: { pointerId, group, index, points (scene px, start … goal) }. */
    this.drag = null;
    overlay.addEventListener('pointerdown', (e) => this.pointerDown(e), { capture: true });
    overlay.addEventListener('pointermove', (e) => this.pointerMove(e), { capture: true });
    overlay.addEventListener('pointerup', (e) => this.pointerUp(e), { capture: true });
    overlay.addEventListener('pointercancel', () => { this.drag = null; }, { capture: true });
    overlay.addEventListener('dblclick', (e) => this.replan(e), { capture: true });
  }

  point(e) {
    return clientToScene(this.app, this.canvas, e.clientX, e.clientY);
  }

  /** Whether the scene draws waypoint handles (an IGSA group's path): only then are picks asked. */
  hasHandles() {
    return (this.app.scene.groups ?? []).some((g) => g.planner?.kind === 'igsa');
  }

  /** The handle under the pointer: a Promise of `{ group, index }` or null. */
  async pick(e) {
    if (this.editor.tool !== 'select' || this.app.crashed || !this.editor.lock.movable({ kind: 'waypoint' })) return null;
    const [x, y] = this.point(e);
    const tolerance = HANDLE_TOLERANCE_CSS * sceneUnitsPerCssPixel(this.app, this.canvas);
    const result = await this.app.guard((sim) => sim.pick_waypoint(x, y, tolerance));
    return result.ok ? JSON.parse(result.value) : null;
  }

  /**
   * The simulation worker answers the pick, so the gesture is held meanwhile: a miss hands the
   * pointer-down (and a pointer-up that came in the meantime) to the editor's own tools.
   */
  pointerDown(e) {
    if (e.pointerType === 'mouse' && e.button !== 0) return;
    if (this.editor.tool !== 'select' || !this.hasHandles()) return;
    e.preventDefault();
    e.stopImmediatePropagation();
    const held = { down: e, up: null };
    this.held = held;
    this.pickHandle(e).then((taken) => {
      if (this.held !== held) return;
      this.held = null;
      if (taken) {
        if (held.up) this.pointerUp(held.up);
        return;
      }
      this.editor.pointerDown(held.down);
      if (held.up) this.editor.pointerUp(held.up);
    });
  }

  /** Starts a waypoint drag when `e` is on a handle; resolves to whether it did. */
  async pickHandle(e) {
    const hit = await this.pick(e);
    if (!hit) return false;
    const path = await this.app.guard((sim) => sim.group_path_json(hit.group));
    const value = path.ok ? JSON.parse(path.value) : null;
    if (!value) return false;
    try {
      this.overlay.setPointerCapture(e.pointerId);
    } catch {
      // The pointer was released while the pick was answered: the drag ends at once.
    }
    this.drag = { pointerId: e.pointerId, group: hit.group, index: hit.index, points: value.points };
    this.app.setActiveGroup(hit.group);
    return true;
  }

  pointerMove(e) {
    if (!this.drag || e.pointerId !== this.drag.pointerId) return;
    e.stopImmediatePropagation();
    this.drag.points[this.drag.index + 1] = this.point(e);
    this.draw();
  }

  pointerUp(e) {
    if (this.held && this.held.down.pointerId === e.pointerId) {
      this.held.up = e;
      e.stopImmediatePropagation();
      return;
    }
    if (!this.drag || e.pointerId !== this.drag.pointerId) return;
    e.stopImmediatePropagation();
    const drag = this.drag;
    this.drag = null;
    if (this.overlay.hasPointerCapture(e.pointerId)) this.overlay.releasePointerCapture(e.pointerId);
    drag.points[drag.index + 1] = this.point(e);
    const round = (v) => Math.round(v * 10) / 10;
    const waypoints = drag.points.slice(1, -1).map(([x, y]) => [round(x), round(y)]);
    this.apply(drag.group, waypoints);
  }

  /** Double-click on a handle: forget the edits and plan the path again. */
  async replan(e) {
    if (!this.hasHandles()) return;
    const hit = await this.pick(e);
    if (hit) this.apply(hit.group, []);
  }

  /** Sends the waypoints (one undo step) and warns when the path crosses an obstacle. */
  async apply(group, waypoints) {
    const result = await this.app.change((sim) => sim.set_group_waypoints(group, JSON.stringify(waypoints)), {
      clearSelection: false,
    });
    this.editor.draw();
    if (!result.ok) return;
    // A path planned again (no waypoints) is null until the frame loop has planned it.
    const checked = JSON.parse(result.value);
    const crossing = (checked?.crossing ?? []).map((c, i) => (c ? i + 1 : 0)).filter((i) => i > 0);
    if (crossing.length) {
      showMessage(t('path.crossing', { group: group + 1, segments: crossing.join(', ') }));
    }
  }

  /** The edited polyline while dragging, on the overlay (the Rust frame shows the old path). */
  draw() {
    this.editor.draw();
    if (!this.drag) return;
    const ctx = this.overlay.getContext('2d');
    const { scale, ox, oy } = viewTransform(this.app);
    ctx.setTransform(scale, 0, 0, scale, ox, oy);
    const px = (window.devicePixelRatio || 1) / scale;
    ctx.lineWidth = 2 * px;
    ctx.setLineDash([6 * px, 4 * px]);
    ctx.strokeStyle = '#17202c';
    ctx.beginPath();
    this.drag.points.forEach(([x, y], i) => (i ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
    ctx.stroke();
    ctx.setLineDash([]);
    const [x, y] = this.drag.points[this.drag.index + 1];
    ctx.beginPath();
    ctx.arc(x, y, 6 * px, 0, Math.PI * 2);
    ctx.fillStyle = '#ffffff';
    ctx.fill();
    ctx.stroke();
  }
}
