// The page API for course notes, scripts and tests: `window.flockpath` and this module's exports.
//
//   import flockpath from './js/play/api.js';
//   await flockpath.ready;
//   await flockpath.load(sceneJson); await flockpath.step(600); flockpath.metrics().arrived_share;
//
// The simulation runs in a worker (core/sim-worker.js), so calls that advance or change it return
// a Promise, settled once the worker did it; reads (`metrics()`, `digest()`, `scene()`, …) answer
// at once with the state after the last settled call (or the last frame shown while playing).
// `positions()`, `agentAt()` and `metricsHistory()` ask the worker and return a Promise too.
// Every call goes through the same guarded path as the UI: a refused input rejects (throws) with
// an `Error` carrying a readable message (also shown in the page's banner) and the current scene
// keeps running.

import { Restarted } from '../core/sim-proxy.js';
import { seekTo } from './timeline.js';

let app = null;
let resolveReady;

/** Resolves with the API once the wasm module has booted and the first scene runs. */
export const ready = new Promise((resolve) => {
  resolveReady = resolve;
});

function booted() {
  if (!app) throw new Error('flockpath is still loading: await flockpath.ready first');
  return app;
}

/**
 * Loads a scene: JSON text, a scene object, a URL fragment value (`2.…`), a `#s=…` fragment or
 * a whole URL. Returns the loaded scene object; throws a readable Error and keeps the current
 * scene when the input is refused.
 */
export async function load(sceneJsonOrUrlString) {
  const a = booted();
  let text = sceneJsonOrUrlString;
  if (text !== null && typeof text === 'object') text = JSON.stringify(text);
  if (typeof text !== 'string') {
    throw new TypeError(`load() takes scene JSON text, a scene object or a URL string, not ${typeof text}`);
  }
  await a.load(text, { rethrow: true });
  return scene();
}

/**
 * Resolves once the simulation worker has answered everything the page sent it, including what a
 * click or a key sent (an edit after a pick): the reads then show the state it left.
 */
async function settledFor(a) {
  do {
    try {
      await a.remote.call('steps');
    } catch (error) {
      // A worker restarted under the call (sim-proxy.js): wait for the new one instead.
      if (!(error instanceof Restarted)) throw error;
    }
    // A reply may start the next call of a gesture (the edit after its pick): let it be sent.
    await new Promise((resolve) => setTimeout(resolve, 0));
  } while (a.remote.busy());
}

/** Resolves once the page's simulation has caught up with every call, click and key so far. */
export function settled() {
  return settledFor(booted());
}

/** Starts the frame loop stepping; resolves once the worker plays. */
export function play() {
  const a = booted();
  a.setPlaying(true);
  return settledFor(a);
}

/**
 * Stops the frame loop stepping (the canvas keeps showing the current state); resolves once the
 * worker stopped, with the reads showing the step it stopped at.
 */
export function pause() {
  const a = booted();
  a.setPlaying(false);
  return settledFor(a);
}

/** Whether the frame loop is stepping. */
export function isPlaying() {
  return booted().playing;
}

/** Advances `n` fixed steps now; resolves to the step count afterwards. */
export async function step(n = 1) {
  const count = Number(n);
  if (!Number.isInteger(count) || count < 0 || count > 0xffffffff) {
    throw new RangeError(`step(n) takes a whole number of steps ≥ 0, not ${n}`);
  }
  return (await booted().stepNow(count, { rethrow: true })).value;
}

/** Restarts the current scene from step 0 with its seed; resolves once it did. */
export async function reset() {
  await booted().reset({ rethrow: true });
}

/** The metrics object (DESIGN §4 keys: steps, agents, arrived_share, …, groups). */
export function metrics() {
  return booted().guard((sim) => JSON.parse(sim.metrics_json()), { rethrow: true }).value;
}

/** The current scene as a JSON object (a copy: changing it changes nothing). */
export function scene() {
  return booted().guard((sim) => JSON.parse(sim.scene_json()), { rethrow: true }).value;
}

/** The URL fragment value of the current scene: `index.html#s=<value>` reopens it. */
export function sceneString() {
  return booted().guard((sim) => sim.scene_string(), { rethrow: true }).value;
}

/** A hash of every agent's state, for checking that two runs are identical. */
export function digest() {
  return booted().guard((sim) => String(sim.digest()), { rethrow: true }).value;
}

/**
 * Share of the scene's planning ahead done (IGSA group paths), 0…1. Below 1 the page plans in
 * slices and does not step yet; `step(n)` would finish the planning at once.
 */
export function planningProgress() {
  return booted().guard((sim) => sim.planning_progress(), { rethrow: true }).value;
}

/**
 * Agent positions as `[[x, y], …]` in scene px, in agent order (groups in scene order), for
 * tests and course notes that want to measure something the metrics do not cover.
 */
export async function positions() {
  const result = await booted().guard((sim) => sim.positions_json(), { rethrow: true });
  const flat = JSON.parse(result.value);
  const pairs = [];
  for (let i = 0; i + 1 < flat.length; i += 2) pairs.push([flat[i], flat[i + 1]]);
  return pairs;
}

/**
 * Each goal where it is at the step shown, as the canvas draws it: `[{x, y, radius}, …]` in scene
 * px, in the scene's goal order. A moving goal's `position` in `scene()` is only where it starts.
 */
export function goals() {
  return booted().guard((sim) => JSON.parse(sim.goals_json()), { rethrow: true }).value;
}

/**
 * The scene→canvas transform: canvas backing-store px = scene px × scale + offset. With the
 * canvas's CSS box it maps scene points to pointer positions (`canvasWidth` is in device px).
 */
export function view() {
  return booted().guard((sim) => {
    const [scale, offsetX, offsetY] = sim.view();
    return { scale, offsetX, offsetY, canvasWidth: sim.width(), canvasHeight: sim.height() };
  }, { rethrow: true }).value;
}

/**
 * Jumps to recorded step `k` (clamped to the run's history): the nearest checkpoint is restored
 * and re-simulated, so the state is bit-identical to the original run at `k`; play goes on from
 * there. Returns the step count afterwards.
 */
export async function seek(k) {
  const target = Number(k);
  if (!Number.isInteger(target) || target < 0 || target > 0xffffffff) {
    throw new RangeError(`seek(k) takes a whole step number ≥ 0, not ${k}`);
  }
  const a = booted();
  await seekTo(a, target, { rethrow: true });
  return a.guard((sim) => sim.steps(), { rethrow: true }).value;
}

/** The timeline's state: `{step, first_step, end_step, frame_every, checkpoint_every, note, …}`. */
export function timeline() {
  return booted().guard((sim) => JSON.parse(sim.timeline_json()), { rethrow: true }).value;
}

/**
 * The agent at scene point (x, y) within `tolerance` px of its body (the nearest), or null.
 */
export async function agentAt(x, y, tolerance = 0) {
  const result = await booted().guard((sim) => sim.agent_at(Number(x), Number(y), Number(tolerance)), { rethrow: true });
  return result.value < 0 ? null : result.value;
}

/** Inspects agent `id` (null: nobody): the inspector opens and its forces are drawn. */
export async function inspect(id) {
  const a = booted();
  await a.guard((sim) => sim.inspect(id === null || id === undefined ? -1 : Number(id)), { rethrow: true });
  a.dirty = true;
  a.dispatchEvent(new Event('inspection'));
}

/**
 * Why the inspected agent moves as it does (null if nobody is inspected): `{agent, group,
 * planner, position, velocity, speed, state, stuck, neighbours, vectors, points, applied, values}`.
 */
export function explanation() {
  return booted().guard((sim) => JSON.parse(sim.explanation_json()), { rethrow: true }).value;
}

/** Ids of the agents stuck now (no progress towards their goal for 300 steps). */
export function stuckAgents() {
  return Array.from(booted().guard((sim) => sim.stuck_agents(), { rethrow: true }).value);
}

/**
 * Switches overlays: `{stuck, explanation, landscape, fireflies}` (missing keys keep their
 * state); returns the overlays now on.
 */
export async function overlays(changes = {}) {
  const a = booted();
  await a.guard((sim) => {
    const on = { ...JSON.parse(sim.overlays_json()), ...changes };
    return sim.set_overlays(Boolean(on.stuck), Boolean(on.explanation), Boolean(on.landscape), Boolean(on.fireflies));
  }, { rethrow: true });
  a.dirty = true;
  a.dispatchEvent(new Event('overlays'));
  return a.guard((sim) => JSON.parse(sim.overlays_json()), { rethrow: true }).value;
}

/**
 * The metrics over time from the core: `{steps, every, thinned, series: {key: {label, unit,
 * overall: [...], groups: [[...], ...]}}}`; missing values are null.
 */
export async function metricsHistory() {
  const a = booted();
  // One worker call per series, answered in order: every one is of the same step.
  const asked = a.guard((sim) => {
    const meta = JSON.parse(sim.history_json());
    const remote = a.remote;
    const series = meta.series.map((s) => ({
      s,
      overall: remote.call('history_series', [s.key, -1]),
      groups: meta.groups.map((_, i) => remote.call('history_series', [s.key, i])),
    }));
    return { meta, steps: remote.call('history_steps'), series };
  }, { rethrow: true });
  const { meta, steps, series: pending } = asked.value ?? (await asked).value;
  const list = (values) => Array.from(values, (v) => (Number.isFinite(v) ? v : null));
  const series = {};
  for (const { s, overall, groups } of pending) {
    series[s.key] = { label: s.label, unit: s.unit, overall: list(await overall), groups: (await Promise.all(groups)).map(list) };
  }
  return { steps: Array.from(await steps), every: meta.every, thinned: meta.thinned, series };
}

/**
 * The render theme: with a name ('standard' or 'projector') draws in it from the next frame on
 * (a page option, not part of the scene) and resolves to the theme's name; without, returns it. js/core/theme.js drives it.
 */
export function theme(name) {
  const a = booted();
  if (name === undefined) return a.guard((sim) => sim.theme(), { rethrow: true }).value;
  return a.guard((sim) => sim.set_theme(String(name)), { rethrow: true }).then(() => {
    a.dirty = true;
    return a.guard((sim) => sim.theme(), { rethrow: true }).value;
  });
}

/**
 * The link's classroom options as the page applies them: `{controls, lock, hide, locked_tools,
 * can_load, open, fragment, attributes}` (a copy). They restrict the page's controls only;
 * every call of this API stays open.
 */
export function classroom() {
  return structuredClone(booted().classroom ?? null);
}

/**
 * The scene activity's check (null without one): `{status: 'running' | 'met' | 'missed' |
 * 'unavailable', step, limit, from_step, conditions: [{condition, applies, holds, measured}]}`,
 * the values of the deciding step once decided (the page's activity card shows the same).
 */
export function activityReport() {
  return booted().guard((sim) => JSON.parse(sim.activity_report_json()), { rethrow: true }).value;
}

/** The API object: `window.flockpath` and this module's default export. */
export const flockpath = Object.freeze({
  ready,
  settled,
  load,
  play,
  pause,
  isPlaying,
  step,
  reset,
  metrics,
  scene,
  sceneString,
  digest,
  planningProgress,
  seek,
  timeline,
  positions,
  goals,
  view,
  agentAt,
  inspect,
  explanation,
  stuckAgents,
  overlays,
  metricsHistory,
  theme,
  activityReport,
  classroom,
});

export default flockpath;

/** Called once by main.js when the first scene runs. */
export function attach(booted_app) {
  app = booted_app;
  resolveReady(flockpath);
}
