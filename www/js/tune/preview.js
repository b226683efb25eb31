// The Tune page's preview: a `Sim` on the page's own wasm instance runs the scene with the best
// weights so far and replays it from the start after the evaluation's frame count. It counts
// painted frames so tests can see the page keeps animating while the worker computes. Paused
// (`playing` false: a reader who asked for less motion starts so), it paints each new scene's
// first frame once and does not step.

import { blitSim } from '../core/blit.js';
import { backingSize } from '../core/view.js';

/** Simulation steps per animation frame: an evaluation (400 steps) replays in about 3 s. */
const STEPS_PER_FRAME = 2;

export class Preview {
  /**
   * @param {object} module the wasm bindings (for `Sim`)
   * @param {object} wasm   the instance exports (for `memory`)
   * @param {HTMLCanvasElement} canvas
   */
  constructor(module, wasm, canvas) {
    this.module = module;
    this.wasm = wasm;
    this.canvas = canvas;
    this.ctx = canvas.getContext('2d', { alpha: false });
    this.sim = null;
    this.sceneString = null;
    this.frames = 400;
    /** Whether the replay advances; when false only a new scene or a resize repaints. */
    this.playing = true;
    this.stale = true;
    /** Animation frames painted so far. */
    this.painted = 0;
    this.resize();
    new ResizeObserver(() => this.resize()).observe(canvas);
    /** Called once with the error when the preview fails (it stops; the tuning goes on). */
    this.onError = () => {};
    const frame = () => {
      try {
        this.tick();
      } catch (error) {
        this.sim = null;
        this.onError(error);
      }
      requestAnimationFrame(frame);
    };
    requestAnimationFrame(frame);
  }

  /** Shows `sceneString` (a fragment value), replayed every `frames` steps; throws if it is bad. */
  show(sceneString, frames = this.frames) {
    this.frames = Math.max(1, frames);
    if (sceneString === this.sceneString) return;
    const sim = new this.module.Sim(sceneString, this.canvas.width, this.canvas.height);
    this.sim?.free();
    this.sim = sim;
    this.sceneString = sceneString;
    this.stale = true;
  }

  /** Plays or pauses the replay. */
  setPlaying(playing) {
    this.playing = playing;
  }

  resize() {
    const rect = this.canvas.getBoundingClientRect();
    const { width, height } = backingSize(rect.width, rect.height, null);
    if (this.canvas.width === width && this.canvas.height === height) return;
    this.canvas.width = width;
    this.canvas.height = height;
    this.sim?.resize(width, height);
    this.stale = true;
  }

  tick() {
    if (this.sim === null || (!this.playing && !this.stale)) return;
    this.stale = false;
    if (this.playing) {
      if (this.sim.steps() >= this.frames) this.sim.reset();
      this.sim.step(STEPS_PER_FRAME);
    }
    this.sim.render();
    blitSim(this.ctx, this.wasm, this.sim);
    this.painted += 1;
  }

  /** Steps of the current replay. */
  steps() {
    return this.sim?.steps() ?? 0;
  }
}
