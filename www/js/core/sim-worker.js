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
import { STEP_BUDGET_MS } from './pace.js';
import { PlanningBudget } from './planning-slice.js';
import { READS } from './sim-reads.js';

/**
 * Time a timeline jump may re-simulate before the worker shows its progress and reads its
 * messages (ms): a short jump (tens of steps of a small crowd) ends in one slice, answered at
 * once; a jump through steps of a second shows each step.
 */
const SEEK_BUDGET_MS = 100;
/** Time given to planning ahead (IGSA) per frame (ms). */
const PLANNING_BUDGET_MS = 24;
/** Time between frames while planning ahead (ms): the progress bar's refresh. */
const PLANNING_FRAME_MS = 100;

let module = null;
let wasm = null;
let sim = null;
/** The handle's class (`Sim` or `CompareSim`) and its read tables (core/sim-reads.js). */
let kind = 'Sim';
let reads = READS.Sim;
let crashed = false;
let playing = false;
let stepsPerFrame = 2;
/** Slow motion (stepsPerFrame < 1): the share of a step the frames so far have earned. */
let slowCredit = 0;
/** Steps to reach without playing (a restarted worker replaying the run the page had). */
let replayTo = 0;
/** Evaluations per planning call, adapted to the scene's cost (core/planning-slice.js). */
const planningBudget = new PlanningBudget();
/** When the last frame while planning was posted (performance.now()). */
let lastPlanningFrame = 0;
let awaitingAck = false;
let dirty = true;
let sceneChanged = true;
/** Reads with arguments the page asked for lately (`[method, args]`), e.g. a plot's series. */
let subscriptions = [];
/** The pixel buffers of a frame the page has drawn, handed back for the next frame. */
let spare = [];
/** Calls that arrived while the handle was still being made (answered, in order, once it is). */
let early = [];
/**
 * A jump on the timeline in progress, re-simulated in slices (`Sim.seek_toward`) so a scene whose
 * steps take a second shows its progress: `{ id, step, target, done, total }` (the call's id,
 * the step asked for, the step it ends on, steps re-simulated so far and in all), or null.
 * Calls that arrive meanwhile wait in `afterSeek` and are answered, in order, once it ends.
 */
let seeking = null;
let afterSeek = [];

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
  for (const method of reads.frame) values[method] = read(method);
  if (sceneChanged) {
    for (const method of reads.scene) values[method] = read(method);
    sceneChanged = false;
  }
  const subscribed = {};
  for (const [method, args] of subscriptions) {
    if (reads.subscribable.has(method)) subscribed[`${method}|${JSON.stringify(args)}`] = read(method, args);
  }
  const jump = seeking && { step: seeking.target, at: sim.steps(), done: seeking.done, total: seeking.total };
  return { values, subscribed, seeking: jump };
}

function fail(error) {
  if (isPanic(error)) {
    crashed = true;
    self.postMessage({ type: 'panic', message: messageOf(error) });
    return true;
  }
  return false;
}

/**
 * The rendered pixels of view `pane` (a `CompareSim` pane; null: the `Sim`'s one frame), copied
 * once out of wasm memory into a buffer the page gave back when one fits.
 */
function pixelsOf(pane) {
  const args = pane === null ? [] : [pane];
  sim.render(...args);
  const len = sim.frame_len(...args);
  const frame = new Uint8ClampedArray(wasm.memory.buffer, sim.frame_ptr(...args), len);
  const reuse = spare.findIndex((buffer) => buffer.byteLength === len);
  if (reuse < 0) return frame.slice().buffer;
  const [buffer] = spare.splice(reuse, 1);
  new Uint8ClampedArray(buffer).set(frame);
  return buffer;
}

function postFrame(extra) {
  // A `Sim` renders one frame; a `CompareSim` one per pane, all of the same size.
  const panes = kind === 'CompareSim' ? Array.from({ length: sim.pane_count() }, (_, i) => pixelsOf(i)) : [pixelsOf(null)];
  spare = [];
  awaitingAck = true;
  dirty = false;
  self.postMessage(
    { type: 'frame', pixels: panes[0] ?? null, panes, width: sim.width(), height: sim.height(), state: snapshot(), ...extra },
    panes,
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
    if (seeking) {
      seekSlice();
      dirty = true;
    } else if (kind === 'Sim' && sim.planning_progress() < 1) {
      // Planning runs whether or not the scene plays (the page shows its progress and Cancel).
      planning = true;
      const progress = planningBudget.spend((evaluations) => sim.advance_planning(evaluations), PLANNING_BUDGET_MS);
      // The picture does not change while planning: a frame (with the progress) every
      // PLANNING_FRAME_MS, and between them the next slice runs at once (messages still get
      // their turn between slices), not after the page's answer to a frame.
      const now = performance.now();
      if (progress >= 1 || now - lastPlanningFrame >= PLANNING_FRAME_MS) {
        lastPlanningFrame = now;
        dirty = true;
      }
    } else if (playing && stepsPerFrame < 1) {
      // Slow motion: a step once the frames since the last one add up to a whole step (every
      // fourth frame at 0.25×); every frame is still posted, so the page's acknowledgements pace
      // the count, one per painted frame.
      slowCredit += stepsPerFrame;
      if (slowCredit >= 1 - 1e-9) {
        slowCredit -= 1;
        const before = performance.now();
        sim.step(1);
        stepMs = performance.now() - before;
        asked = 1;
        done = 1;
      }
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
    if (seeking?.ended) endSeek();
  } catch (error) {
    if (seeking && !isPanic(error)) {
      refuseSeek(error);
      return;
    }
    if (!fail(error)) {
      // A refused step (not a panic) would repeat every frame: stop and let the page explain.
      playing = false;
      self.postMessage({ type: 'refused', error: errorData(error) });
    }
  }
}

/**
 * A compare page's panes: the linked scene (else `fallbackText`, and why in `sceneError`) with
 * the linked comparison spec (else the default one, and why in `specError`).
 */
function startCompare({ sceneText, fallbackText, specText, width, height }) {
  let sceneError = null;
  let specError = null;
  let scene = sceneText;
  try {
    module.scene_from_text(scene);
  } catch (error) {
    if (isPanic(error)) throw error;
    sceneError = errorData(error);
    scene = fallbackText;
  }
  try {
    sim = new module.CompareSim(scene, specText ?? '', width, height);
  } catch (error) {
    if (isPanic(error)) throw error;
    specError = errorData(error);
    sim = new module.CompareSim(scene, '', width, height);
  }
  sceneChanged = true;
  dirty = true;
  return { sceneError, specError };
}

async function start(options) {
  const { sceneText, linked, width, height, theme } = options;
  // The page's compiled wasm, when it sent one: no second download or compile.
  ({ module, wasm } = await loadWasm(options.wasmModule ?? null));
  kind = options.kind ?? 'Sim';
  reads = READS[kind];
  if (kind === 'CompareSim') return startCompare(options);
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

/**
 * One slice of the jump in progress: single re-simulated steps until SEEK_BUDGET_MS is spent
 * (at least one). The world reached is the one a single `seek` would give (core: `seek_toward`).
 */
function seekSlice() {
  const start = performance.now();
  do {
    const before = sim.steps();
    const steps = sim.seek_toward(seeking.step, 1);
    seeking.done += steps;
    const at = sim.steps();
    // After the first slice the world is on the way: what is left is the distance to the target.
    seeking.total = seeking.done + Math.max(0, seeking.target - at);
    if (at === seeking.target || (steps === 0 && at === before)) {
      seeking.ended = true;
      break;
    }
  } while (performance.now() - start < SEEK_BUDGET_MS);
}

/** Answers the finished jump's call, then the calls that waited for it. */
function endSeek() {
  const { id, done } = seeking;
  seeking = null;
  sceneChanged = true;
  sim.render();
  self.postMessage({ type: 'reply', id, ok: true, value: done, state: snapshot() });
  answerWaiting();
}

/** Answers, in order, the calls that waited for a jump. */
function answerWaiting() {
  const waiting = afterSeek;
  afterSeek = [];
  for (const call of waiting) answer(call.id, call.method, call.args);
  schedule();
}

/** Answers the jump in progress with the core's refusal and ends it. */
function refuseSeek(error) {
  const { id } = seeking;
  seeking = null;
  sceneChanged = true;
  self.postMessage({ type: 'reply', id, ok: false, error: errorData(error), state: snapshot() });
  answerWaiting();
}

/** Starts a jump on the timeline in slices; a jump asked for meanwhile takes over from it. */
function startSeek(id, step) {
  if (seeking) {
    // The earlier jump's call is answered with what it re-simulated: the new one goes on from there.
    self.postMessage({ type: 'reply', id: seeking.id, ok: true, value: seeking.done, state: snapshot() });
  }
  seeking = { id, step, target: sim.seek_target(step), done: 0, total: 0, ended: false };
  dirty = true;
  // The first slice at once: a short jump is answered without waiting for the next frame.
  seekSlice();
  if (seeking.ended) endSeek();
  else schedule();
}

function answer(id, method, args) {
  if (crashed) return;
  // A long jump re-simulates in slices between frames (`Sim` only: the timeline's).
  if (kind === 'Sim' && method === 'seek' && Number.isInteger(args[0]) && args[0] >= 0) {
    try {
      startSeek(id, args[0]);
    } catch (error) {
      if (!fail(error)) refuseSeek(error);
    }
    return;
  }
  if (seeking) {
    afterSeek.push({ id, method, args });
    return;
  }
  let reply;
  try {
    if (typeof sim?.[method] !== 'function' || method === 'free') throw new Error(`no such call: ${method}`);
    const value = sim[method](...args);
    if (!reads.pure.has(method)) {
      dirty = true;
      if (!reads.sceneKeeping.has(method)) sceneChanged = true;
      // The view transform is fitted when a frame is rendered: render before the state is read.
      if (kind === 'Sim') sim.render();
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
        const outcome = await start(data);
        self.postMessage({ type: 'started', ...outcome, state: snapshot() });
        for (const call of early) answer(call.id, call.method, call.args);
        early = [];
        schedule();
      } catch (error) {
        if (!fail(error)) {
          self.postMessage({ type: 'start-failed', error: errorData(error) });
          // Calls that waited for the handle get the same reason.
          for (const call of early) self.postMessage({ type: 'reply', id: call.id, ok: false, error: errorData(error) });
          early = [];
        }
      }
      break;
    case 'call':
      // A restarted worker may be asked before its handle exists (wasm still loading).
      if (sim === null) early.push(data);
      else answer(data.id, data.method, data.args);
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
      if (Array.isArray(data.buffers)) spare = data.buffers;
      if (data.subscriptions) subscriptions = data.subscriptions;
      if ('stepsPerFrame' in data) stepsPerFrame = data.stepsPerFrame;
      if (data.render) dirty = true;
      schedule();
      break;
    default:
      break;
  }
};
