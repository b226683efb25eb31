// Canvas sizing and coordinates: the backing store is the CSS size × devicePixelRatio (sharp on
// HiDPI screens), kept in step with a ResizeObserver; the Sim renders at exactly that size.

/**
 * Largest backing store in pixels, for every scene canvas (pages and <flock-path> elements):
 * beyond this a 4K projector would spend the frame on blits.
 */
export const MAX_PIXELS = 3840 * 2400;

/** The backing-store size for a CSS box of `cssWidth`×`cssHeight` at the current pixel ratio. */
export function backingSize(cssWidth, cssHeight, devicePixels) {
  const ratio = window.devicePixelRatio || 1;
  let width = Math.round(cssWidth * ratio);
  let height = Math.round(cssHeight * ratio);
  // The exact device-pixel box avoids a blurry half pixel at fractional sizes; ignore it when it
  // disagrees with the ratio (emulated pixel ratios report CSS-sized device boxes).
  if (devicePixels && Math.abs(devicePixels.width - width) <= 1 && Math.abs(devicePixels.height - height) <= 1) {
    width = devicePixels.width;
    height = devicePixels.height;
  }
  const pixels = width * height;
  if (pixels > MAX_PIXELS) {
    const shrink = Math.sqrt(MAX_PIXELS / pixels);
    width = Math.floor(width * shrink);
    height = Math.floor(height * shrink);
  }
  return { width: Math.max(1, width), height: Math.max(1, height) };
}

/** The size the scene canvas should have right now (before the first ResizeObserver report). */
export function measure(canvas) {
  const rect = canvas.getBoundingClientRect();
  return backingSize(rect.width, rect.height, null);
}

/**
 * Calls `onSize({ width, height })` with the backing-store size `canvas` should have whenever its
 * CSS box (or the pixel ratio) changes, from the exact device-pixel box where the browser reports
 * one. Returns the observer (disconnect it when the canvas goes).
 */
export function observeSize(canvas, onSize) {
  const observer = new ResizeObserver((entries) => {
    const entry = entries[entries.length - 1];
    const device = entry.devicePixelContentBoxSize?.[0];
    const box = entry.contentBoxSize?.[0];
    const cssWidth = box ? box.inlineSize : entry.contentRect.width;
    const cssHeight = box ? box.blockSize : entry.contentRect.height;
    onSize(backingSize(cssWidth, cssHeight, device ? { width: device.inlineSize, height: device.blockSize } : null));
  });
  try {
    observer.observe(canvas, { box: 'device-pixel-content-box' });
  } catch {
    observer.observe(canvas);
  }
  return observer;
}

/**
 * Keeps both canvases' backing stores at CSS size × devicePixelRatio and tells the Sim, which
 * re-fits the scene (its `view()` transform changes with the size).
 */
export function setupView(app, canvas, overlay) {
  const apply = (size) => {
    if (app.crashed) return;
    // A print layout (the handout's full-width stage) must not resize the canvas: resizing clears
    // it, and core/print.js's still of what it showed stands in for it on paper.
    if (window.matchMedia?.('print').matches) return;
    if (canvas.width === size.width && canvas.height === size.height && app.sim.width() === size.width &&
        app.sim.height() === size.height) {
      return;
    }
    canvas.width = size.width;
    canvas.height = size.height;
    overlay.width = size.width;
    overlay.height = size.height;
    app.guard((sim) => sim.resize(size.width, size.height));
    app.dirty = true;
    app.dispatchEvent(new Event('resize'));
  };
  observeSize(canvas, apply);
  apply(measure(canvas));
}

/** The Sim's scene→canvas transform: canvas_px = scene_px × scale + offset. */
export function viewTransform(app) {
  const view = app.sim.view();
  return { scale: view[0], ox: view[1], oy: view[2] };
}

/** Scene coordinates of a pointer event's client position. */
export function clientToScene(app, canvas, clientX, clientY) {
  const rect = canvas.getBoundingClientRect();
  const px = ((clientX - rect.left) * canvas.width) / rect.width;
  const py = ((clientY - rect.top) * canvas.height) / rect.height;
  const { scale, ox, oy } = viewTransform(app);
  return [(px - ox) / scale, (py - oy) / scale];
}

/** Scene px per CSS px (turns a tolerance in screen px into scene units). */
export function sceneUnitsPerCssPixel(app, canvas) {
  const rect = canvas.getBoundingClientRect();
  const { scale } = viewTransform(app);
  return canvas.width / Math.max(1, rect.width) / scale;
}
