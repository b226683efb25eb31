// The optimizer lab page: pick a function and an algorithm, watch the swarm on the function's
// heat map (d = 2, pixels from Rust), compare best-so-far curves of several algorithms on the
// same seed, and fill a 30-run table in a Web Worker. The page owns the frame loop; every
// number comes from the wasm core.

import { blit } from '../core/blit.js';
import { bootPage } from '../core/boot.js';
import { errorFromData, messageOf, showMessage } from '../core/errors.js';
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

bootPage(t('boot.what_lab'), ({ module, wasm }) => {
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
    runs: [],
    playing: false,
    speed: 1,
    frames: 0,
    renderMs: [],
    worker: null,
    pings: 0,
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

  /** (Re)creates the runs: the chosen algorithm plus every checked one, all on the same seed. */
  const reset = () => {
    for (const run of state.runs) run.lab.free();
    state.runs = [];
    const s = settings();
    const names = [s.algorithm, ...comparedAlgorithms().filter((n) => n !== s.algorithm)];
    try {
      for (const name of names) {
        state.runs.push({ name, lab: new module.Lab(name, s.fn, s.dim, s.population, s.iterations, s.seed), primary: name === s.algorithm });
      }
    } catch (error) {
      showMessage(messageOf(error));
      for (const run of state.runs) run.lab.free();
      state.runs = [];
    }
    const flat = s.dim === 2;
    canvas.hidden = !flat;
    $('lab-no-view').hidden = flat;
    draw();
  };

  const setPlaying = (playing) => {
    state.playing = playing;
    setText($('lab-play'), playing ? 'playback.pause' : 'playback.play');
  };

  const step = (n) => {
    for (const run of state.runs) run.lab.step(n);
    const done = state.runs.every((r) => r.lab.iteration() >= r.lab.iterations());
    if (done && state.playing) setPlaying(false);
  };

  /** Shows the primary run's picture (d = 2), the curves and the status line. */
  const draw = () => {
    const primary = state.runs[0];
    if (!primary) return;
    const lab = primary.lab;
    if (!canvas.hidden) {
      const t0 = performance.now();
      lab.render(canvas.width, canvas.height);
      blit(canvas.getContext('2d'), wasm, lab.frame_ptr(), lab.frame_len());
      state.renderMs.push(performance.now() - t0);
      if (state.renderMs.length > 120) state.renderMs.shift();
    }
    drawPlot(plot, convergence(state.runs.map((r) => ({ name: r.name, curve: r.lab.curve(), budget: r.lab.iterations(), primary: r.primary }))));
    $('lab-status').textContent =
      t('lab.status', { name: primary.name, iteration: lab.iteration(), iterations: lab.iterations(), best: fmt(lab.best_value()), particles: lab.particles() });
  };

  let last = performance.now();
  let fpsFrames = 0;
  const frame = (now) => {
    if (state.playing) {
      step(state.speed);
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
    step(1);
    draw();
  });
  $('lab-reset').addEventListener('click', () => {
    setPlaying(false);
    reset();
  });
  $('lab-speed').addEventListener('input', () => {
    state.speed = Number($('lab-speed').value);
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
  $('lab-ping').addEventListener('click', () => {
    state.pings += 1;
    $('lab-ping-count').textContent = String(state.pings);
  });
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

  reset();
  requestAnimationFrame(frame);

  // For scripts and tests: read-only views of the state.
  window.flockpathLab = {
    play: () => setPlaying(true),
    pause: () => setPlaying(false),
    isPlaying: () => state.playing,
    iteration: () => state.runs[0]?.lab.iteration() ?? 0,
    particles: () => state.runs[0]?.lab.particles() ?? 0,
    positions: () => Array.from(state.runs[0]?.lab.positions() ?? []),
    bestValue: () => state.runs[0]?.lab.best_value(),
    renderMs: () => [...state.renderMs],
    frames: () => state.frames,
    tableSeconds: () => state.lastTableSeconds ?? null,
  };
  window.dispatchEvent(new Event('flockpath-lab-ready'));
});
