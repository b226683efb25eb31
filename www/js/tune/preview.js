// The Tune page's preview: a `Sim` in a worker of its own (core/sim-worker.js, through
// core/sim-proxy.js) runs the scene with the best weights so far and replays it from the start
// after the evaluation's frame count, so a costly scene never blocks the page. It counts painted
// frames so tests can see the page keeps animating while the GA worker computes. Paused
// (`playing` false: a reader who asked for less motion starts so), it paints each new scene's
// first frame once and does not step.

import { errorFromData } from '../core/errors.js';
import { RemoteSim } from '../core/sim-proxy.js';
import { backingSize } from '../core/view.js';

/** Simulation steps per animation frame: an evaluation (400 steps) replays in about 3 s. */
const STEPS_PER_FRAME = 2;

export class Preview {
  /**
   * @param {object} module the wasm bindings (unused: the worker loads its own)
   * @param {object} wasm   the instance exports (unused: frames arrive as pixels)
   * @param {HTMLCanvasElement} canvas
   */
  constructor(module, wasm, canvas) {
    this.canvas = canvas;
    this.ctx = canvas.getContext('2d', { alpha: false });
    this.remote = null;
    this.sceneString = null;
    this.frames = 400;
    /** Whether the replay advances; when false only a new scene or a resize repaints. */
    this.playing = true;
    /** Animation frames painted so far. */
    this.painted = 0;
    /** A replay restart asked of the worker and not answered yet. */
    this.restarting = false;
    this.resize();
    new ResizeObserver(() => this.resize()).observe(canvas);
    /** Called once with the error when the preview fails (it stops; the tuning goes on). */
    this.onError = () => {};
    const frame = () => {
      this.tick();
      requestAnimationFrame(frame);
    };
    requestAnimationFrame(frame);
  }

  /** Stops the preview after a failure in the worker and says why. */
  stop(error) {
    this.remote?.worker?.terminate();
    this.remote = null;
    this.onError(error);
  }

  /**
   * Shows `sceneString` (a fragment value), replayed every `frames` steps. Resolves once it
   * shows; rejects (and keeps the scene shown) when the scene is refused.
   */
  show(sceneString, frames = this.frames) {
    this.frames = Math.max(1, frames);
    if (sceneString === this.sceneString) return Promise.resolve();
    this.sceneString = sceneString;
    if (this.remote === null) {
      const remote = new RemoteSim();
      this.remote = remote;
      remote.addEventListener('panic', (event) => this.stop(event.detail));
      remote.addEventListener('refused', (event) => this.stop(event.detail));
      return remote
        .start({
          sceneText: sceneString,
          width: this.canvas.width,
          height: this.canvas.height,
          playing: this.playing,
          stepsPerFrame: STEPS_PER_FRAME,
        })
        .catch((error) => {
          if (this.remote === remote) this.remote = null;
          this.sceneString = null;
          throw error instanceof Error ? error : errorFromData(error);
        });
    }
    return this.remote.call('load', [sceneString]).catch((error) => {
      this.sceneString = null;
      throw error;
    });
  }

  /** Plays or pauses the replay. */
  setPlaying(playing) {
    this.playing = playing;
    this.remote?.control({ playing });
  }

  resize() {
    const rect = this.canvas.getBoundingClientRect();
    const { width, height } = backingSize(rect.width, rect.height, null);
    if (this.canvas.width === width && this.canvas.height === height) return;
    this.canvas.width = width;
    this.canvas.height = height;
    this.remote?.call('resize', [width, height]).catch(() => {});
  }

  tick() {
    const remote = this.remote;
    if (remote === null) return;
    // The replay starts again after the evaluation's frame count.
    if (this.playing && !this.restarting && this.steps() >= this.frames) {
      this.restarting = true;
      remote
        .call('reset')
        .catch(() => {})
        .finally(() => {
          this.restarting = false;
        });
    }
    const frame = remote.takeFrame();
    if (!frame) return;
    if (frame.width === this.canvas.width && frame.height === this.canvas.height) {
      this.ctx.putImageData(new ImageData(new Uint8ClampedArray(frame.pixels), frame.width, frame.height), 0, 0);
      this.painted += 1;
    }
    remote.ack(frame.panes);
  }

  /** Steps of the current replay. */
  steps() {
    return this.remote?.mirror.get('steps')?.value ?? 0;
  }
}
