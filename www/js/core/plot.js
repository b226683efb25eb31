// Small time-series plots on a Canvas 2D: one plot per metric, one line per group plus the whole
// run. The values come from the core's metrics history (`history_series`, Float32Array); this
// module only scales and strokes them. NaN values leave a gap.

/** Draws `lines` ([{ values: Float32Array, color, width }]) over `steps` (Uint32Array) into `canvas`. */
export function drawPlot(canvas, { steps, lines, label, unit }) {
  const ratio = window.devicePixelRatio || 1;
  const cssWidth = canvas.clientWidth || 150;
  const cssHeight = canvas.clientHeight || 60;
  const width = Math.round(cssWidth * ratio);
  const height = Math.round(cssHeight * ratio);
  if (canvas.width !== width || canvas.height !== height) {
    canvas.width = width;
    canvas.height = height;
  }
  const ctx = canvas.getContext('2d');
  ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
  ctx.fillStyle = '#ffffff';
  ctx.fillRect(0, 0, cssWidth, cssHeight);

  let lo = Infinity;
  let hi = -Infinity;
  for (const line of lines) {
    for (const v of line.values) {
      if (Number.isFinite(v)) {
        lo = Math.min(lo, v);
        hi = Math.max(hi, v);
      }
    }
  }
  const top = 24;
  const bottom = cssHeight - 3;
  ctx.font = '10px system-ui, sans-serif';
  ctx.fillStyle = '#5a6676';
  ctx.textBaseline = 'top';
  ctx.textAlign = 'left';
  ctx.fillText(label, 3, 1);
  if (!Number.isFinite(lo) || steps.length === 0) {
    ctx.fillText('no data yet', 3, top + 4);
    return;
  }
  // The scale (largest value shown) on a second line: labels and values never overlap.
  ctx.fillText(`max ${formatValue(hi)} ${unit}`.trim(), 3, 12);
  lo = Math.min(lo, 0);
  if (hi - lo < 1e-9) hi = lo + 1;

  const first = steps[0];
  const last = steps[steps.length - 1];
  const span = Math.max(1, last - first);
  const x = (s) => 2 + ((s - first) / span) * (cssWidth - 4);
  const y = (v) => bottom - ((v - lo) / (hi - lo)) * (bottom - top);

  ctx.strokeStyle = '#e4e2da';
  ctx.lineWidth = 1;
  ctx.beginPath();
  ctx.moveTo(0, Math.round(y(0)) + 0.5);
  ctx.lineTo(cssWidth, Math.round(y(0)) + 0.5);
  ctx.stroke();

  for (const line of lines) {
    ctx.strokeStyle = line.color;
    ctx.lineWidth = line.width ?? 1.5;
    ctx.beginPath();
    let pen = false;
    const n = Math.min(steps.length, line.values.length);
    for (let i = 0; i < n; i += 1) {
      const v = line.values[i];
      if (!Number.isFinite(v)) {
        pen = false;
        continue;
      }
      if (pen) ctx.lineTo(x(steps[i]), y(v));
      else ctx.moveTo(x(steps[i]), y(v));
      pen = true;
    }
    ctx.stroke();
  }
}

function formatValue(v) {
  const a = Math.abs(v);
  if (a === 0) return '0';
  if (a >= 1000) return v.toFixed(0);
  if (a >= 10) return v.toFixed(1);
  if (a >= 1) return v.toFixed(2);
  return v.toPrecision(2);
}
