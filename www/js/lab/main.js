// The optimizer lab page: pick a function and an algorithm, watch the swarm on the function's
// heat map (d = 2, pixels from Rust), compare best-so-far curves of several algorithms on the
// same seed, and fill a 30-run table in a Web Worker. The live runs step and render in a worker
// of their own (live-worker.js; issue 24: at d = 200 × N = 500 an iteration of five algorithms
// takes seconds), so Play, Pause, Step and every field answer at once; the page draws the frames
// and the curves it is sent. Every number comes from the wasm core.

import { bootPage } from '../core/boot.js';
import { errorFromData, messageOf, showMessage, showPanic } from '../core/errors.js';
import { drawPlot } from '../core/plot.js';
import { onPage } from '../core/keys.js';
import { setText, t } from '../core/i18n.js';

const $ = (id) => document.getElementById(id);

/** Line and label colour per algorithm name; each ≥ 4.5:1 on white, as the checkbox labels are text (axe colour contrast). */
const ALGORITHM_COLORS = { gsa: '#c2410c', igsa: '#1971c2', pso: '#2b7a3b', firefly: '#ae3ec9', ga: '#5c5f66' };

/**
 * The convergence chart: best-so-far against iteration on a log scale, one line per run
 * (`[{ name, curve, budget, primary }]`), drawn at the canvas's own size. Values ≤ 0 sit at the
 * bottom (the log of 0 does not exist).
 */
function convergence(runs) {
  const values = runs.flatMap((r) => Array.from(r.curve).filter((v) => v > 0 && Number.isFinite(v)));
  let lo = values.length ? Math.floor(Math.log10(Math.min(...values))) : 0;
  let hi = values.length ? Math.ceil(Math.log10(Math.max(...values))) : 1;
  if (hi <= lo) hi = lo + 1;
  lo = Math.max(lo, hi - 40);
  const budget = Math.max(1, ...runs.map((r) => r.budget));
  const yTicks = [];
  const stride = Math.max(1, Math.ceil((hi - lo) / 8));
  for (let e = lo; e <= hi; e += stride) yTicks.push({ value: 10 ** e, text: `1e${e}` });
  return {
    lines: runs.map((r) => ({
      xs: Array.from(r.curve, (_, i) => i),
      ys: Array.from(r.curve, (v) => (values.length ? v : NaN)),
      color: ALGORITHM_COLORS[r.name] ?? '#000000',
      width: r.primary ? 2.5 : 1.5,
      name: r.name,
    })),
    x: { min: 0, max: budget },
    y: { min: lo, max: hi, log: true },
    margin: { left: 58, right: 10, top: 10, bottom: 26 },
    yTicks,
    xTicks: [{ value: 0, text: '0' }, { value: budget, text: String(budget) }],
    xLabel: t('lab.iteration'),
    legend: true,
    background: '#ffffff',
    fit: false,
  };
}

/** Format a value the way Table 3 does. */
const fmt = (v) => (Number.isFinite(v) ? (v === 0 ? '0' : v.toExponential(4)) : String(v));

/** A Reset waits this long (ms) for a worker inside one piece of work before it ends the worker. */
const RESTART_AFTER_MS = 250;

/** The error of a request a restarted worker never answered. */
class Restarted extends Error {}

/**
 * The page's side of the live runs' worker (live-worker.js): requests answered in order with the
 * runs' state, frames drawn one at a time. `onState(state)` gets every state the worker sends
 * (replies and frames, in order); `onFrame(frame)` every frame; `onPanic(message)` a crash.
 */
class LiveRuns {
  constructor({ onState, onFrame, onPanic }) {
    this.onState = onState;
    this.onFrame = onFrame;
    this.onPanic = onPanic;
    this.playing = false;
    this.speed = 1;
    this.nextId = 1;
    this.start();
  }

  start() {
    const worker = new Worker(new URL('./live-worker.js', import.meta.url), { type: 'module' });
    this.worker = worker;
    this.calls = new Map();
    this.frame = null;
    this.lastHeard = performance.now();
    worker.onmessage = ({ data }) => {
      if (worker !== this.worker) return;
      this.lastHeard = performance.now();
      if (data.state) this.onState(data.state);
      if (data.type === 'reply') {
        const call = this.calls.get(data.id);
        this.calls.delete(data.id);
        if (data.ok) call?.resolve(data.state);
        else call?.reject(errorFromData(data.error));
      } else if (data.type === 'frame') {
        this.onFrame(data);
      } else if (data.type === 'panic') {
        for (const call of this.calls.values()) call.reject(new Error(data.message));
        this.calls.clear();
        this.onPanic(data.message);
      }
    };
    worker.onerror = (event) => {
      if (worker !== this.worker) return;
      event.preventDefault();
      const error = new Error(t('lab.worker_failed', { reason: event.message || 'live-worker.js' }));
      for (const call of this.calls.values()) call.reject(error);
      this.calls.clear();
      showMessage(error.message);
    };
    this.control({ playing: this.playing, speed: this.speed });
  }

  /** Sends one request; resolves to the runs' state after it (rejects with the refusal). */
  call(type, payload = {}) {
    const id = this.nextId;
    this.nextId += 1;
    const promise = new Promise((resolve, reject) => this.calls.set(id, { resolve, reject }));
    this.worker.postMessage({ ...payload, type, id });
    return promise;
  }

  /** Play or pause, iterations per frame: the worker picks them up after the work it is in. */
  control(changes) {
    if ('playing' in changes) this.playing = changes.playing;
    if ('speed' in changes) this.speed = changes.speed;
    this.worker.postMessage({ type: 'control', ...changes });
  }

  /** Lets the worker render its next frame; the drawn frame's pixels go back to be filled again. */
  ack(buffer) {
    this.worker.postMessage({ type: 'ack', buffer }, buffer ? [buffer] : []);
  }

  /** Whether the worker has been inside one piece of work (a request, a frame) too long to wait for. */
  stuck() {
    return (this.calls.size > 0 || this.playing) && performance.now() - this.lastHeard > RESTART_AFTER_MS;
  }

  /** Ends the worker and starts a fresh one (the runs are made again by the next reset). */
  restart() {
    this.worker.terminate();
    for (const call of this.calls.values()) call.reject(new Restarted('restarted'));
    this.start();
  }
}

bootPage(t('boot.what_lab'), async ({ module }) => {
  const options = JSON.parse(module.lab_options_json());
  const fnSelect = $('lab-function');
  const algSelect = $('lab-algorithm');
  for (const f of options.functions) fnSelect.append(new Option(`${f.name} [±${f.half_range}]`, f.name));
  for (const a of options.algorithms) algSelect.append(new Option(a.name, a.name));
  algSelect.value = 'igsa';
  fnSelect.value = 'rastrigin';
  const compare = $('lab-compare');
  for (const a of options.algorithms) {
    const label = document.createElement('label');
    label.className = 'check';
    label.style.color = ALGORITHM_COLORS[a.name] ?? '';
    label.innerHTML = `<input type="checkbox" value="${a.name}"> ${a.name}`;
    compare.append(label);
  }

  const canvas = $('lab-canvas');
  const plot = $('lab-plot');
  const state = {
    /** The runs' state the worker sent last (live-worker.js `snapshot`), or null before the first. */
    view: null,
    /** Whether the curves and the status line must be drawn again (a new state arrived). */
    fresh: false,
    playing: false,
    speed: 1,
    frames: 0,
    renderMs: [],
    worker: null,
  };

  const settings = () => ({
    fn: fnSelect.value,
    algorithm: algSelect.value,
    dim: Number($('lab-dim').value),
    population: Number($('lab-pop').value),
    iterations: Number($('lab-iters').value),
    seed: Number($('lab-seed').value) >>> 0,
  });
  const comparedAlgorithms = () => [...compare.querySelectorAll('input:checked')].map((i) => i.value);

  /** Draws the newest frame's picture (d = 2) and hands its pixels back to the worker. */
  const showFrame = (frame) => {
    let ms = null;
    if (frame.pixels && !canvas.hidden && frame.width === canvas.width && frame.height === canvas.height) {
      const t0 = performance.now();
      canvas.getContext('2d').putImageData(new ImageData(new Uint8ClampedArray(frame.pixels), frame.width, frame.height), 0, 0);
      ms = (frame.renderMs ?? 0) + performance.now() - t0;
    }
    if (ms !== null) {
      state.renderMs.push(ms);
      if (state.renderMs.length > 120) state.renderMs.shift();
    }
    live.ack(frame.pixels);
  };
  let pendingFrame = null;
  const live = new LiveRuns({
    onState: (view) => {
      state.view = view;
      state.fresh = true;
      // The worker stops at the end of the budget: the button says so.
      if (view.finished && state.playing && !view.playing) setPlaying(false);
    },
    onFrame: (frame) => {
      // Only the newest frame is drawn; an older one not drawn yet goes back at once.
      if (pendingFrame) live.ack(pendingFrame.pixels);
      pendingFrame = frame;
    },
    onPanic: (message) => {
      setPlaying(false);
      if (!showPanic(message)) showMessage(message);
    },
  });

  /** (Re)creates the runs: the chosen algorithm plus every checked one, all on the same seed. */
  const reset = async () => {
    const s = settings();
    const names = [s.algorithm, ...comparedAlgorithms().filter((n) => n !== s.algorithm)];
    const flat = s.dim === 2;
    canvas.hidden = !flat;
    $('lab-no-view').hidden = flat;
    // A worker still inside an iteration of a big run is not waited for: the new runs start afresh.
    if (live.stuck()) live.restart();
    const size = flat ? { width: canvas.width, height: canvas.height } : { width: 0, height: 0 };
    try {
      await live.call('reset', { settings: { fn: s.fn, dim: s.dim, population: s.population, iterations: s.iterations, seed: s.seed }, names, ...size });
    } catch (error) {
      if (error instanceof Restarted) return;
      showMessage(messageOf(error));
    }
  };

  const setPlaying = (playing) => {
    state.playing = playing;
    setText($('lab-play'), playing ? 'playback.pause' : 'playback.play');
    $('lab-play').setAttribute('aria-pressed', String(playing));
    live?.control({ playing });
  };

  /** The curves and the status line of the runs' newest state. */
  const draw = () => {
    const view = state.view;
    if (!view || view.name === null) return;
    drawPlot(plot, convergence(view.curves));
    $('lab-status').textContent =
      t('lab.status', { name: view.name, iteration: view.iteration, iterations: view.iterations, best: fmt(view.best), particles: view.particles });
  };

  let last = performance.now();
  let fpsFrames = 0;
  const frame = (now) => {
    if (pendingFrame) {
      showFrame(pendingFrame);
      pendingFrame = null;
    }
    if (state.fresh) {
      state.fresh = false;
      draw();
    }
    state.frames += 1;
    fpsFrames += 1;
    if (now - last > 1000) {
      const mean = state.renderMs.reduce((a, b) => a + b, 0) / Math.max(1, state.renderMs.length);
      $('lab-fps').textContent = t('lab.fps', { fps: Math.round((fpsFrames * 1000) / (now - last)), ms: mean.toFixed(2) });
      last = now;
      fpsFrames = 0;
    }
    requestAnimationFrame(frame);
  };

  // ----- 30 runs in a worker -----
  const tbody = $('lab-table').querySelector('tbody');
  const finishTable = (text) => {
    state.worker?.terminate();
    state.worker = null;
    $('lab-30').disabled = false;
    $('lab-cancel').disabled = true;
    $('lab-table-time').textContent = text;
  };
  const startTable = () => {
    const s = settings();
    const algorithms = [s.algorithm, ...comparedAlgorithms().filter((n) => n !== s.algorithm)];
    const list = algorithms.length > 1 ? algorithms : options.algorithms.map((a) => a.name);
    tbody.replaceChildren();
    $('lab-progress').value = 0;
    $('lab-progress-text').textContent = '';
    $('lab-30').disabled = true;
    $('lab-cancel').disabled = false;
    $('lab-table-time').textContent = t('lab.table_running', { fn: s.fn, dim: s.dim, population: s.population, iterations: s.iterations, seed: s.seed });
    const worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
    state.worker = worker;
    worker.onmessage = ({ data }) => {
      if (data.type === 'progress') {
        $('lab-progress').value = data.done / data.total;
        $('lab-progress-text').textContent = t('lab.runs_progress', { done: data.done, total: data.total });
      } else if (data.type === 'row') {
        const r = data.row;
        const tr = document.createElement('tr');
        tr.dataset.algorithm = r.algorithm;
        for (const cell of [r.algorithm, fmt(r.best), fmt(r.worst), fmt(r.mean), fmt(r.median), String(r.runs)]) {
          const td = document.createElement('td');
          td.textContent = cell;
          tr.append(td);
        }
        tbody.append(tr);
        const means = [...tbody.rows].map((row) => Number(row.cells[3].textContent));
        const best = Math.min(...means);
        for (const row of tbody.rows) row.cells[3].classList.toggle('best', Number(row.cells[3].textContent) === best);
      } else if (data.type === 'done') {
        finishTable(t('lab.table_done', { fn: s.fn, dim: s.dim, population: s.population, iterations: s.iterations, seed: s.seed, n: list.length, seconds: data.seconds.toFixed(1) }));
        state.lastTableSeconds = data.seconds;
      } else if (data.type === 'error') {
        finishTable('');
        showMessage(messageOf(errorFromData(data.error)));
      }
    };
    worker.onerror = (e) => {
      finishTable('');
      showMessage(t('lab.worker_failed', { reason: e.message }));
    };
    worker.postMessage({ algorithms: list, fn: s.fn, dim: s.dim, population: s.population, iterations: s.iterations, seed: s.seed, runs: 30 });
  };

  // ----- wiring -----
  $('lab-play').addEventListener('click', () => setPlaying(!state.playing));
  $('lab-step').addEventListener('click', () => {
    setPlaying(false);
    live.call('step', { n: 1 }).catch((error) => {
      if (!(error instanceof Restarted)) showMessage(messageOf(error));
    });
  });
  $('lab-reset').addEventListener('click', () => {
    setPlaying(false);
    reset();
  });
  $('lab-speed').addEventListener('input', () => {
    state.speed = Number($('lab-speed').value);
    live.control({ speed: state.speed });
    $('lab-speed-value').textContent = t('playback.times', { n: state.speed });
  });
  for (const input of [fnSelect, algSelect, $('lab-dim'), $('lab-pop'), $('lab-iters'), $('lab-seed')]) {
    input.addEventListener('change', () => {
      setPlaying(false);
      reset();
    });
  }
  compare.addEventListener('change', () => reset());
  $('lab-30').addEventListener('click', startTable);
  $('lab-cancel').addEventListener('click', () => finishTable(t('lab.cancelled')));
  // Single-key shortcuts only while the page or a canvas has focus (core/keys.js): a focused
  // button or checkbox keeps Space.
  window.addEventListener('keydown', (e) => {
    if (!onPage(e) || e.ctrlKey || e.metaKey || e.altKey) return;
    if (e.key === ' ') {
      e.preventDefault();
      setPlaying(!state.playing);
    } else if (e.key === 's') {
      $('lab-step').click();
    } else if (e.key === 'r') {
      $('lab-reset').click();
    }
  });

  await reset();
  requestAnimationFrame(frame);

  // For scripts and tests: read-only views of the state the worker sent last (the primary run's),
  // and `settled()`, which resolves once the worker has handled every click and call so far.
  window.flockpathLab = {
    play: () => setPlaying(true),
    pause: () => setPlaying(false),
    isPlaying: () => state.playing,
    settled: () => live.call('sync').then(() => undefined),
    iteration: () => state.view?.iteration ?? 0,
    particles: () => state.view?.particles ?? 0,
    positions: () => Array.from(state.view?.positions ?? []),
    bestValue: () => state.view?.best ?? undefined,
    digest: () => state.view?.digest ?? null,
    renderMs: () => [...state.renderMs],
    frames: () => state.frames,
    tableSeconds: () => state.lastTableSeconds ?? null,
  };
  window.dispatchEvent(new Event('flockpath-lab-ready'));
});
