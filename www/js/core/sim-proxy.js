// The page's side of the simulation worker (core/sim-worker.js): a stand-in for the wasm `Sim`
// handle with the same method names. A read the page mirrors (steps, metrics, scene, … see
// core/sim-reads.js) answers at once from the state the last frame or reply brought; every other
// call goes to the worker and returns a Promise of its value. Frames arrive as RGBA pixels; the
// page draws the newest and acknowledges it, which lets the worker run the next frame.
//
// Stop always works: when the worker has not answered a pause for RESTART_AFTER_MS (it is inside
// one step that takes longer), it is ended and a new one starts from the scene the page knows, then
// replays the run to the step the page last showed (the same steps: the run is deterministic).

import { loadWasm } from './boot.js';
import { errorFromData } from './errors.js';
import { startModuleWorker } from './module-worker.js';
import { READS } from './sim-reads.js';

/** The simulation worker's module. */
export const WORKER_URL = new URL('./sim-worker.js', import.meta.url).href;

/** How long the worker may leave a pause unanswered before it is ended and restarted (ms). */
export const RESTART_AFTER_MS = 1000;
/** A subscribed read not read for this long is no longer sent with every frame (ms). */
const SUBSCRIPTION_TTL_MS = 2000;

/** Thrown by a subscribed read whose first value has not arrived yet (guard stays silent). */
export class Pending extends Error {
  constructor(method) {
    super(`${method} is on its way from the simulation worker`);
    this.name = 'Pending';
  }
}

/** The error of a call the worker never answered because it was restarted. */
export class Restarted extends Error {}

function unwrap(entry) {
  if (entry.ok) return entry.value;
  throw errorFromData(entry.error);
}

/** A panic in the worker, as the page's `isPanic` recognises it. */
function panicError(message) {
  return typeof WebAssembly !== 'undefined' ? new WebAssembly.RuntimeError(message) : new Error(message);
}

export class RemoteSim extends EventTarget {
  constructor() {
    super();
    this.worker = null;
    this.mirror = new Map();
    this.subscribed = new Map();
    /** key → { method, args, at } of the subscribed reads the page made. */
    this.wanted = new Map();
    /** Whether a message asking the worker for newly wanted reads is queued. */
    this.asking = false;
    this.calls = new Map();
    this.nextId = 1;
    this.controlSeq = 0;
    /** The newest frame not yet drawn, or null. */
    this.frame = null;
    /** performance.now() of the last message from the worker. */
    this.lastHeard = 0;
    this.startOptions = null;
    /** Set while guard() collects the Promises of the calls its function makes. */
    this.collecting = null;
    this.crashed = false;
    this.seeking = null;
    this.restarts = 0;
    this.playing = false;
    this.stepsPerFrame = 2;
    /** The handle's class in the worker and its read tables (core/sim-reads.js). */
    this.kind = 'Sim';
    this.reads = READS.Sim;
    /** The stand-in handle: `handle.metrics_json()`, `await handle.step(3)`, … */
    this.handle = new Proxy(
      {},
      {
        get: (_, name) => {
          if (typeof name !== 'string' || name === 'then') return undefined;
          return (...args) => this.invoke(name, args);
        },
      },
    );
  }

  /**
   * Starts the worker on `sceneText` (then the link's `linked` text, whose refusal comes back as
   * `linkError`) at `width`×`height`; resolves to `{ linkError }` once the first state arrived.
   * `kind: 'CompareSim'` starts the compare page's panes instead, from `sceneText` (else
   * `fallbackText`) and `specText`, and resolves to `{ sceneError, specError }`.
   */
  start(options) {
    const { kind = 'Sim', sceneText, linked = null, width, height, playing = false, stepsPerFrame = 2, theme = null, replayTo = 0 } = options;
    this.startOptions = { ...options, linked: null };
    this.kind = kind;
    this.reads = READS[kind];
    this.playing = playing;
    this.stepsPerFrame = stepsPerFrame;
    // From another origin (a <flock-path> on a course page) through a same-origin blob.
    this.worker = startModuleWorker(WORKER_URL);
    const worker = this.worker;
    const started = new Promise((resolve, reject) => {
      this.onStarted = resolve;
      this.onStartFailed = reject;
    });
    worker.onmessage = ({ data }) => {
      if (worker === this.worker) this.receive(data);
    };
    worker.onerror = (event) => {
      if (worker !== this.worker) return;
      event.preventDefault?.();
      this.onStartFailed?.(new Error(event.message || 'the simulation worker failed to start'));
    };
    // The page's compiled wasm goes along (a worker would otherwise download and compile its own).
    const post = (wasmModule) => {
      if (worker !== this.worker) return;
      worker.postMessage({ ...options, type: 'start', kind, sceneText, linked, width, height, playing, stepsPerFrame, theme, replayTo, wasmModule });
    };
    loadWasm().then(({ wasmModule }) => post(wasmModule), () => post(null));
    return started;
  }

  receive(data) {
    this.lastHeard = performance.now();
    if (data.state) this.absorb(data.state);
    switch (data.type) {
      case 'started': {
        const error = (key) => (data[key] ? errorFromData(data[key]) : null);
        this.onStarted?.({ linkError: error('linkError'), sceneError: error('sceneError'), specError: error('specError') });
        this.onStarted = null;
        this.onStartFailed = null;
        this.dispatchEvent(new Event('started'));
        break;
      }
      case 'start-failed':
        this.onStartFailed?.(errorFromData(data.error));
        break;
      case 'reply': {
        const call = this.calls.get(data.id);
        this.calls.delete(data.id);
        if (!call) break;
        if (data.ok) call.resolve(data.value);
        else call.reject(errorFromData(data.error));
        break;
      }
      case 'frame':
        this.frame = data;
        this.dispatchEvent(new Event('frame'));
        break;
      case 'control-ack':
        this.dispatchEvent(new CustomEvent('control-ack', { detail: data }));
        break;
      case 'refused':
        this.dispatchEvent(new CustomEvent('refused', { detail: errorFromData(data.error) }));
        break;
      case 'panic':
        this.crashed = true;
        for (const call of this.calls.values()) call.reject(panicError(data.message));
        this.calls.clear();
        this.dispatchEvent(new CustomEvent('panic', { detail: panicError(data.message) }));
        break;
      default:
        break;
    }
  }

  absorb({ values, subscribed, seeking = null }) {
    for (const [method, entry] of Object.entries(values)) this.mirror.set(method, entry);
    /** A timeline jump in progress (`{ step, at, done, total }`: re-simulated in slices), or null. */
    this.seeking = seeking;
    if (subscribed) for (const [key, entry] of Object.entries(subscribed)) this.subscribed.set(key, entry);
  }

  invoke(method, args) {
    if (this.reads.mirrored.has(method) && args.length === 0) {
      const entry = this.mirror.get(method);
      if (!entry) throw new Pending(method);
      return unwrap(entry);
    }
    if (this.reads.subscribable.has(method)) {
      const key = `${method}|${JSON.stringify(args)}`;
      const fresh = !this.wanted.has(key);
      this.wanted.set(key, { method, args, at: performance.now() });
      // A new read asks the worker once for all reads asked in this task (one message, not one
      // per read: a panel may ask for hundreds at once).
      if (fresh && !this.asking) {
        this.asking = true;
        queueMicrotask(() => {
          this.asking = false;
          this.control({ render: true });
        });
      }
      const entry = this.subscribed.get(key);
      if (!entry) throw new Pending(method);
      return unwrap(entry);
    }
    return this.call(method, args);
  }

  /** Sends one call to the worker; resolves to its value (rejects with the refusal). */
  call(method, args = []) {
    if (this.crashed) return Promise.reject(panicError('the simulation has crashed'));
    const id = this.nextId;
    this.nextId += 1;
    const promise = new Promise((resolve, reject) => {
      this.calls.set(id, { resolve, reject, method });
    });
    this.worker.postMessage({ type: 'call', id, method, args });
    this.collecting?.push(promise);
    return promise;
  }

  /** The subscribed reads still wanted, for the worker (older ones are dropped). */
  subscriptions() {
    const now = performance.now();
    const list = [];
    for (const [key, want] of this.wanted) {
      if (now - want.at > SUBSCRIPTION_TTL_MS) {
        this.wanted.delete(key);
        this.subscribed.delete(key);
      } else {
        list.push([want.method, want.args]);
      }
    }
    return list;
  }

  /**
   * Tells the worker to play or pause, the steps per frame, or to render again (a view change);
   * returns the message's sequence number (the worker's `control-ack` echoes it).
   */
  control(changes) {
    if (!this.worker) return 0;
    if ('playing' in changes) this.playing = changes.playing;
    if ('stepsPerFrame' in changes) this.stepsPerFrame = changes.stepsPerFrame;
    this.controlSeq += 1;
    this.worker.postMessage({ type: 'control', seq: this.controlSeq, subscriptions: this.subscriptions(), ...changes });
    return this.controlSeq;
  }

  /** Takes the newest frame (null when none arrived since the last take). */
  takeFrame() {
    const frame = this.frame;
    this.frame = null;
    return frame;
  }

  /**
   * Lets the worker run its next frame (called once the page has drawn the last one); the drawn
   * frame's pixel `buffers` go back to the worker, which fills them again instead of allocating.
   */
  ack(buffers = []) {
    this.worker?.postMessage(
      { type: 'ack', subscriptions: this.subscriptions(), stepsPerFrame: this.stepsPerFrame, buffers },
      buffers,
    );
  }

  /** Whether calls are waiting for the worker's answer. */
  busy() {
    return this.calls.size > 0;
  }

  /**
   * Ends a worker stuck in a step and starts a new one from the scene the page last saw, which
   * replays the run to the step the page last showed. Calls in flight reject with `Restarted`.
   * Resolves to the step it replays to.
   */
  restart(reason) {
    const known = (method, fallback) => this.mirror.get(method)?.value ?? fallback;
    const sceneText = known('scene_json', this.startOptions.sceneText);
    const replayTo = known('steps', 0);
    const theme = known('theme', this.startOptions.theme);
    const width = known('width', this.startOptions.width);
    const height = known('height', this.startOptions.height);
    // A compare page's panes: the same scene with the same comparison.
    const compare = { fallbackText: sceneText, specText: known('spec_string', this.startOptions.specText) };
    this.worker.terminate();
    this.worker = null;
    for (const call of this.calls.values()) call.reject(new Restarted(reason));
    this.calls.clear();
    this.frame = null;
    this.restarts += 1;
    this.start({ ...this.startOptions, ...compare, sceneText, width, height, playing: false, stepsPerFrame: this.stepsPerFrame, theme, replayTo }).catch(
      (error) => this.dispatchEvent(new CustomEvent('panic', { detail: error })),
    );
    return replayTo;
  }
}
