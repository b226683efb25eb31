// Drawing tools on the overlay canvas, with Pointer Events and pointer capture so mouse, pen and
// touch behave the same. Every scene change goes through `Sim.edit`; hit testing is `Sim.pick`.
// The overlay only shows rubber-band previews of gestures in progress.
//
// Keyboard: the focused overlay canvas shows a cursor; arrows move it (Shift: five times
// further), Enter places with the current tool through the same `finish` / `polygonClick` a
// pointer uses (circle, rectangle and group: one Enter for the first point, one for the second;
// polygon and path: Enter adds a point, Enter again on the last point ends the shape), Escape
// cancels. What happens is said in a polite live region next to the canvas. The tool buttons are
// a radio group: one tab stop, arrows move and select.

import { clientToScene, sceneUnitsPerCssPixel, viewTransform } from '../core/view.js';
import { PathEditor } from './path-edit.js';
import { onLanguageChange, setText, t } from '../core/i18n.js';

/** Tool names in number-key order (1…7). */
export const TOOLS = ['select', 'circle', 'rect', 'polygon', 'goal', 'group', 'path'];

/** Tools whose shape is a list of clicked points. */
const POINT_TOOLS = ['polygon', 'path'];

/** How long the hint pill shows after its words change before it fades (ms). */
export const HINT_SHOW_MS = 6000;

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

/** The `pointerId` of a gesture made with the keyboard cursor (no pointer has it). */
const KEYBOARD = 'keyboard';

/** Arrow keys → cursor direction. */
const ARROWS = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, -1], ArrowDown: [0, 1] };

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
    /** The keyboard cursor (scene coordinates) and whether it is shown (keyboard in use). */
    this.cursor = null;
    this.keyboard = false;
    this.status = this.makeStatus();
    this.paths = new PathEditor(app, this, overlay, canvas);
    /** What the teacher's link allows (lock.js replaces it): every tool, move and edit. */
    this.lock = { toolAllowed: () => true, movable: () => true, permit: (op) => op };
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
    // A second finger turns a drag into a pinch (zoom.js): the first finger's gesture ends.
    app.addEventListener('pinch', () => this.cancel());
    overlay.addEventListener('keydown', (e) => this.keyDown(e));
    overlay.addEventListener('focus', () => {
      if (overlay.matches(':focus-visible')) this.showCursor();
    });
    overlay.addEventListener('blur', () => {
      this.keyboard = false;
      if (this.drag?.pointerId === KEYBOARD) this.drag = null;
      this.showHint();
      this.draw();
    });
    this.fadeHintWhenRead();
    for (const button of document.querySelectorAll('button[data-tool]')) {
      button.setAttribute('role', 'radio');
      button.addEventListener('click', () => this.setTool(button.dataset.tool));
    }
    document.getElementById('tools')?.addEventListener('keydown', (e) => this.toolKey(e));
    this.setTool('select');
    onLanguageChange(() => this.showHint());
  }

  /** The live region that says where the keyboard cursor is and what Enter did. */
  makeStatus() {
    const status = Object.assign(document.createElement('p'), { id: 'canvas-cursor', className: 'visually-hidden' });
    status.setAttribute('aria-live', 'polite');
    this.overlay.after(status);
    return status;
  }

  /** Tool radio group: arrows (and Home/End) move the choice and the focus, wrapping round. */
  toolKey(e) {
    const buttons = [...document.querySelectorAll('button[data-tool]:not(:disabled)')];
    const at = buttons.indexOf(e.target);
    if (at < 0 || e.altKey || e.ctrlKey || e.metaKey) return;
    const moves = { ArrowRight: at + 1, ArrowDown: at + 1, ArrowLeft: at - 1, ArrowUp: at - 1, Home: 0, End: buttons.length - 1 };
    if (!Object.hasOwn(moves, e.key)) return;
    e.preventDefault();
    const next = buttons[(moves[e.key] + buttons.length) % buttons.length];
    this.setTool(next.dataset.tool);
    next.focus();
  }

  /** Switches tool, dropping any unfinished shape. */
  setTool(tool) {
    if (!TOOLS.includes(tool) || !this.lock.toolAllowed(tool)) return;
    this.cancel();
    this.tool = tool;
    this.overlay.dataset.tool = tool;
    // Roving tabindex: the checked tool is the group's one tab stop.
    for (const button of document.querySelectorAll('button[data-tool]')) {
      const checked = button.dataset.tool === tool;
      button.setAttribute('aria-checked', String(checked));
      button.tabIndex = checked ? 0 : -1;
    }
    this.showHint();
    if (this.keyboard) this.say(this.cursorText());
  }

  /**
   * The hint pill sits over the canvas's bottom-left corner, where agents walk too: it shows for
   * HINT_SHOW_MS whenever its words change (a tool, a refusal, the language) or the pointer
   * enters the canvas, then fades out. While the keyboard cursor is on it stays: it lists the
   * cursor's keys.
   */
  fadeHintWhenRead() {
    const hint = document.getElementById('hint');
    if (!hint) return;
    let timer = null;
    const show = () => {
      hint.classList.remove('faded');
      clearTimeout(timer);
      timer = setTimeout(() => {
        if (!this.keyboard) hint.classList.add('faded');
      }, HINT_SHOW_MS);
    };
    new MutationObserver(show).observe(hint, { childList: true, characterData: true, subtree: true });
    this.overlay.addEventListener('pointerenter', show);
    this.overlay.addEventListener('blur', show);
    show();
  }

  /** The hint line under the canvas: the tool's, plus the keys while the keyboard cursor shows. */
  showHint() {
    const hint = document.getElementById('hint');
    if (!hint) return;
    // The tool's hint from the tables (re-translated on a language switch), plus the cursor keys.
    // On a teacher-locked page the select hint names what stays put.
    const locked = this.tool === 'select' ? (this.lock?.lockedParts?.() ?? []) : [];
    const key = locked.length ? 'hint.select_locked' : HINTS[this.tool];
    const vars = locked.length ? { parts: locked.map((part) => t(`classroom.part.${part}`)).join(', ') } : undefined;
    if (!this.keyboard) setText(hint, key, vars);
    else {
      delete hint.dataset.i18n;
      hint.textContent = `${t(key, vars)} ${t('a11y.cursor.keys')}`;
    }
  }

  /** Shows the keyboard cursor (at the scene's centre the first time). */
  showCursor() {
    const { width, height } = this.app.scene;
    this.cursor ??= [Math.round(width / 2), Math.round(height / 2)];
    if (!this.keyboard) {
      this.keyboard = true;
      this.showHint();
      this.say(this.cursorText());
    }
    this.draw();
  }

  /** Writes `text` into the cursor's live region. */
  say(text) {
    this.status.textContent = text;
  }

  /** Where the cursor is and what Enter would do there. */
  cursorText() {
    const [x, y] = this.cursor ?? [0, 0];
    const at = t('a11y.cursor.at', { x: Math.round(x), y: Math.round(y) });
    const drag = this.drag?.pointerId === KEYBOARD ? this.drag : null;
    if (drag && this.tool === 'select') {
      return `${at} ${t('a11y.cursor.select.second', { dx: Math.round(x - drag.start[0]), dy: Math.round(y - drag.start[1]) })}`;
    }
    if (drag && this.tool === 'circle') {
      const r = Math.round(Math.hypot(x - drag.start[0], y - drag.start[1]));
      return `${at} ${t('a11y.cursor.circle.second', { r })}`;
    }
    if (drag) {
      const w = Math.round(Math.abs(x - drag.start[0]));
      const h = Math.round(Math.abs(y - drag.start[1]));
      return `${at} ${t(`a11y.cursor.${this.tool}.second`, { w, h })}`;
    }
    if (POINT_TOOLS.includes(this.tool) && this.polygon.length) {
      return `${at} ${t(`a11y.cursor.${this.tool}.more`, { n: this.polygon.length })}`;
    }
    return `${at} ${t(`a11y.cursor.${this.tool}`)}`;
  }

  /** Keys on the focused canvas: arrows move the cursor, Enter places, Escape cancels. */
  keyDown(e) {
    if (this.app.crashed || e.altKey || e.ctrlKey || e.metaKey) return;
    const arrow = ARROWS[e.key];
    if (arrow) {
      e.preventDefault();
      const wasShown = this.keyboard;
      this.showCursor();
      if (wasShown) this.moveCursor(arrow, e.shiftKey);
      return;
    }
    if (e.key === 'Enter') {
      // A polygon clicked with the pointer (no cursor shown) ends on Enter as before (controls.js).
      if (!this.keyboard && POINT_TOOLS.includes(this.tool) && this.polygon.length) return;
      e.preventDefault();
      if (!this.keyboard) this.showCursor();
      else this.place();
      return;
    }
    if (e.key === 'Escape' && this.keyboard && (this.drag?.pointerId === KEYBOARD || this.polygon.length)) {
      e.preventDefault();
      this.cancel();
      this.say(`${t('a11y.cursor.cancelled')} ${this.cursorText()}`);
    }
  }

  /** Moves the cursor one step (Shift: five), kept inside the scene. */
  moveCursor([dx, dy], big) {
    const { width, height } = this.app.scene;
    const step = Math.max(1, Math.round(Math.min(width, height) / 50)) * (big ? 5 : 1);
    const [x, y] = this.cursor;
    this.cursor = [Math.min(Math.max(x + dx * step, 0), width), Math.min(Math.max(y + dy * step, 0), height)];
    if (this.drag?.pointerId === KEYBOARD) this.drag.current = this.cursor;
    if (POINT_TOOLS.includes(this.tool) && this.polygon.length) this.hover = this.cursor;
    this.say(this.cursorText());
    this.draw();
  }

  /** Enter with the keyboard cursor: the current tool's pointer gesture, at the cursor. */
  async place() {
    const p = [...this.cursor];
    const before = this.countItems();
    this.lastEdit = null;
    if (this.tool === 'select' && this.drag?.pointerId === KEYBOARD) {
      // The second Enter puts the picked-up item down at the cursor (a move, as a pointer drag).
      const drag = this.drag;
      this.drag = null;
      drag.current = p;
      const moved = drag.current[0] !== drag.start[0] || drag.current[1] !== drag.start[1];
      this.finish(drag);
      this.say(`${t(moved ? 'a11y.cursor.moved' : 'a11y.cursor.kept')} ${this.cursorText()}`);
      this.draw();
      return;
    }
    if (this.tool === 'select') {
      const picked = await this.app.guard((sim) => sim.pick(p[0], p[1], this.units(PICK_TOLERANCE_CSS)));
      const item = picked.ok ? JSON.parse(picked.value) : null;
      this.app.select(item);
      if (item && item.kind === 'group') this.app.setActiveGroup(item.index);
      const detail = { x: p[0], y: p[1], tolerance: this.units(PICK_TOLERANCE_CSS) };
      this.app.dispatchEvent(new CustomEvent('canvas-click', { detail }));
      // The first Enter on an item also picks it up: arrows carry it, Enter puts it down.
      if (item && this.lock.movable(item)) this.drag = { pointerId: KEYBOARD, start: p, current: p, item };
      this.say(item ? t('a11y.cursor.selected', { item: t(`a11y.item.${item.kind}`, { n: item.index + 1 }) }) : t('a11y.cursor.nothing'));
      this.draw();
      return;
    }
    if (POINT_TOOLS.includes(this.tool)) {
      const last = this.polygon[this.polygon.length - 1];
      const round = (v) => Math.round(v * 10) / 10;
      if (last && last[0] === round(p[0]) && last[1] === round(p[1])) this.closePolygon();
      else this.polygonClick(p);
      if (this.polygon.length) {
        this.hover = this.cursor;
        this.say(this.cursorText());
        this.draw();
        return;
      }
    } else if (this.tool === 'goal') {
      this.finish({ start: p, current: p, item: null });
    } else if (!this.drag) {
      this.drag = { pointerId: KEYBOARD, start: p, current: p, item: null };
      this.say(this.cursorText());
      this.draw();
      return;
    } else {
      const drag = this.drag;
      this.drag = null;
      drag.current = p;
      this.finish(drag);
    }
    // The edit runs in the simulation worker: count once it was answered.
    await this.editDone;
    const after = this.countItems();
    const added = Object.keys(after).find((key) => after[key] > before[key]);
    // A refused edit is explained by the banner (an alert); say only that nothing was added.
    const outcome = added ? `a11y.added.${this.tool}` : this.lastEdit && !this.lastEdit.ok ? 'a11y.cursor.refused' : 'a11y.cursor.too.small';
    this.say(`${t(outcome)} ${this.cursorText()}`);
    this.draw();
  }

  /** How many obstacles, goals, groups and paths the scene has (to say whether Enter added one). */
  countItems() {
    const s = this.app.scene;
    return { obstacles: s.obstacles?.length ?? 0, goals: s.goals?.length ?? 0, groups: s.groups?.length ?? 0, paths: s.paths?.length ?? 0 };
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
    // The pointer takes over from the keyboard cursor (a keyboard gesture in progress ends).
    if (this.drag?.pointerId === KEYBOARD) this.drag = null;
    if (this.keyboard) {
      this.keyboard = false;
      this.showHint();
    }
    // A second finger pinches (zoom.js); Space held, any tool's drag pans a zoomed view.
    if (this.app.zoom?.pinching()) return;
    if (this.app.zoom?.spaceHeld()) {
      this.startPan(e);
      return;
    }
    const p = this.point(e);
    if (POINT_TOOLS.includes(this.tool)) {
      this.polygonClick(p);
      return;
    }
    try {
      this.overlay.setPointerCapture(e.pointerId);
    } catch {
      // Handed over late (path-edit.js held it while a pick was answered): already released.
    }
    this.drag = { pointerId: e.pointerId, start: p, current: p, item: null, picked: null, client: [e.clientX, e.clientY] };
    if (this.tool === 'select') {
      // The pick is answered by the simulation worker; the pointer-up waits for it (pointerUp).
      const drag = this.drag;
      drag.picked = Promise.resolve(this.app.guard((sim) => sim.pick(p[0], p[1], this.units(PICK_TOLERANCE_CSS)))).then((picked) => {
        const item = picked.ok ? JSON.parse(picked.value) : null;
        // A locked item can be selected (and its agents inspected), not dragged.
        drag.item = item && this.lock.movable(item) ? item : null;
        this.app.select(item);
        if (item && item.kind === 'group') this.app.setActiveGroup(item.index);
        // Empty space under the Select tool in a zoomed view: the drag pans (zoom.js).
        if (!item && (this.app.zoom?.level() ?? 1) > 1) drag.pan = true;
        this.draw();
      });
      // A key pressed before the pick is answered (Delete) acts on what it picks.
      this.picking = drag.picked;
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
    if (this.drag.pan) {
      const [x, y] = this.drag.client;
      if (x !== e.clientX || y !== e.clientY) {
        this.app.zoom?.panBy(e.clientX - x, e.clientY - y);
        this.drag.client = [e.clientX, e.clientY];
        this.drag.panned = true;
      }
      return;
    }
    this.drag.current = this.point(e);
    this.draw();
  }

  /** A drag that only pans the view (Space held): no edit, no selection. */
  startPan(e) {
    try {
      this.overlay.setPointerCapture(e.pointerId);
    } catch {
      // Already released: the drag still pans while the pointer is over the canvas.
    }
    // Space pressed to pan is not Space pressed to play (zoom.js plays on its release otherwise).
    this.app.zoom.spaceUsed = true;
    this.drag = { pointerId: e.pointerId, pan: true, panned: false, client: [e.clientX, e.clientY], start: null, current: null };
  }

  pointerUp(e) {
    if (!this.drag || e.pointerId !== this.drag.pointerId) return;
    const drag = this.drag;
    this.drag = null;
    if (this.overlay.hasPointerCapture(e.pointerId)) this.overlay.releasePointerCapture(e.pointerId);
    if (drag.pan && (drag.panned || !drag.start)) {
      this.draw();
      return;
    }
    drag.current = this.point(e);
    if (drag.picked) {
      drag.picked.then(() => {
        this.finish(drag);
        this.draw();
      });
      return;
    }
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
    this.edit({ op: 'add_group', group }).then((added) => {
      if (added) this.app.setActiveGroup((this.app.scene.groups?.length ?? 1) - 1);
    });
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

  /** Deletes the selected item (Delete/Backspace), once a pick in progress has been answered. */
  async deleteSelection() {
    await this.picking;
    const item = this.app.selection;
    if (!item) return;
    if (this.drag?.pointerId === KEYBOARD) this.drag = null;
    this.edit({ op: 'delete', item });
  }

  /**
   * One undoable `edit`; errors show in the banner and leave the scene unchanged. Resolves to
   * whether it was applied (the simulation worker answers it); `editDone` is the last one's.
   */
  edit(op, options = {}) {
    // The teacher's link may refuse it (lock.js says why in the hint line).
    const allowed = this.lock.permit(op);
    if (!allowed) {
      this.lastEdit = { ok: false };
      this.editDone = Promise.resolve(false);
      return this.editDone;
    }
    this.editDone = Promise.resolve(this.app.change((sim) => sim.edit(JSON.stringify(allowed)), options)).then((result) => {
      this.lastEdit = result;
      return result.ok;
    });
    return this.editDone;
  }

  /** Redraws the rubber-band previews. */
  draw() {
    const ctx = this.ctx;
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.clearRect(0, 0, this.overlay.width, this.overlay.height);
    const cursor = this.keyboard && this.cursor;
    if (this.app.crashed || (!this.drag && !this.polygon.length && !cursor)) return;
    const { scale, ox, oy } = viewTransform(this.app);
    ctx.setTransform(scale, 0, 0, scale, ox, oy);
    const px = 1 / scale;
    const ratio = window.devicePixelRatio || 1;
    if (cursor) this.drawCursor(ctx, ratio * px);
    if (!this.drag && !this.polygon.length) return;
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

  /** The keyboard cursor: a cross in a ring, dark over light so it shows on any field. */
  drawCursor(ctx, cssPx) {
    const [x, y] = this.cursor;
    const arm = 12 * cssPx;
    ctx.save();
    ctx.setLineDash([]);
    for (const [colour, width] of [['#ffffff', 5], ['#17202c', 2]]) {
      ctx.strokeStyle = colour;
      ctx.lineWidth = width * cssPx;
      ctx.beginPath();
      ctx.moveTo(x - arm, y);
      ctx.lineTo(x + arm, y);
      ctx.moveTo(x, y - arm);
      ctx.lineTo(x, y + arm);
      ctx.moveTo(x + arm * 0.6, y);
      ctx.arc(x, y, arm * 0.6, 0, Math.PI * 2);
      ctx.stroke();
    }
    ctx.restore();
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
      // Where the frame draws it (a moving goal is not at its scene `position`), from the core.
      const g = this.app.guard((sim) => JSON.parse(sim.goals_json())).value?.[item.index];
      if (g) ctx.arc(g.x + dx, g.y + dy, g.radius, 0, Math.PI * 2);
    } else if (item.kind === 'path') {
      const path = scene.paths?.[item.index];
      path?.points.forEach(([x, y], i) => (i ? ctx.lineTo(x + dx, y + dy) : ctx.moveTo(x + dx, y + dy)));
    } else if (item.kind === 'group') {
      const g = scene.groups?.[item.index];
      if (g) ctx.rect(g.spawn.min[0] + dx, g.spawn.min[1] + dy, g.spawn.max[0] - g.spawn.min[0], g.spawn.max[1] - g.spawn.min[1]);
    }
  }
}
