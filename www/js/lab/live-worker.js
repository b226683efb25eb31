// The lab's live runs (issue 24): this worker owns the wasm `Lab` handles (the chosen algorithm and
// every one overlaid on the same seed), steps them while the page plays, renders the primary run's
// 2-D picture and posts it with the runs' readable state (iteration, best value, curves,
// positions, digest). At dimension 200 × population 500 an iteration of the five algorithms takes
// seconds: here it never delays the page's clicks. The worker computes nothing itself: it calls
// the handles and forwards what they return. One frame is in flight at a time: the next is
// rendered once the page drew the last (`ack`), so the page is never flooded.
//
// Requests from the page (lab/main.js), answered in order with `{type: 'reply', id, ok, state}`:
//   {type: 'reset', id, settings: {fn, dim, population, iterations, seed}, names, width, height}
//   {type: 'step', id, n}   n iterations of every run, paused
//   {type: 'sync', id}      nothing: the reply says every earlier request was handled
// and without a reply: {type: 'control', playing, speed}, {type: 'ack', buffer}.

import { loadWasm } from '../core/boot.js';
import { errorData, isPanic, messageOf } from '../core/errors.js';
import { STEP_BUDGET_MS } from '../core/pace.js';

let module = null;
let wasm = null;
/** `[{ name, lab, primary }]`: the primary (chosen) algorithm first. */
let runs = [];
let width = 0;
let height = 0;
let playing = false;
/** Iterations per frame asked for (the Speed slider). */
let speed = 1;
let awaitingAck = false;
let dirty = true;
let crashed = false;
/** A drawn frame's pixel buffer, handed back to be filled again. */
let spare = null;

const tickChannel = new MessageChannel();
let tickQueued = false;
tickChannel.port1.onmessage = () => {
  tickQueued = false;
  tick();
};
function schedule() {
  if (tickQueued || crashed) return;
  tickQueued = true;
  tickChannel.port2.postMessage(null);
}

function free() {
  for (const run of runs) run.lab.free();
  runs = [];
}

/** Whether every run has spent its iteration budget. */
const finished = () => runs.length > 0 && runs.every((run) => run.lab.iteration() >= run.lab.iterations());

/**
 * The runs' readable state for the page, and the buffers that can be transferred with it. The
 * primary run's positions go along (row-major, `dim` numbers per particle).
 */
function snapshot() {
  const primary = runs[0]?.lab ?? null;
  const curves = runs.map((run) => ({ name: run.name, curve: new Float64Array(run.lab.curve()), budget: run.lab.iterations(), primary: run.primary }));
  const positions = primary ? new Float64Array(primary.positions()) : new Float64Array(0);
  const state = {
    name: runs[0]?.name ?? null,
    iteration: primary?.iteration() ?? 0,
    iterations: primary?.iterations() ?? 0,
    particles: primary?.particles() ?? 0,
    best: primary?.best_value() ?? null,
    digest: primary?.digest() ?? null,
    finished: finished(),
    playing,
    curves,
    positions,
  };
  return { state, transfer: [positions.buffer, ...curves.map((c) => c.curve.buffer)] };
}

/** The primary run's picture, copied once out of wasm memory (null when there is none). */
function picture() {
  const primary = runs[0]?.lab;
  if (!primary || width === 0 || height === 0) return null;
  const start = performance.now();
  primary.render(width, height);
  const len = primary.frame_len();
  const view = new Uint8ClampedArray(wasm.memory.buffer, primary.frame_ptr(), len);
  let buffer;
  if (spare && spare.byteLength === len) {
    buffer = spare;
    new Uint8ClampedArray(buffer).set(view);
  } else {
    buffer = view.slice().buffer;
  }
  spare = null;
  return { buffer, renderMs: performance.now() - start };
}

function postFrame(stepped) {
  const pixels = picture();
  const { state, transfer } = snapshot();
  awaitingAck = true;
  dirty = false;
  self.postMessage(
    { type: 'frame', pixels: pixels?.buffer ?? null, renderMs: pixels?.renderMs ?? null, width, height, stepped, state },
    pixels ? [pixels.buffer, ...transfer] : transfer,
  );
}

function crash(error) {
  crashed = true;
  self.postMessage({ type: 'panic', message: messageOf(error) });
}

/**
 * One frame: while playing, up to `speed` iterations of every run (all runs advance together),
 * stopping early once the frame's work plus one more iteration would pass STEP_BUDGET_MS; then
 * the picture and the state. A finished set of runs stops playing.
 */
function tick() {
  if (crashed || awaitingAck || !module) return;
  try {
    let stepped = 0;
    if (playing && runs.length > 0) {
      const start = performance.now();
      while (stepped < speed && !finished()) {
        const before = performance.now();
        for (const run of runs) run.lab.step(1);
        stepped += 1;
        const after = performance.now();
        if (after - start + (after - before) > STEP_BUDGET_MS) break;
      }
      if (finished()) playing = false;
      dirty = true;
    }
    if (dirty) postFrame(stepped);
  } catch (error) {
    if (isPanic(error)) crash(error);
    else throw error;
  }
}

/** Replaces the runs: one per name, the first the primary, all on the same settings and seed. */
function reset({ settings, names }) {
  free();
  const { fn, dim, population, iterations, seed } = settings;
  try {
    for (const name of names) runs.push({ name, lab: new module.Lab(name, fn, dim, population, iterations, seed), primary: runs.length === 0 });
  } catch (error) {
    free();
    throw error;
  }
}

function handle(data) {
  switch (data.type) {
    case 'reset':
      width = data.width;
      height = data.height;
      reset(data);
      return;
    case 'step':
      playing = false;
      for (const run of runs) run.lab.step(data.n);
      return;
    case 'sync':
      return;
    default:
      throw new Error(`no such request: ${data.type}`);
  }
}

const ready = loadWasm().then((loaded) => {
  ({ module, wasm } = loaded);
});

self.onmessage = async ({ data }) => {
  if (data.type === 'control') {
    if ('playing' in data) playing = Boolean(data.playing);
    if ('speed' in data) speed = Math.max(1, data.speed | 0);
    schedule();
    return;
  }
  if (data.type === 'ack') {
    awaitingAck = false;
    if (data.buffer) spare = data.buffer;
    schedule();
    return;
  }
  try {
    await ready;
  } catch (error) {
    self.postMessage({ type: 'reply', id: data.id, ok: false, error: errorData(error) });
    return;
  }
  if (crashed) return;
  let reply;
  try {
    handle(data);
    dirty = true;
    const { state, transfer } = snapshot();
    reply = [{ type: 'reply', id: data.id, ok: true, state }, transfer];
  } catch (error) {
    if (isPanic(error)) {
      crash(error);
      return;
    }
    const { state, transfer } = snapshot();
    reply = [{ type: 'reply', id: data.id, ok: false, error: errorData(error), state }, transfer];
  }
  self.postMessage(...reply);
  schedule();
};
