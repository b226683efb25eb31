// The live plot of the Tune page: best and mean Gsum per generation (drawn by core/plot.js). It
// only keeps and shows the numbers the worker reports.

import { drawPlot } from '../core/plot.js';

const BEST = '#2f6fdf';
const MEAN = '#df9f1f';

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
    const values = this.points.flatMap((p) => [p.best, p.mean]);
    // Gsum is a score out of 100; zoom on the range reached, in steps of 10.
    const lo = values.length ? Math.max(0, Math.floor(Math.min(...values) / 10) * 10) : 0;
    const hi = values.length ? Math.min(100, Math.max(lo + 10, Math.ceil(Math.max(...values) / 10) * 10)) : 100;
    const yTicks = [];
    for (let v = lo; v <= hi; v += 10) yTicks.push({ value: v, text: String(v) });
    const xTicks = [];
    const step = Math.max(1, Math.ceil(this.maxGenerations / 10));
    // Generations are counted from 1 on this page, as in its status line and preview.
    for (let g = 1; g <= this.maxGenerations; g += step) xTicks.push({ value: g, text: String(g) });
    const generations = this.points.map((p) => p.generation + 1);
    drawPlot(this.canvas, {
      lines: [
        { xs: generations, ys: this.points.map((p) => p.mean), color: MEAN, width: 2, dots: true },
        { xs: generations, ys: this.points.map((p) => p.best), color: BEST, width: 2, dots: true },
      ],
      x: { min: 1, max: Math.max(2, this.maxGenerations) },
      y: { min: lo, max: hi },
      margin: { left: 36, right: 8, top: 8, bottom: 22 },
      yTicks,
      xTicks,
    });
    this.canvas.dataset.points = String(this.points.length);
    // The generations the axis spans and the last one drawn, as the page counts them (from 1).
    this.canvas.dataset.axis = `${xTicks[0]?.value ?? 1}–${Math.max(2, this.maxGenerations)}`;
    this.canvas.dataset.last = String(generations.at(-1) ?? '');
  }
}
