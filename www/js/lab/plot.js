// The lab's convergence plot: best-so-far against iteration on a log scale, one line per run,
// drawn with the canvas 2-D API (a chart of numbers the core computed; no scoring here).

/** Line colour per algorithm name. */
export const ALGORITHM_COLORS = { gsa: '#d9480f', igsa: '#1c7ed6', pso: '#2b8a3e', firefly: '#ae3ec9', ga: '#5c5f66' };

/**
 * Draws `series` (`[{ name, curve: Float64Array|number[], budget }]`) on `canvas`. Values ≤ 0
 * are drawn at the smallest positive value shown (the log of 0 does not exist).
 */
export function drawPlot(canvas, series) {
  const ctx = canvas.getContext('2d');
  const { width, height } = canvas;
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  ctx.fillStyle = '#ffffff';
  ctx.fillRect(0, 0, width, height);
  const left = 58;
  const bottom = 26;
  const right = 10;
  const top = 10;
  const values = series.flatMap((s) => Array.from(s.curve).filter((v) => v > 0 && Number.isFinite(v)));
  if (!values.length) return;
  let lo = Math.floor(Math.log10(Math.min(...values)));
  let hi = Math.ceil(Math.log10(Math.max(...values)));
  if (hi <= lo) hi = lo + 1;
  lo = Math.max(lo, hi - 40);
  const budget = Math.max(1, ...series.map((s) => s.budget));
  const x = (i) => left + (i / budget) * (width - left - right);
  const y = (v) => {
    const l = Math.log10(Math.max(v, 10 ** lo));
    return top + ((hi - l) / (hi - lo)) * (height - top - bottom);
  };
  ctx.strokeStyle = '#e3e6ea';
  ctx.fillStyle = '#5a6676';
  ctx.font = '11px system-ui, sans-serif';
  ctx.lineWidth = 1;
  const stride = Math.max(1, Math.ceil((hi - lo) / 8));
  for (let e = lo; e <= hi; e += stride) {
    ctx.beginPath();
    ctx.moveTo(left, y(10 ** e));
    ctx.lineTo(width - right, y(10 ** e));
    ctx.stroke();
    ctx.fillText(`1e${e}`, 6, y(10 ** e) + 4);
  }
  ctx.fillText('0', left - 3, height - 8);
  ctx.fillText(String(budget), width - right - 30, height - 8);
  ctx.fillText('iteration', (width - left) / 2, height - 8);
  for (const s of series) {
    ctx.strokeStyle = ALGORITHM_COLORS[s.name] ?? '#000000';
    ctx.lineWidth = s.primary ? 2.5 : 1.5;
    ctx.beginPath();
    const curve = s.curve;
    const step = Math.max(1, Math.floor(curve.length / (width * 2)));
    for (let i = 0; i < curve.length; i += step) {
      if (i === 0) ctx.moveTo(x(i), y(curve[i]));
      else ctx.lineTo(x(i), y(curve[i]));
    }
    ctx.lineTo(x(curve.length - 1), y(curve[curve.length - 1]));
    ctx.stroke();
  }
  let legend = left + 8;
  for (const s of series) {
    ctx.fillStyle = ALGORITHM_COLORS[s.name] ?? '#000000';
    ctx.fillRect(legend, top + 4, 14, 4);
    ctx.fillStyle = '#17202c';
    ctx.fillText(s.name, legend + 18, top + 10);
    legend += 30 + ctx.measureText(s.name).width;
  }
}
