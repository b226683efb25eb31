// The live metrics readout, the per-group table, the time-series plots and the FPS counter.
// Values come from `metrics_json()` (DESIGN §4 keys) and the core's metrics history
// (`history_series`); wall-clock time is used only to throttle the readout and to count frames.
//
// The readout is on the page's refresh path, so it is kept cheap: it refreshes every REFRESH_MS
// but never takes more than READOUT_SHARE of the main thread (a refresh that cost c ms waits
// c / READOUT_SHARE ms before the next one), the plots are redrawn only when the history gained
// a sample, and a cell is written only when its text changed (a write costs a style and layout
// pass of the whole page).

import { drawPlot, formatTick } from '../core/plot.js';
import { Pending } from '../core/sim-proxy.js';
import { onLanguageChange, setText as bindText, t, tOr } from '../core/i18n.js';
import { unitText } from '../core/params-form.js';
import { METRIC_KEYS, describeMetric, metricsGlossary } from '../core/metric-words.js';

/**
 * [key, label key, format, shown in red when above zero, optional]; each name's hover and the
 * card explain the key (core/metric-words.js). An optional row shows only when the metrics have
 * its key (`waiting_agents` comes with goals that fill).
 */
const ROWS = [
  ['steps', 'metrics.steps', (m) => m.steps.toLocaleString('en-US')],
  ['agents', 'metrics.agents', (m) => m.agents.toLocaleString('en-US')],
  ['arrived_share', 'metrics.arrived', (m) => `${(100 * m.arrived_share).toFixed(1)} %`],
  ['waiting_agents', 'metrics.waiting', (m) => waitingText(m), false, true],
  ['collisions_agent_agent', 'metrics.collisions', (m) => m.collisions_agent_agent.toLocaleString('en-US')],
  ['penetrations_agent_obstacle', 'metrics.penetrations', (m) => m.penetrations_agent_obstacle.toLocaleString('en-US'), true],
  ['mean_speed', 'metrics.mean_speed', (m) => `${m.mean_speed.toFixed(2)} ${unitText('px/step')}`],
  ['stuck_agents', 'metrics.stuck', (m) => m.stuck_agents.toLocaleString('en-US'), true],
];

/** The metrics the Metrics card explains: its rows' and columns' keys, in the card's order. */
const EXPLAINED = METRIC_KEYS.filter((key) =>
  ['steps', 'agents', 'arrived_share', 'waiting_agents', 'waiting_share', 'collisions_agent_agent',
    'penetrations_agent_obstacle', 'mean_speed', 'stuck_agents', 'queue_order', 'fitness'].includes(key));

/** Waiting agents, with their share when the metrics give it: `3 (5.0 %)`. */
function waitingText(m) {
  const count = m.waiting_agents.toLocaleString('en-US');
  return typeof m.waiting_share === 'number' ? `${count} (${(100 * m.waiting_share).toFixed(1)} %)` : count;
}

/** How often the readout refreshes (ms): fast enough to feel live, slow enough to read. */
const REFRESH_MS = 250;
/** Most of the main thread the readout may use: an expensive refresh comes less often. */
const READOUT_SHARE = 0.05;

/** Sets a node's text only when it changed. */
function setText(node, text) {
  if (node.textContent !== text) node.textContent = text;
}

/** Whole numbers with thousands separators; one format for every cell (each toLocaleString builds its own). */
const WHOLE = new Intl.NumberFormat('en-US');

/**
 * Per-group table columns: [key, heading key, format, optional]; the heading's hover explains the
 * key. An optional column shows only when the groups' metrics have its key.
 */
const GROUP_COLUMNS = [
  ['arrived_share', 'metrics.col.arrived', (v) => `${Math.round(100 * v)}%`],
  ['waiting_agents', 'metrics.col.waiting', (v) => WHOLE.format(v), true],
  ['collisions_agent_agent', 'metrics.col.collisions', (v) => WHOLE.format(v)],
  ['penetrations_agent_obstacle', 'metrics.col.penetrations', (v) => WHOLE.format(v)],
  ['stuck_agents', 'metrics.col.stuck', (v) => String(v)],
  ['queue_order', 'metrics.col.queue', (v) => (v === null ? '–' : v.toFixed(2))],
  ['fitness', 'metrics.col.gsum', (v) => (v ? v.gsum.toFixed(1) : '–')],
];

/** Colour of the whole-run line in the plots. */
const OVERALL_COLOR = '#17202c';

export function setupMetrics(app) {
  const list = document.getElementById('metrics');
  const fps = document.getElementById('fps');
  const cells = new Map();
  for (const [key, label, , , optional] of ROWS) {
    const dt = describeMetric(bindText(document.createElement('dt'), label), key);
    const dd = document.createElement('dd');
    dd.dataset.key = key;
    dd.textContent = '–';
    dt.hidden = dd.hidden = Boolean(optional);
    list.append(dt, dd);
    cells.set(key, dd);
  }
  // The card sits below the per-group table, closed until asked for.
  (list.closest('section') ?? list.parentElement).append(metricsGlossary(EXPLAINED));
  let lastRefresh = -Infinity;
  let refreshEvery = REFRESH_MS;
  let frames = 0;
  let fpsSince = null;
  let forced = true;
  const force = () => (forced = true);
  app.addEventListener('stepped', force);
  app.addEventListener('scene', force);
  // Paused, a frame from the worker is the only news: it brings the state after a step, a load or
  // a seek, and the plots' series the panel asked for (the first read of a series only asks).
  // While playing, the refresh interval paces the panel instead.
  app.remote?.addEventListener('frame', () => {
    if (!app.playing) forced = true;
  });
  // Paused, a frame from the worker is the only news: it brings the state after a step, a load or
  // a seek, and the plots' series the panel asked for (the first read of a series only asks).
  // While playing, the refresh interval paces the panel instead.
  app.remote?.addEventListener('frame', () => {
    if (!app.playing) forced = true;
  });

  const groupTable = document.getElementById('metrics-groups');
  const plotBox = document.getElementById('plots');
  let plots = [];
  let plotGroups = [];
  /** What the plots show now (samples, last step, groups): unchanged history, no redraw. */
  let plotted = null;
  const buildPlots = () => {
    const meta = app.guard((sim) => JSON.parse(sim.history_json()));
    if (!meta.ok || !plotBox) return;
    plotGroups = meta.value.groups;
    plotted = null;
    const keys = meta.value.series.map((s) => s.key).join();
    if (plots.map((p) => p.key).join() === keys) return;
    plotBox.replaceChildren();
    plots = meta.value.series.map((series) => {
      const canvas = document.createElement('canvas');
      canvas.className = 'plot';
      canvas.dataset.key = series.key;
      const label = tOr(`series.${series.key}`, series.label);
      const unit = unitText(series.unit);
      canvas.title = t('plots.tip', { label, unit });
      plotBox.append(canvas);
      return { ...series, label, unit, canvas };
    });
  };
  const drawPlots = () => {
    if (!plotBox || plotBox.closest('details')?.open === false) {
      plotted = null;
      return;
    }
    const result = app.guard((sim) => {
      const steps = sim.history_steps();
      const shown = `${steps.length}:${steps.at(-1)}:${plotGroups.map((g) => g.color).join()}`;
      if (shown === plotted) return [];
      // A series' first read only asks the worker for it: ask for all of them in one go, and draw
      // (and remember what is drawn) only once every one has arrived.
      let pending = null;
      const series = (key, group) => {
        try {
          return sim.history_series(key, group);
        } catch (error) {
          if (!(error instanceof Pending)) throw error;
          pending = error;
          return null;
        }
      };
      const drawn = plots.map((p) => {
        const lines = plotGroups.map((g, i) => ({ values: series(p.key, i), color: g.color }));
        if (plotGroups.length > 1) lines.push({ values: series(p.key, -1), color: OVERALL_COLOR, width: 1 });
        return { plot: p, steps, lines };
      });
      if (pending) throw pending;
      plotted = shown;
      return drawn;
    });
    if (!result.ok) return;
    for (const { plot, steps, lines } of result.value) {
      // What the chart shows, for scripts and tests: the samples and the last step drawn.
      plot.canvas.dataset.samples = String(steps.length);
      plot.canvas.dataset.lastStep = String(steps.at(-1) ?? '');
      drawPlot(plot.canvas, overTime(steps, lines, plot));
    }
  };
  /** The columns shown now (optional ones only when the metrics have their key). */
  let columns = [];
  const fillGroups = (m) => {
    if (!groupTable) return;
    const body = groupTable.tBodies[0] ?? groupTable.createTBody();
    const shown = GROUP_COLUMNS.filter(([key, , , optional]) => !optional || (m.groups[0] ?? m)[key] !== undefined);
    if (!groupTable.tHead || shown.length !== columns.length) {
      columns = shown;
      groupTable.tHead?.remove();
      body.replaceChildren();
      const head = groupTable.createTHead().insertRow();
      const group = bindText(document.createElement('th'), 'metrics.col.group');
      head.append(group);
      for (const [key, heading] of columns) {
        const th = describeMetric(bindText(document.createElement('th'), heading), key);
        th.scope = 'col';
        head.append(th);
      }
    }
    while (body.rows.length > m.groups.length) body.deleteRow(-1);
    while (body.rows.length < m.groups.length) {
      const row = body.insertRow();
      for (let c = 0; c <= columns.length; c += 1) row.insertCell();
    }
    m.groups.forEach((g, i) => {
      const row = body.rows[i];
      row.dataset.group = String(i);
      const color = app.scene.groups?.[i]?.color ?? '#888';
      const name = row.cells[0];
      const label = `${g.name ?? i + 1} (${g.planner ?? ''})`;
      if (name.dataset.color !== color || name.dataset.label !== label) {
        name.dataset.color = color;
        name.dataset.label = label;
        name.replaceChildren();
        const swatch = document.createElement('span');
        swatch.className = 'swatch';
        swatch.style.background = color;
        name.append(swatch, label);
      }
      columns.forEach(([key, , format], c) => {
        const value = g[key];
        setText(row.cells[c + 1], value === undefined ? '–' : format(value));
        row.cells[c + 1].classList.toggle('bad', (key === 'stuck_agents' || key === 'penetrations_agent_obstacle') && value > 0);
      });
    });
  };
  // Groups (names, colours) change with the scene; the series list never does.
  app.addEventListener('scene', buildPlots);
  buildPlots();
  // A language switch: the plots' titles are drawn on their canvases, so build and draw them again.
  onLanguageChange(() => {
    plots = [];
    buildPlots();
    forced = true;
  });

  const refresh = () => {
    const result = app.guard((sim) => JSON.parse(sim.metrics_json()));
    if (!result.ok) return;
    const m = result.value;
    // The plots read their canvas sizes: draw them before any text write, or the read would
    // force a second layout pass in this frame.
    drawPlots();
    fillGroups(m);
    for (const [key, , format, badWhenPositive, optional] of ROWS) {
      const cell = cells.get(key);
      if (optional) {
        const absent = typeof m[key] !== 'number';
        if (cell.hidden !== absent) cell.hidden = cell.previousElementSibling.hidden = absent;
      }
      if (typeof m[key] !== 'number') {
        setText(cell, '–');
        continue;
      }
      setText(cell, format(m));
      cell.classList.toggle('bad', Boolean(badWhenPositive) && m[key] > 0);
    }
  };

  /** Called by the frame loop after every frame. */
  return (now) => {
    frames += 1;
    if (fpsSince === null) fpsSince = now;
    if (now - fpsSince >= 1000) {
      setText(fps, t('metrics.fps', { n: Math.round((frames * 1000) / (now - fpsSince)) }));
      frames = 0;
      fpsSince = now;
    }
    if (forced || (app.playing && now - lastRefresh >= refreshEvery)) {
      forced = false;
      lastRefresh = now;
      const started = performance.now();
      refresh();
      refreshEvery = Math.max(REFRESH_MS, (performance.now() - started) / READOUT_SHARE);
    }
  };
}

/**
 * One metric over time as a chart: a line per group (`values`: Float32Array over `steps`, NaN a
 * gap), the axis from 0 (or below) to the largest value, which the second line states.
 */
function overTime(steps, lines, { label, unit }) {
  let lo = 0;
  let hi = -Infinity;
  for (const line of lines) {
    for (const v of line.values) {
      if (Number.isFinite(v)) {
        lo = Math.min(lo, v);
        hi = Math.max(hi, v);
      }
    }
  }
  return {
    lines: lines.map((line) => ({ xs: steps, ys: line.values, color: line.color, width: line.width })),
    x: { min: steps[0] ?? 0, max: steps.at(-1) ?? 1 },
    y: { min: lo, max: hi - lo < 1e-9 ? lo + 1 : hi },
    margin: { left: 2, right: 2, top: 24, bottom: 3 },
    yTicks: [{ value: 0 }],
    font: 10,
    title: label,
    note: t('plots.max', { value: formatTick(hi), unit }).trim(),
    empty: t('plots.empty'),
    background: '#ffffff',
  };
}
