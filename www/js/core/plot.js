// The one chart drawer of the shell: line charts on a Canvas 2D for every page (the playground's
// metrics over time, the compare page's overlaid panes, the Tune page's fitness per generation,
// the lab's convergence curves on a log scale). The numbers come from the core; the pages only say
// which lines, ranges and ticks to draw. A non-finite value leaves a gap in its line.

import { backingSize } from './view.js';

const INK = '#5a6676';
const GRID = '#e4e2da';

/**
 * Draws `chart` into `canvas`, in CSS pixels:
 * - `lines`: `[{ xs, ys, color, width = 1.5, dots = false, name }]` (arrays or typed arrays);
 * - `x`: `{ min, max }`; `y`: `{ min, max, log = false }` (log: exponents of ten; values below
 *   10^min are drawn at the bottom);
 * - `margin`: `{ left, right, top, bottom }` around the plot area;
 * - `yTicks`: `[{ value, text }]`, a grid line each, labelled left of the area; `xTicks`: labels
 *   under it; `xLabel`: a caption under the middle of the x axis;
 * - `title`, `note`: one line each at the top left; `legend`: the lines' names over the area;
 * - `empty`: what to say when no line has a value (then nothing else is drawn);
 * - `background`: a fill colour (else the canvas is cleared); `fit` (default true): the backing
 *   store follows the CSS box × devicePixelRatio, false: drawn at the canvas's own size.
 */
export function drawPlot(canvas, chart) {
  const { lines = [], margin = {}, font = 11 } = chart;
  const { ctx, width, height } = prepare(canvas, chart.fit ?? true);
  if (chart.background) {
    ctx.fillStyle = chart.background;
    ctx.fillRect(0, 0, width, height);
  } else {
    ctx.clearRect(0, 0, width, height);
  }
  const left = margin.left ?? 0;
  const right = width - (margin.right ?? 0);
  const top = margin.top ?? 0;
  const bottom = height - (margin.bottom ?? 0);
  ctx.font = `${font}px system-ui, sans-serif`;
  ctx.fillStyle = INK;
  ctx.textAlign = 'left';
  ctx.textBaseline = 'top';
  if (chart.title) ctx.fillText(chart.title, 3, 1);
  const hasData = lines.some((line) => Array.prototype.some.call(line.ys, Number.isFinite));
  if (!hasData) {
    if (chart.empty) ctx.fillText(chart.empty, 3, top + 4);
    return;
  }
  if (chart.note) ctx.fillText(chart.note, 3, chart.title ? 12 : 1);

  const { x: xr, y: yr } = chart;
  const xSpan = xr.max - xr.min || 1;
  const x = (v) => left + ((v - xr.min) / xSpan) * (right - left);
  const scale = yr.log ? (v) => Math.log10(Math.max(v, 10 ** yr.min)) : (v) => v;
  const ySpan = yr.max - yr.min || 1;
  const y = (v) => bottom - ((scale(v) - yr.min) / ySpan) * (bottom - top);

  ctx.lineWidth = 1;
  ctx.strokeStyle = GRID;
  ctx.textAlign = 'right';
  ctx.textBaseline = 'middle';
  for (const tick of chart.yTicks ?? []) {
    const at = Math.round(y(tick.value)) + 0.5;
    ctx.beginPath();
    ctx.moveTo(left, at);
    ctx.lineTo(right, at);
    ctx.stroke();
    if (tick.text) ctx.fillText(tick.text, left - 4, at);
  }
  ctx.textAlign = 'center';
  ctx.textBaseline = 'top';
  // A label centred on its tick, but never cut at the canvas's edges.
  const centred = (text, at) => {
    const half = ctx.measureText(text).width / 2;
    return Math.min(Math.max(at, half + 1), width - half - 1);
  };
  for (const tick of chart.xTicks ?? []) ctx.fillText(tick.text, centred(tick.text, x(tick.value)), bottom + 6);
  if (chart.xLabel) ctx.fillText(chart.xLabel, (left + right) / 2, bottom + 6);

  for (const line of lines) {
    ctx.strokeStyle = line.color;
    ctx.fillStyle = line.color;
    ctx.lineWidth = line.width ?? 1.5;
    const n = Math.min(line.xs.length, line.ys.length);
    // More points than half-pixels only cost time: draw every k-th, and always the last.
    const stride = Math.max(1, Math.floor(n / (2 * Math.max(1, right - left))));
    ctx.beginPath();
    let pen = false;
    for (let i = 0; i < n; i += 1) {
      if (i % stride !== 0 && i !== n - 1) continue;
      const v = line.ys[i];
      if (!Number.isFinite(v)) {
        pen = false;
        continue;
      }
      if (pen) ctx.lineTo(x(line.xs[i]), y(v));
      else ctx.moveTo(x(line.xs[i]), y(v));
      pen = true;
    }
    ctx.stroke();
    if (line.dots) {
      for (let i = 0; i < n; i += 1) {
        if (!Number.isFinite(line.ys[i])) continue;
        ctx.beginPath();
        ctx.arc(x(line.xs[i]), y(line.ys[i]), 2.5, 0, 2 * Math.PI);
        ctx.fill();
      }
    }
  }

  if (chart.legend) {
    ctx.textAlign = 'left';
    ctx.textBaseline = 'alphabetic';
    let at = left + 8;
    for (const line of lines) {
      ctx.fillStyle = line.color;
      ctx.fillRect(at, top + 4, 14, 4);
      ctx.fillStyle = '#17202c';
      ctx.fillText(line.name, at + 18, top + 10);
      at += 30 + ctx.measureText(line.name).width;
    }
  }
}

/** The context drawing in CSS pixels, its backing store sized first when `fit`. */
function prepare(canvas, fit) {
  const ctx = canvas.getContext('2d');
  if (!fit) {
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    return { ctx, width: canvas.width, height: canvas.height };
  }
  const cssWidth = canvas.clientWidth || 150;
  const cssHeight = canvas.clientHeight || 60;
  const { width, height } = backingSize(cssWidth, cssHeight, null);
  if (canvas.width !== width || canvas.height !== height) {
    canvas.width = width;
    canvas.height = height;
  }
  ctx.setTransform(width / cssWidth, 0, 0, height / cssHeight, 0, 0);
  return { ctx, width: cssWidth, height: cssHeight };
}

/** A number short enough for an axis label (0, 1234, 12.3, 1.23, 0.012). */
export function formatTick(v) {
  const a = Math.abs(v);
  if (a === 0) return '0';
  if (a >= 1000) return v.toFixed(0);
  if (a >= 10) return v.toFixed(1);
  if (a >= 1) return v.toFixed(2);
  return v.toPrecision(2);
}
