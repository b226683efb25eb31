// Zoom and pan on the playground canvas. The renderer (Rust, src/render) draws the scene through
// its view, so the pixels of a zoomed frame come from the core like any other; this module only
// maps input to `zoom_view` / `pan_view` / `fit_view`: the wheel and a two-finger pinch zoom about
// the pointer, + and − (and 0 for Fit) zoom about the centre, and a drag pans a zoomed view: with
// the Select tool on empty space (editor.js asks here) or with any tool while Space is held. The
// editor maps pointers through the same `view()`, so drawing while zoomed lands under the pointer.

import { onPage } from '../core/keys.js';

/** Zoom of one + / − press or one button press. */
export const KEY_FACTOR = 1.5;
/** Wheel delta (px) that zooms by e (a notch of 100 px: ×1.22). */
const WHEEL_PX_PER_E = 500;

/** Device px per CSS px of `canvas`'s backing store. */
function deviceRatio(canvas) {
  const rect = canvas.getBoundingClientRect();
  return { x: canvas.width / Math.max(1, rect.width), y: canvas.height / Math.max(1, rect.height), rect };
}

/**
 * Wires zoom and pan on `overlay` (the input canvas over `canvas`); returns the controls other
 * modules use (the Present overlay's buttons, the editor's pan on empty space).
 */
export function setupZoom(app, canvas, overlay) {
  /** Canvas device px of a client point. */
  const toCanvas = (clientX, clientY) => {
    const { x, y, rect } = deviceRatio(canvas);
    return [(clientX - rect.left) * x, (clientY - rect.top) * y];
  };
  const zoomAt = (cx, cy, factor) => {
    app.guard((sim) => sim.zoom_view(cx, cy, factor));
    app.dirty = true;
  };
  const zoomBy = (factor) => zoomAt(canvas.width / 2, canvas.height / 2, factor);
  const fit = () => {
    app.guard((sim) => sim.fit_view());
    app.dirty = true;
  };
  /** The zoom over the fitted view (1: the whole scene), as the worker last reported it. */
  const level = () => app.guard((sim) => sim.view_zoom()).value ?? 1;

  // Pans wait for the worker: while one is on its way, later drags add up into the next call.
  let panOwed = [0, 0];
  let panning = false;
  const panBy = (dxCss, dyCss) => {
    const { x, y } = deviceRatio(canvas);
    panOwed = [panOwed[0] + dxCss * x, panOwed[1] + dyCss * y];
    if (panning) return;
    const send = () => {
      const [dx, dy] = panOwed;
      panOwed = [0, 0];
      if (dx === 0 && dy === 0) {
        panning = false;
        return;
      }
      panning = true;
      Promise.resolve(app.guard((sim) => sim.pan_view(dx, dy))).finally(() => {
        app.dirty = true;
        send();
      });
    };
    send();
  };

  let space = false;
  let pinch = null;
  /** What other modules use: `spaceUsed` is set once a drag has panned with Space held (editor.js). */
  const controls = {
    zoomBy,
    fit,
    panBy,
    level,
    spaceHeld: () => space,
    pinching: () => pinch !== null,
    spaceUsed: false,
  };

  overlay.addEventListener('wheel', (e) => {
    if (app.crashed || e.deltaY === 0) return;
    e.preventDefault();
    const pixels = e.deltaMode === 1 ? e.deltaY * 33 : e.deltaMode === 2 ? e.deltaY * 400 : e.deltaY;
    const [cx, cy] = toCanvas(e.clientX, e.clientY);
    zoomAt(cx, cy, Math.exp(-pixels / WHEEL_PX_PER_E));
  }, { passive: false });

  // Two touches pinch (zoom about their midpoint by the change of their distance) and pan.
  const touches = new Map();
  overlay.addEventListener('pointerdown', (e) => {
    if (e.pointerType !== 'touch') return;
    touches.set(e.pointerId, [e.clientX, e.clientY]);
    if (touches.size === 2) {
      const [a, b] = [...touches.values()];
      pinch = { distance: Math.hypot(a[0] - b[0], a[1] - b[1]), mid: [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2] };
      app.dispatchEvent(new Event('pinch'));
    }
  }, true);
  overlay.addEventListener('pointermove', (e) => {
    if (!touches.has(e.pointerId)) return;
    touches.set(e.pointerId, [e.clientX, e.clientY]);
    if (!pinch || touches.size !== 2) return;
    const [a, b] = [...touches.values()];
    const distance = Math.hypot(a[0] - b[0], a[1] - b[1]);
    const mid = [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
    if (pinch.distance > 0 && distance > 0 && Math.abs(distance / pinch.distance - 1) > 0.02) {
      const [cx, cy] = toCanvas(mid[0], mid[1]);
      zoomAt(cx, cy, distance / pinch.distance);
      pinch.distance = distance;
    }
    panBy(mid[0] - pinch.mid[0], mid[1] - pinch.mid[1]);
    pinch.mid = mid;
  }, true);
  for (const type of ['pointerup', 'pointercancel']) {
    overlay.addEventListener(type, (e) => {
      touches.delete(e.pointerId);
      if (touches.size < 2) pinch = null;
    }, true);
  }

  // Space held: a drag with any tool pans (the editor asks `spaceHeld()`). So that holding Space
  // to pan does not play meanwhile, on this page Space plays or pauses when it is released, and
  // only when no drag used it (its press is taken here, before the page's shortcuts).
  document.addEventListener('keydown', (e) => {
    if (e.key !== ' ' || e.altKey || e.ctrlKey || e.metaKey || app.crashed || !onPage(e)) return;
    e.preventDefault();
    if (e.repeat) return;
    space = true;
    controls.spaceUsed = false;
  }, true);
  document.addEventListener('keyup', (e) => {
    if (e.key !== ' ' || !space) return;
    space = false;
    if (!controls.spaceUsed && !app.crashed) app.setPlaying(!app.playing);
  }, true);
  window.addEventListener('blur', () => (space = false));

  document.addEventListener('keydown', (e) => {
    if (app.crashed || e.defaultPrevented || e.altKey || e.ctrlKey || e.metaKey || !onPage(e)) return;
    if (e.key === '+' || e.key === '=') zoomBy(KEY_FACTOR);
    else if (e.key === '-' || e.key === '_') zoomBy(1 / KEY_FACTOR);
    else if (e.key === '0') fit();
    else return;
    e.preventDefault();
  });

  const fitButton = document.getElementById('zoom-fit');
  fitButton?.addEventListener('click', fit);
  document.getElementById('zoom-in')?.addEventListener('click', () => zoomBy(KEY_FACTOR));
  document.getElementById('zoom-out')?.addEventListener('click', () => zoomBy(1 / KEY_FACTOR));

  app.zoom = controls;
  return controls;
}
