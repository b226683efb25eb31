// The live plot of the Tune page: best and mean Gsum per generation on a 2D canvas. It only draws
// the numbers the worker reports.

const BEST = '#2f6fdf';
const MEAN = '#df9f1f';
const AXIS = '#5a6676';
const GRID = '#e3e8ee';

export class FitnessPlot {
  /** @param {HTMLCanvasElement} canvas */
  constructor(canvas) {
    this.canvas = canvas;
    this.points = [];
    this.maxGenerations = 1;
    new ResizeObserver(() => this.draw()).observe(canvas);
  }

  /** Forgets the points; the x axis spans `maxGenerations`. */
  reset(maxGenerations) {
    this.points = [];
    this.maxGenerations = Math.max(1, maxGenerations);
    this.draw();
  }

  /** Adds one generation's `{generation, best_gsum, mean_gsum}` and redraws. */
  add(stats) {
    this.points.push({ generation: stats.generation, best: stats.best_gsum, mean: stats.mean_gsum });
    this.draw();
  }

  draw() {
    const canvas = this.canvas;
    const ratio = window.devicePixelRatio || 1;
    const width = Math.max(1, Math.round(canvas.clientWidth * ratio));
    const height = Math.max(1, Math.round(canvas.clientHeight * ratio));
    if (canvas.width !== width || canvas.height !== height) {
      canvas.width = width;
      canvas.height = height;
    }
    const ctx = canvas.getContext('2d');
    ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    const w = width / ratio;
    const h = height / ratio;
    ctx.clearRect(0, 0, w, h);
    const left = 36;
    const right = 8;
    const top = 8;
    const bottom = 22;
    const values = this.points.flatMap((p) => [p.best, p.mean]);
    // Gsum is a score out of 100; zoom on the range reached, in steps of 10.
    const lo = values.length ? Math.max(0, Math.floor(Math.min(...values) / 10) * 10) : 0;
    const hi = values.length ? Math.min(100, Math.max(lo + 10, Math.ceil(Math.max(...values) / 10) * 10)) : 100;
    const x = (g) => left + ((w - left - right) * g) / Math.max(1, this.maxGenerations - 1);
    const y = (v) => h - bottom - ((h - top - bottom) * (v - lo)) / (hi - lo);

    ctx.font = '11px system-ui, sans-serif';
    ctx.fillStyle = AXIS;
    ctx.strokeStyle = GRID;
    ctx.lineWidth = 1;
    ctx.textAlign = 'right';
    ctx.textBaseline = 'middle';
    for (let v = lo; v <= hi; v += 10) {
      ctx.beginPath();
      ctx.moveTo(left, y(v));
      ctx.lineTo(w - right, y(v));
      ctx.stroke();
      ctx.fillText(String(v), left - 4, y(v));
    }
    ctx.textAlign = 'center';
    ctx.textBaseline = 'top';
    const step = Math.max(1, Math.ceil(this.maxGenerations / 10));
    for (let g = 0; g < this.maxGenerations; g += step) ctx.fillText(String(g), x(g), h - bottom + 6);

    for (const [key, colour] of [['mean', MEAN], ['best', BEST]]) {
      ctx.strokeStyle = colour;
      ctx.fillStyle = colour;
      ctx.lineWidth = 2;
      ctx.beginPath();
      this.points.forEach((p, i) => (i === 0 ? ctx.moveTo(x(p.generation), y(p[key])) : ctx.lineTo(x(p.generation), y(p[key]))));
      ctx.stroke();
      for (const p of this.points) {
        ctx.beginPath();
        ctx.arc(x(p.generation), y(p[key]), 2.5, 0, 2 * Math.PI);
        ctx.fill();
      }
    }
    canvas.dataset.points = String(this.points.length);
  }
}
