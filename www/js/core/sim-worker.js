// The simulation's own thread: this worker owns the wasm `Sim` handle, steps it and renders it, so
// a scene whose step takes seconds never blocks the page's clicks, keys or drawing (issue 24).
// The page (core/sim-proxy.js) sends `call` requests ({id, method, args}) and gets one reply each,
// in order; while playing, the worker steps, renders and posts a frame (the RGBA pixels as a
// transferred ArrayBuffer, no copy on the page's side), then waits for the page to acknowledge
// it, so it never runs more than one frame ahead of what the page shows. Every reply and frame
// carries the handle's readable state (steps, metrics, scene, …: the page's synchronous mirror);
// the worker computes nothing the core does not: it only calls the handle and forwards the results.
// No SharedArrayBuffer: it works from any static server and inside a cross-origin iframe.

import { loadWasm } from './boot.js';
import { errorData, isPanic, messageOf } from './errors.js';
import { FRAME_READS, PURE_READS, SCENE_READS, SCENE_KEEPING } from './sim-reads.js';

/** Simulation work per frame (ms) before the frame is shown: the frame rate of a playing scene. */
const STEP_BUDGET_MS = 10;
/** Time given to planning ahead (IGSA) per frame (ms). */
const PLANNING_BUDGET_MS = 24;

let module = null;
let wasm = null;
let sim = null;
let crashed = false;
let playing = false;
let stepsPerFrame = 2;
/** Steps to reach without playing (a restarted worker replaying the run the page had). */
let replayTo = 0;
let awaitingAck = false;
let dirty = true;
let sceneChanged = true;
/** Reads with arguments the page asked for lately (`[method, args]`), e.g. a plot's series. */
let subscriptions = [];
/** The pixel buffer of a frame the page has drawn, handed back for the next frame (or null). */
let spare = null;

// The next frame's work runs in a task of its own, after any request already queued.
const tickChannel = new MessageChannel();
let tickQueued = false;
tickChannel.port1.onmessage = () => {
  tickQueued = false;
  tick();
};
function schedule() {
  if (tickQueued || crashed || !sim) return;
  tickQueued = true;
  tickChannel.port2.postMessage(null);
}

/** `{ ok, value }` or `{ ok: false, error }` for one read. */
function read(method, args = []) {
  try {
    return { ok: true, value: sim[method](...args) };
  } catch (error) {
    if (isPanic(error)) throw error;
    return { ok: false, error: errorData(error) };
  }
}

/** The readable state for the page's mirror: every frame's reads, the scene's when it changed. */
function snapshot() {
  const values = {};
  for (const method of FRAME_READS) values[method] = read(method);
  if (sceneChanged) {
    for (const method of SCENE_READS) values[method] = read(method);
    sceneChanged = false;
  }
  const subscribed = {};
  for (const [method, args] of subscriptions) {
    if (PURE_READS.has(method)) subscribed[`${method}|${JSON.stringify(args)}`] = read(method, args);
  }
  return { values, subscribed };
}

function fail(error) {
  if (isPanic(error)) {
    crashed = true;
    self.postMessage({ type: 'panic', message: messageOf(error) });
    return true;
  }
  return false;
}

function postFrame(extra) {
  sim.render();
  const len = sim.frame_len();
  const frame = new Uint8ClampedArray(wasm.memory.buffer, sim.frame_ptr(), len);
  // One copy out of wasm memory per frame, into the buffer the page gave back when it fits.
  let pixels;
  if (spare !== null && spare.byteLength === len) {
    pixels = new Uint8ClampedArray(spare);
    pixels.set(frame);
  } else {
    pixels = frame.slice();
  }
  spare = null;
  awaitingAck = true;
  dirty = false;
  self.postMessage(
    { type: 'frame', pixels: pixels.buffer, width: sim.width(), height: sim.height(), state: snapshot(), ...extra },
    [pixels.buffer],
  );
}

/** One frame: plan or step (while playing or replaying), then render and post it. */
function tick() {
  if (!sim || crashed || awaitingAck) return;
  try {
    let asked = 0;
    let done = 0;
    let stepMs = null;
    let planning = false;
    const replaying = !playing && sim.steps() < replayTo;
    if (sim.planning_progress() < 1) {
      // Planning runs whether or not the scene plays (the page shows its progress and Cancel).
      planning = true;
      const end = performance.now() + PLANNING_BUDGET_MS;
      let progress;
      do {
        progress = sim.advance_planning(1);
      } while (progress < 1 && performance.now() < end);
      dirty = true;
    } else if (playing || replaying) {
      asked = replaying ? 1 : stepsPerFrame;
      const start = performance.now();
      while (done < asked) {
        const before = performance.now();
        sim.step(1);
        done += 1;
        const after = performance.now();
        stepMs = after - before;
        if (after - start + stepMs > STEP_BUDGET_MS) break;
      }
      dirty = true;
    }
    if (dirty) postFrame({ asked, done, stepMs, planning, replaying, replayTo });
    else if (planning || playing || replaying) schedule();
  } catch (error) {
    if (!fail(error)) {
      // A refused step (not a panic) would repeat every frame: stop and let the page explain.
      playing = false;
      self.postMessage({ type: 'refused', error: errorData(error) });
    }
  }
}

async function start({ sceneText, linked, width, height, theme }) {
  ({ module, wasm } = await loadWasm());
  sim = new module.Sim(sceneText, width, height);
  let linkError = null;
  if (linked !== null && linked !== undefined) {
    try {
      sim.load(linked);
    } catch (error) {
      if (isPanic(error)) throw error;
      linkError = errorData(error);
    }
  }
  if (theme) sim.set_theme(theme);
  // The first state read (the view transform) follows a render, as every later one does.
  sim.render();
  sceneChanged = true;
  dirty = true;
  return { linkError };
}

function answer(id, method, args) {
  if (crashed) return;
  let reply;
  try {
    if (typeof sim?.[method] !== 'function' || method === 'free') throw new Error(`no such call: ${method}`);
    const value = sim[method](...args);
    if (!PURE_READS.has(method)) {
      dirty = true;
      if (!SCENE_KEEPING.has(method)) sceneChanged = true;
      // The view transform is fitted when a frame is rendered: render before the state is read.
      sim.render();
    }
    reply = { type: 'reply', id, ok: true, value: clonable(value), state: snapshot() };
  } catch (error) {
    if (fail(error)) return;
    reply = { type: 'reply', id, ok: false, error: errorData(error), state: snapshot() };
  }
  self.postMessage(reply);
  schedule();
}

/** A value the page can receive (wasm-bindgen returns strings, numbers, typed arrays, undefined). */
function clonable(value) {
  return value === undefined ? null : value;
}

self.onmessage = async ({ data }) => {
  switch (data.type) {
    case 'start':
      try {
        playing = Boolean(data.playing);
        stepsPerFrame = data.stepsPerFrame ?? stepsPerFrame;
        replayTo = data.replayTo ?? 0;
        const { linkError } = await start(data);
        self.postMessage({ type: 'started', linkError, state: snapshot() });
        schedule();
      } catch (error) {
        if (!fail(error)) self.postMessage({ type: 'start-failed', error: errorData(error) });
      }
      break;
    case 'call':
      answer(data.id, data.method, data.args);
      break;
    case 'control':
      if ('playing' in data) playing = Boolean(data.playing);
      if ('stepsPerFrame' in data) stepsPerFrame = data.stepsPerFrame;
      if ('replayTo' in data) replayTo = data.replayTo;
      if (data.render) dirty = true;
      // Sent before any frame the page asks for: every control is answered, so the page knows the
      // worker is not stuck in a step.
      self.postMessage({ type: 'control-ack', seq: data.seq, playing });
      schedule();
      break;
    case 'ack':
      awaitingAck = false;
      if (data.pixels) spare = data.pixels;
      if (data.subscriptions) subscriptions = data.subscriptions;
      if ('stepsPerFrame' in data) stepsPerFrame = data.stepsPerFrame;
      if (data.render) dirty = true;
      schedule();
      break;
    default:
      break;
  }
};
