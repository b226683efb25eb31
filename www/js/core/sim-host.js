// What every page that drives a wasm handle shares (the playground's App, the compare page,
// each <flock-path> element): the one guarded door to the handle, so a thrown error reaches the
// banner and a panic the crash panel (or, for an element, its own box), plus play/pause, stepping
// and reset.

import { isPanic, messageOf, showMessage, showPanic } from './errors.js';
import { t } from './i18n.js';
import { Pending, Restarted } from './sim-proxy.js';

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
   *
   * With a simulation in a worker (`this.remote`, core/sim-proxy.js) `fn` may call the worker: then
   * guard returns a Promise of the same result, settled once every call `fn` made was answered
   * (so the mirror shows their effect). A read still on its way from the worker (`Pending`) gives
   * `{ ok: false, pending: true }` without a message.
   */
  guard(fn, { rethrow = false } = {}) {
    if (this.crashed) {
      const error = new Error(t('panic.crashed_short'));
      if (rethrow) throw error;
      return { ok: false, error };
    }
    const fail = (thrown) => {
      if (thrown instanceof Pending) return { ok: false, pending: true, error: thrown };
      const message = messageOf(thrown);
      if (isPanic(thrown)) {
        this.crash(message);
      } else if (!(thrown instanceof Restarted)) {
        this.say.error(message);
      }
      if (rethrow) throw thrown instanceof Error ? thrown : new Error(message);
      return { ok: false, error: thrown };
    };
    const remote = this.remote ?? null;
    const outer = remote ? remote.collecting : null;
    const calls = [];
    if (remote) remote.collecting = calls;
    let value;
    try {
      value = fn(this.sim);
    } catch (thrown) {
      if (remote) remote.collecting = outer;
      // Calls made before the throw still settle; their refusals are not shown twice.
      for (const call of calls) call.catch(() => {});
      return fail(thrown);
    }
    if (remote) {
      remote.collecting = outer;
      outer?.push(...calls);
    }
    const thenable = value !== null && typeof value === 'object' && typeof value.then === 'function';
    if (!thenable && calls.length === 0) return { ok: true, value };
    // Every call settles before the result does; the first refusal is the result's error.
    return Promise.allSettled(calls).then(async (settled) => {
      const refused = settled.find((s) => s.status === 'rejected');
      let resolved;
      try {
        resolved = await value;
      } catch (thrown) {
        return fail(thrown);
      }
      if (refused) return fail(refused.reason);
      return { ok: true, value: resolved };
    });
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

  /**
   * Advances `n` steps now (paused stepping, the page API). With a worker: a Promise of the
   * result, settled once the steps ran.
   */
  stepNow(n, options = {}) {
    const result = this.guard((sim) => {
      const stepped = sim.step(n);
      return stepped?.then ? stepped.then(() => sim.steps()) : sim.steps();
    }, options);
    return after(result, () => {
      this.dirty = true;
      this.dispatchEvent(new Event('stepped'));
    });
  }

  /** Restarts the current scene from its seed (a Promise with a worker). */
  reset(options = {}) {
    const result = this.guard((sim) => sim.reset(), options);
    return after(result, () => {
      this.dirty = true;
      this.dispatchEvent(new Event('stepped'));
    });
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

/**
 * Runs `then(result)` once `result` is settled (at once for a plain result, after it for a
 * Promise) and returns the result, or the Promise of it: one path for handles in the page and in a
 * worker. A rejected Promise stays rejected (`then` does not run).
 */
export function after(result, then) {
  if (result !== null && typeof result?.then === 'function') {
    return result.then((settled) => {
      then(settled);
      return settled;
    });
  }
  then(result);
  return result;
}
