// Drawing tools on the overlay canvas, with Pointer Events and pointer capture so mouse, pen and
// touch behave the same. Every scene change goes through `Sim.edit`; hit testing is `Sim.pick`.
// The overlay only shows rubber-band previews of gestures in progress.

import { clientToScene, sceneUnitsPerCssPixel, viewTransform } from '../core/view.js';
import { PathEditor } from './path-edit.js';
import { setText, t } from '../core/i18n.js';

/** Tool names in number-key order (1…7). */
export const TOOLS = ['select', 'circle', 'rect', 'polygon', 'goal', 'group', 'path'];

/** Tools whose shape is a list of clicked points. */
const POINT_TOOLS = ['polygon', 'path'];

/** The hint of each tool (its key in the strings tables). */
const HINTS = {
  select: 'hint.select',
  circle: 'hint.circle',
  rect: 'hint.rect',
  polygon: 'hint.polygon',
  goal: 'hint.goal',
  group: 'hint.group',
  path: 'hint.path',
};

/** Pick tolerance and gesture thresholds, in CSS px. */
const PICK_TOLERANCE_CSS = 10;
const CLICK_SLOP_CSS = 3;
const CLOSE_POLYGON_CSS = 12;

export class Editor {
  constructor(app, overlay, canvas) {
    this.app = app;
    this.overlay = overlay;
    this.canvas = canvas;
    this.ctx = overlay.getContext('2d');
    this.tool = 'select';
    /** Gesture in progress: { pointerId, start, current, item? } (scene coordinates). */
    this.drag = null;
    /** Polygon vertices placed so far (scene coordinates). */
    this.polygon = [];
    this.hover = null;
    this.paths = new PathEditor(app, this, overlay, canvas);
    overlay.addEventListener('pointerdown', (e) => this.pointerDown(e));
    overlay.addEventListener('pointermove', (e) => this.pointerMove(e));
    overlay.addEventListener('pointerup', (e) => this.pointerUp(e));
    overlay.addEventListener('pointercancel', () => this.cancel());
    overlay.addEventListener('dblclick', (e) => {
      if (POINT_TOOLS.includes(this.tool)) {
        e.preventDefault();
        this.closePolygon();
      }
    });
    app.addEventListener('resize', () => this.draw());
    app.addEventListener('scene', () => this.draw());
    for (const button of document.querySelectorAll('[data-tool]')) {
      button.setAttribute('role', 'radio');
      button.addEventListener('click', () => this.setTool(button.dataset.tool));
    }
    this.setTool('select');
  }

  /** Switches tool, dropping any unfinished shape. */
  setTool(tool) {
    if (!TOOLS.includes(tool)) return;
    this.cancel();
    this.tool = tool;
    this.overlay.dataset.tool = tool;
    for (const button of document.querySelectorAll('[data-tool]')) {
      button.setAttribute('aria-checked', String(button.dataset.tool === tool));
    }
    const hint = document.getElementById('hint');
    if (hint) setText(hint, HINTS[tool]);
  }

  /** Drops the gesture or polygon in progress (Escape). */
  cancel() {
    this.drag = null;
    this.polygon = [];
    this.hover = null;
    this.draw();
  }

  /** Scene point of a pointer event, clamped to the scene so shapes never start off-world. */
  point(e) {
    const [x, y] = clientToScene(this.app, this.canvas, e.clientX, e.clientY);
    const { width, height } = this.app.scene;
    return [Math.min(Math.max(x, 0), width), Math.min(Math.max(y, 0), height)];
  }

  /** Scene units for `css` screen pixels. */
  units(css) {
    return css * sceneUnitsPerCssPixel(this.app, this.canvas);
  }

  pointerDown(e) {
    if (this.app.crashed || (e.pointerType === 'mouse' && e.button !== 0)) return;
    e.preventDefault();
    this.overlay.focus?.({ preventScroll: true });
    const p = this.point(e);
    if (POINT_TOOLS.includes(this.tool)) {
      this.polygonClick(p);
      return;
    }
    this.overlay.setPointerCapture(e.pointerId);
    this.drag = { pointerId: e.pointerId, start: p, current: p, item: null };
    if (this.tool === 'select') {
      const picked = this.app.guard((sim) => JSON.parse(sim.pick(p[0], p[1], this.units(PICK_TOLERANCE_CSS))));
      const item = picked.ok ? picked.value : null;
      this.drag.item = item;
      this.app.select(item);
      if (item && item.kind === 'group') this.app.setActiveGroup(item.index);
    }
    this.draw();
  }

  pointerMove(e) {
    if (POINT_TOOLS.includes(this.tool) && this.polygon.length) {
      this.hover = this.point(e);
      this.draw();
      return;
    }
    if (!this.drag || e.pointerId !== this.drag.pointerId) return;
    this.drag.current = this.point(e);
    this.draw();
  }

  pointerUp(e) {
    if (!this.drag || e.pointerId !== this.drag.pointerId) return;
    const drag = this.drag;
    drag.current = this.point(e);
    this.drag = null;
    if (this.overlay.hasPointerCapture(e.pointerId)) this.overlay.releasePointerCapture(e.pointerId);
    this.finish(drag);
    this.draw();
  }

  /** Turns a finished drag into one `edit` call. */
  finish({ start, current, item }) {
    const [x0, y0] = start;
    const [x1, y1] = current;
    const moved = Math.abs(x1 - x0) > this.units(CLICK_SLOP_CSS) || Math.abs(y1 - y0) > this.units(CLICK_SLOP_CSS);
    const round = (v) => Math.round(v * 10) / 10;
    const box = { min: [round(Math.min(x0, x1)), round(Math.min(y0, y1))], max: [round(Math.max(x0, x1)), round(Math.max(y0, y1))] };
    switch (this.tool) {
      case 'select':
        if (item && moved) {
          this.edit({ op: 'move', item, dx: x1 - x0, dy: y1 - y0 }, { clearSelection: false });
        }
        // A plain click also inspects the agent under it (inspector.js listens).
        if (!moved) {
          const detail = { x: x0, y: y0, tolerance: this.units(PICK_TOLERANCE_CSS) };
          this.app.dispatchEvent(new CustomEvent('canvas-click', { detail }));
        }
        break;
      case 'circle':
        if (moved) {
          this.edit({ op: 'add_obstacle', obstacle: { shape: 'circle', center: [round(x0), round(y0)], radius: round(Math.hypot(x1 - x0, y1 - y0)) } });
        }
        break;
      case 'rect':
        if (moved) this.edit({ op: 'add_obstacle', obstacle: { shape: 'rect', ...box } });
        break;
      case 'goal': {
        const groups = this.app.scene.groups ?? [];
        const group = groups.length ? this.app.activeGroup : null;
        this.edit({ op: 'add_goal', position: [round(x1), round(y1)], radius: null, group });
        break;
      }
      case 'group':
        if (moved) this.addGroup(box);
        break;
      default:
        break;
    }
  }

  /** A new group in `spawn`: next palette colour, the active group's goal, planner and radius. */
  addGroup(spawn) {
    const groups = this.app.scene.groups ?? [];
    const model = groups[this.app.activeGroup];
    const group = {
      name: t('groups.default_name', { n: groups.length + 1 }),
      color: this.app.nextColor(),
      count: 30,
      spawn,
      goal: model ? model.goal : (this.app.scene.goals?.length ? 0 : null),
      agent_radius: model ? model.agent_radius : 4,
      planner: model ? structuredClone(model.planner) : this.app.defaultPlanner(),
    };
    if (this.edit({ op: 'add_group', group })) {
      this.app.setActiveGroup((this.app.scene.groups?.length ?? 1) - 1);
    }
  }

  polygonClick(p) {
    const first = this.polygon[0];
    const near = first && Math.abs(first[0] - p[0]) <= this.units(CLOSE_POLYGON_CSS) &&
      Math.abs(first[1] - p[1]) <= this.units(CLOSE_POLYGON_CSS);
    if (near && this.polygon.length >= 3 && this.tool === 'polygon') {
      this.closePolygon();
      return;
    }
    this.polygon.push(p.map((v) => Math.round(v * 10) / 10));
    this.hover = p;
    this.draw();
  }

  /** Ends the polygon (three points or more) or path (two or more) in progress; a double-click
   * may add a duplicate point. A path is followed by the active group when it uses Boids. */
  closePolygon() {
    const points = this.polygon.filter((p, i, all) => i === 0 || p[0] !== all[i - 1][0] || p[1] !== all[i - 1][1]);
    this.polygon = [];
    this.hover = null;
    if (this.tool === 'path') {
      const active = (this.app.scene.groups ?? [])[this.app.activeGroup];
      const group = active?.planner?.kind === 'boids' ? this.app.activeGroup : null;
      if (points.length >= 2) this.edit({ op: 'add_path', points, radius: null, group });
    } else if (points.length >= 3) {
      this.edit({ op: 'add_obstacle', obstacle: { shape: 'polygon', points } });
    }
    this.draw();
  }

  /** Deletes the selected item (Delete/Backspace). */
  deleteSelection() {
    const item = this.app.selection;
    if (!item) return;
    this.edit({ op: 'delete', item });
  }

  /** One undoable `edit`; errors show in the banner and leave the scene unchanged. */
  edit(op, options = {}) {
    return this.app.change((sim) => sim.edit(JSON.stringify(op)), options).ok;
  }

  /** Redraws the rubber-band previews. */
  draw() {
    const ctx = this.ctx;
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.clearRect(0, 0, this.overlay.width, this.overlay.height);
    if (this.app.crashed || (!this.drag && !this.polygon.length)) return;
    const { scale, ox, oy } = viewTransform(this.app);
    ctx.setTransform(scale, 0, 0, scale, ox, oy);
    const px = 1 / scale;
    const ratio = window.devicePixelRatio || 1;
    ctx.lineWidth = 2 * ratio * px;
    ctx.setLineDash([6 * ratio * px, 4 * ratio * px]);
    ctx.strokeStyle = '#17202c';
    ctx.fillStyle = 'rgba(47, 111, 223, 0.18)';
    if (POINT_TOOLS.includes(this.tool)) {
      this.drawPolygon(ctx, ratio * px);
      return;
    }
    const [x0, y0] = this.drag.start;
    const [x1, y1] = this.drag.current;
    ctx.beginPath();
    switch (this.tool) {
      case 'circle':
        ctx.arc(x0, y0, Math.hypot(x1 - x0, y1 - y0), 0, Math.PI * 2);
        break;
      case 'rect':
      case 'group':
        ctx.rect(Math.min(x0, x1), Math.min(y0, y1), Math.abs(x1 - x0), Math.abs(y1 - y0));
        break;
      case 'goal':
        ctx.arc(x1, y1, 20, 0, Math.PI * 2);
        break;
      case 'select':
        if (this.drag.item) this.itemPath(ctx, this.drag.item, x1 - x0, y1 - y0);
        break;
      default:
        break;
    }
    ctx.fill();
    ctx.stroke();
  }

  drawPolygon(ctx, cssPx) {
    const points = this.hover ? [...this.polygon, this.hover] : this.polygon;
    ctx.beginPath();
    points.forEach(([x, y], i) => (i ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
    if (this.tool === 'polygon') {
      if (points.length > 2) ctx.closePath();
      ctx.fill();
    }
    ctx.stroke();
    ctx.setLineDash([]);
    ctx.fillStyle = '#17202c';
    for (const [i, [x, y]] of this.polygon.entries()) {
      ctx.beginPath();
      ctx.arc(x, y, (i === 0 ? 6 : 4) * cssPx, 0, Math.PI * 2);
      ctx.fill();
    }
  }

  /** Outline of a scene item shifted by (dx, dy): the preview of a move. */
  itemPath(ctx, item, dx, dy) {
    const scene = this.app.scene;
    if (item.kind === 'obstacle') {
      const o = scene.obstacles?.[item.index];
      if (!o) return;
      if (o.shape === 'circle') {
        ctx.moveTo(o.center[0] + dx + o.radius, o.center[1] + dy);
        ctx.arc(o.center[0] + dx, o.center[1] + dy, o.radius, 0, Math.PI * 2);
      } else if (o.shape === 'rect') {
        ctx.rect(o.min[0] + dx, o.min[1] + dy, o.max[0] - o.min[0], o.max[1] - o.min[1]);
      } else if (o.shape === 'polygon') {
        o.points.forEach(([x, y], i) => (i ? ctx.lineTo(x + dx, y + dy) : ctx.moveTo(x + dx, y + dy)));
        ctx.closePath();
      }
    } else if (item.kind === 'goal') {
      const g = scene.goals?.[item.index];
      if (g) ctx.arc(g.position[0] + dx, g.position[1] + dy, g.radius, 0, Math.PI * 2);
    } else if (item.kind === 'path') {
      const path = scene.paths?.[item.index];
      path?.points.forEach(([x, y], i) => (i ? ctx.lineTo(x + dx, y + dy) : ctx.moveTo(x + dx, y + dy)));
    } else if (item.kind === 'group') {
      const g = scene.groups?.[item.index];
      if (g) ctx.rect(g.spawn.min[0] + dx, g.spawn.min[1] + dy, g.spawn.max[0] - g.spawn.min[0], g.spawn.max[1] - g.spawn.min[1]);
    }
  }
}
