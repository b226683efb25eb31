// The Tune page: pick a behaviour and an environment (or the playground's scene, passed as
// `tune.html#s=<fragment>`), press Tune. A Web Worker (worker.js, the same wasm module) runs
// the genetic algorithm one generation per message; this page only shows its reports: progress
// bar, live plot, best weights, and a preview of the scene with those weights. Cancel terminates
// the worker. Apply opens `index.html#s=<scene with the best weights>`, so the link keeps them.
//
// Query parameters preset the fields: ?behaviour=b2&environment=e3&seed=4&population=20
// &generations=5&frames=120&autostart=1. The state is readable as `window.flocktune.state()`.

import { bootPage } from '../core/boot.js';
import { errorFromData, isPanic, messageOf, showMessage, showPanic } from '../core/errors.js';
import { FitnessPlot } from './plot.js';
import { Preview } from './preview.js';
import { sceneFromLocation, shareUrl } from '../core/url.js';
import { formatNumber, onLanguageChange, setText, t } from '../core/i18n.js';
import { prefersReducedMotion } from '../core/motion.js';

const $ = (id) => document.getElementById(id);
const FIELDS = ['behaviour', 'environment', 'seed', 'population', 'generations', 'frames'];
/** The five weights' labels: the virtual-force planner's own parameters (keys in the tables). */
const WEIGHTS = ['separation_weight', 'alignment_weight', 'cohesion_weight', 'following_weight', 'collision_weight'].map((k) => `param.forces.${k}`);
const MEASURES = [['gm', 'tune.gm'], ['gg', 'tune.gg'], ['gc', 'tune.gc'], ['ga', 'tune.ga'], ['gd', 'tune.gd']];
const CURRENT_SCENE = 'scene';

/** Everything the page knows about the run; a copy is published for tests and scripts. */
const state = {
  running: false,
  finished: false,
  cancelled: false,
  error: null,
  setup: null,
  population: 0,
  agents: 0,
  frames: 0,
  history: [],
  best: null,
  bestScene: null,
  evaluations: 0,
  workerMs: 0,
};

let worker = null;
let preview = null;
let plot = null;

/** The fields' values as a TuneSetup (see src/tune.rs). */
function readSetup(linkedScene) {
  const number = (id) => Number.parseInt($(id).value, 10);
  const environment = $('environment').value;
  return {
    behaviour: $('behaviour').value,
    environment: environment === CURRENT_SCENE ? 'e1' : environment,
    scene: environment === CURRENT_SCENE ? linkedScene : null,
    seed: number('seed'),
    population: number('population'),
    generations: number('generations'),
    frames: number('frames'),
  };
}

function setRunning(running) {
  state.running = running;
  $('tune').disabled = running;
  $('cancel').disabled = !running;
  for (const id of FIELDS) $(id).disabled = running;
}

function status(key, vars) {
  setText($('status'), key, vars);
}

function showBest(best) {
  const list = $('best');
  list.replaceChildren();
  if (!best) return;
  const row = (label, value) => {
    const dt = document.createElement('dt');
    setText(dt, label);
    const dd = document.createElement('dd');
    dd.textContent = value;
    list.append(dt, dd);
  };
  best.weights.forEach((w, i) => row(WEIGHTS[i], w.toFixed(3)));
  for (const [key, label] of MEASURES) row(label, best.measures[key].toFixed(3));
  row('metrics.col.gsum', best.gsum.toFixed(2));
}

function showPreview(sceneString, label, vars) {
  // The preview's simulation runs in a worker: a refused scene is answered later.
  preview
    .show(sceneString, state.frames || undefined)
    .then(() => setText($('preview-label'), label, vars))
    .catch((error) => showMessage(t('tune.preview_failed', { reason: messageOf(error) })));
}

function fail(message, panic) {
  state.error = message;
  stopWorker();
  setRunning(false);
  status('tune.stopped', { message });
  if (panic) showPanic(message);
  else showMessage(message);
}

function stopWorker() {
  worker?.terminate();
  worker = null;
}

function onWorkerMessage(event) {
  const message = event.data;
  if (message.type === 'error') {
    fail(messageOf(errorFromData(message.error)), message.panic);
  } else if (message.type === 'started') {
    Object.assign(state, { population: message.population, agents: message.agents, frames: message.frames });
    status('tune.started', { generations: state.setup.generations, population: message.population, agents: message.agents, frames: message.frames });
    showPreview(message.scene, 'tune.preview_before');
    worker.postMessage({ type: 'next' });
  } else if (message.type === 'generation') {
    const stats = message.stats;
    if (stats === null) return;
    state.history.push({ generation: stats.generation, best_gsum: stats.best_gsum, mean_gsum: stats.mean_gsum });
    const improved = state.best === null || stats.best.gsum !== state.best.gsum;
    state.best = stats.best;
    state.bestScene = message.scene;
    state.workerMs += message.ms;
    const newEvaluations = stats.evaluations - state.evaluations;
    state.evaluations = stats.evaluations;
    plot.add(stats);
    const total = state.setup.generations;
    $('progress').max = total;
    $('progress').value = stats.finished ? total : stats.generation + 1;
    $('generation').textContent = t('tune.generation_of', { n: stats.generation + 1, total });
    $('best-gsum').textContent = stats.best.gsum.toFixed(2);
    $('evaluations').textContent = stats.evaluations.toLocaleString('en-US');
    $('rate').textContent = message.ms > 0 ? `${((1000 * newEvaluations) / message.ms).toFixed(0)} /s` : '–';
    showBest(stats.best);
    $('apply').disabled = false;
    if (improved) showPreview(message.scene, 'tune.preview_best', { generation: stats.generation + 1, gsum: stats.best.gsum.toFixed(2) });
    if (stats.finished) {
      state.finished = true;
      setRunning(false);
      stopWorker();
      const why = stats.generation + 1 >= total ? t('tune.why_limit') : t('tune.why_unchanged', { n: stats.unchanged });
      status('tune.done', { n: stats.generation + 1, why, evaluations: stats.evaluations, seconds: (state.workerMs / 1000).toFixed(1) });
    } else {
      status('tune.generation_running', { n: stats.generation + 1, total });
      worker.postMessage({ type: 'next' });
    }
  }
}

function start(linkedScene) {
  stopWorker();
  const setup = readSetup(linkedScene);
  Object.assign(state, {
    running: true, finished: false, cancelled: false, error: null, setup, history: [], best: null,
    bestScene: null, evaluations: 0, workerMs: 0,
  });
  plot.reset(setup.generations);
  $('progress').value = 0;
  for (const id of ['generation', 'best-gsum', 'evaluations', 'rate']) $(id).textContent = '–';
  showBest(null);
  $('apply').disabled = true;
  setRunning(true);
  status('tune.starting');
  worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
  worker.addEventListener('message', onWorkerMessage);
  worker.addEventListener('error', (event) => fail(event.message || t('tune.worker_failed'), false));
  worker.postMessage({ type: 'start', setup });
}

function cancel() {
  if (!state.running) return;
  stopWorker();
  state.cancelled = true;
  setRunning(false);
  const done = state.history.length;
  status(done === 0 ? 'tune.cancelled' : done === 1 ? 'tune.cancelled_one' : 'tune.cancelled_after', { n: done });
}

function apply() {
  if (state.bestScene === null) return;
  location.href = shareUrl(state.bestScene, new URL('index.html', location.href).href);
}

/** Fills the fields from the query string (`?population=20&…`). */
function readQuery(linkedScene) {
  const query = new URLSearchParams(location.search);
  for (const id of FIELDS) {
    const value = query.get(id);
    if (value === null) continue;
    const field = $(id);
    if (field.tagName === 'SELECT' && ![...field.options].some((o) => o.value === value)) {
      showMessage(t('tune.unknown_field', { field: id, value, kept: field.value }));
      continue;
    }
    field.value = value;
  }
  if (linkedScene !== null && query.get('environment') === null) $('environment').value = CURRENT_SCENE;
  return query.get('autostart') === '1';
}

bootPage(t('boot.what_tune'), ({ module, wasm }) => {

  const linkedScene = sceneFromLocation();
  if (linkedScene !== null) {
    try {
      module.scene_from_text(linkedScene);
      const option = document.createElement('option');
      option.value = CURRENT_SCENE;
      setText(option, 'tune.playground_scene');
      $('environment').append(option);
      $('playground-link').href = shareUrl(linkedScene, new URL('index.html', location.href).href);
    } catch (error) {
      showMessage(t('tune.link_failed', { reason: messageOf(error) }));
    }
  }
  const autostart = readQuery(linkedScene);

  preview = new Preview(module, wasm, $('preview-canvas'));
  preview.onError = (error) => {
    if (isPanic(error)) showPanic(messageOf(error));
    else showMessage(t('tune.preview_stopped', { reason: messageOf(error) }));
  };
  // The preview's Play/Pause; a reader who asked for less motion starts paused (Play plays).
  const playPreview = (playing) => {
    preview.setPlaying(playing);
    setText($('preview-play'), playing ? 'playback.pause' : 'playback.play');
    $('preview-play').setAttribute('aria-pressed', String(playing));
  };
  playPreview(!prefersReducedMotion());
  $('preview-play').addEventListener('click', () => playPreview(!preview.playing));
  plot = new FitnessPlot($('plot'));
  plot.reset(Number.parseInt($('generations').value, 10) || 1);

  // Before a run, preview what would be tuned: the scene a run with these settings starts from.
  const previewSetup = () => {
    if (state.running || state.best !== null) return;
    try {
      const run = new module.TuneRun(JSON.stringify({ ...readSetup(linkedScene), population: 2, generations: 1 }));
      const scene = run.best_scene_string();
      const frames = run.frames();
      run.free();
      state.frames = frames;
      showPreview(scene, 'tune.preview_before');
    } catch (error) {
      showMessage(messageOf(error));
    }
  };
  for (const id of ['environment', 'behaviour', 'frames']) $(id).addEventListener('change', previewSetup);
  previewSetup();

  $('tune').addEventListener('click', () => start(linkedScene));
  $('cancel').addEventListener('click', cancel);
  $('apply').addEventListener('click', apply);
  $('loading').hidden = true;

  window.flocktune = {
    /** A copy of the run's state: {running, finished, cancelled, error, setup, history, best, …}. */
    state: () => structuredClone({ ...state, previewFrames: preview.painted, previewSteps: preview.steps(), previewPlaying: preview.playing }),
    /** Starts a run with the fields' values (like pressing Tune). */
    start: () => start(linkedScene),
    /** Cancels the run (like pressing Cancel). */
    cancel,
  };
  window.dispatchEvent(new Event('flocktune-ready'));
  if (autostart) start(linkedScene);
});
