// What every page that drives a wasm handle shares (the playground's App, the compare page,
// each <flock-path> element): the one guarded door to the handle, so a thrown error reaches the
// banner and a panic the crash panel (or, for an element, its own box), plus play/pause, stepping
// and reset.

import { isPanic, messageOf, showMessage, showPanic } from './errors.js';
import { t } from './i18n.js';

export class SimHost extends EventTarget {
  /**
   * @param {object} wasm   the instance exports returned by `init()` (for `memory`)
   * @param {object} module the JS bindings (`presets_json`, `planners_json`, …)
   * @param {object} sim    the wasm handle
   * @param {object} [say]  where messages go: `error(message)` for a refused call (the banner by
   *   default) and `panic(message)` for a crash (the crash panel by default)
   */
  constructor(wasm, module, sim, say = {}) {
    super();
    this.say = { error: say.error ?? ((message) => showMessage(message)), panic: say.panic ?? showPanic };
    this.wasm = wasm;
    this.module = module;
    this.sim = sim;
    this.presets = JSON.parse(module.presets_json());
    this.planners = JSON.parse(module.planners_json());
    this.playing = true;
    this.stepsPerFrame = 2;
    /** Set when the canvas must be re-rendered even though the simulation is paused. */
    this.dirty = true;
    this.crashed = false;
  }

  /**
   * Runs `fn(sim)`; a thrown error shows in the banner (or the crash panel for a panic) and the
   * current run keeps going. Returns `{ ok, value, error }`; with `rethrow` the error is thrown
   * again as a plain `Error` carrying the readable message (for the page API).
   */
  guard(fn, { rethrow = false } = {}) {
    if (this.crashed) {
      const error = new Error(t('panic.crashed_short'));
      if (rethrow) throw error;
      return { ok: false, error };
    }
    try {
      return { ok: true, value: fn(this.sim) };
    } catch (thrown) {
      const message = messageOf(thrown);
      if (isPanic(thrown)) {
        this.crash(message);
      } else {
        this.say.error(message);
      }
      if (rethrow) throw thrown instanceof Error ? thrown : new Error(message);
      return { ok: false, error: thrown };
    }
  }

  /** Stops everything and shows the crash panel. */
  crash(message) {
    if (this.crashed) return;
    this.crashed = true;
    this.setPlaying(false);
    this.say.panic(message);
    this.dispatchEvent(new Event('crash'));
  }

  /** Play or pause the frame loop's stepping. */
  setPlaying(playing) {
    this.playing = playing;
    this.dispatchEvent(new Event('playing'));
  }

  /** Advances `n` steps now (paused stepping, the page API). */
  stepNow(n, options = {}) {
    const result = this.guard((sim) => {
      sim.step(n);
      return sim.steps();
    }, options);
    this.dirty = true;
    this.dispatchEvent(new Event('stepped'));
    return result;
  }

  /** Restarts the current scene from its seed. */
  reset(options = {}) {
    const result = this.guard((sim) => sim.reset(), options);
    this.dirty = true;
    this.dispatchEvent(new Event('stepped'));
    return result;
  }

  /**
   * Crashes on a panic that escapes every guard (an event handler, a promise): after a panic the
   * wasm instance must not be called again. For pages; an element's calls all go through `guard`.
   */
  watchPanics() {
    window.addEventListener('unhandledrejection', (e) => {
      if (isPanic(e.reason)) this.crash(messageOf(e.reason));
    });
    window.addEventListener('error', (e) => {
      if (isPanic(e.error)) this.crash(messageOf(e.error));
    });
  }
}
