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
import { onLanguageChange, setAttr, setText as bindText, t, tOr } from '../core/i18n.js';
import { unitText } from '../core/params-form.js';
import { METRIC_KEYS, describeMetric, metricsGlossary } from '../core/metric-words.js';

/**
 * [key, label key, format, shown in red when above zero, optional]; each name's hover and the
 * card explain the key (core/metric-words.js). An optional row shows only when the metrics have
 * its key (`waiting_agents` comes with goals that fill).
 */
/**
 * The most groups the plots draw one line each: past a dozen the lines are a tangle no one can
 * tell apart (and each is one more series the worker sends every frame); with more groups the
 * plots draw the whole run only and the table below lists each group.
 */
const MAX_PLOTTED_GROUPS = 12;

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

/**
 * Rows the per-group table shows at once; more groups are paged. Every row costs a layout of the
 * whole table when a value changes: 5,000 rows took ~250 ms of the main thread per refresh.
 */
const TABLE_PAGE = 50;

/** The table's pager: `‹ Groups 51–100 of 5,000 ›` (hidden while the groups fit one page). */
function buildPager() {
  const box = document.createElement('div');
  box.className = 'group-pager';
  box.hidden = true;
  const button = (key, text) => {
    const b = document.createElement('button');
    b.type = 'button';
    b.textContent = text;
    setAttr(b, 'aria-label', key);
    setAttr(b, 'title', key);
    return b;
  };
  const previous = button('metrics.groups.previous', '‹');
  const next = button('metrics.groups.next', '›');
  const range = document.createElement('span');
  range.setAttribute('aria-live', 'polite');
  box.append(previous, range, next);
  return { box, previous, next, range };
}

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

  const groupTable = document.getElementById('metrics-groups');
  const plotBox = document.getElementById('plots');
  const plotNote = document.getElementById('plots-note');
  let plots = [];
  /** The groups drawn one line each: all of them, or none when there are more than MAX_PLOTTED_GROUPS. */
  let plotGroups = [];
  /** Whether the plots draw a whole-run line (the scene has more than one group). */
  let plotOverall = false;
  /** What the plots show now (samples, last step, groups): unchanged history, no redraw. */
  let plotted = null;
  const plotTip = ({ label, unit }) => t(plotGroups.length > 0 || !plotOverall ? 'plots.tip' : 'plots.tip.overall', { label, unit });
  const buildPlots = () => {
    const meta = app.guard((sim) => JSON.parse(sim.history_json()));
    if (!meta.ok || !plotBox) return;
    const { groups } = meta.value;
    plotGroups = groups.length <= MAX_PLOTTED_GROUPS ? groups : [];
    plotOverall = groups.length > 1;
    if (plotNote) {
      if (groups.length <= MAX_PLOTTED_GROUPS) bindText(plotNote, 'plots.note');
      else bindText(plotNote, 'plots.note.overall', { groups: groups.length.toLocaleString('en-US'), max: MAX_PLOTTED_GROUPS });
    }
    plotted = null;
    const keys = meta.value.series.map((s) => s.key).join();
    if (plots.map((p) => p.key).join() === keys) {
      for (const plot of plots) plot.canvas.title = plotTip(plot);
      return;
    }
    plotBox.replaceChildren();
    plots = meta.value.series.map((series) => {
      const canvas = document.createElement('canvas');
      canvas.className = 'plot';
      canvas.dataset.key = series.key;
      const label = tOr(`series.${series.key}`, series.label);
      const unit = unitText(series.unit);
      const plot = { ...series, label, unit, canvas };
      canvas.title = plotTip(plot);
      plotBox.append(canvas);
      return plot;
    });
  };
  const drawPlots = () => {
    if (!plotBox || plotBox.closest('details')?.open === false) {
      plotted = null;
      return;
    }
    const result = app.guard((sim) => {
      const steps = sim.history_steps();
      const shown = `${steps.length}:${steps.at(-1)}:${plotOverall}:${plotGroups.map((g) => g.color).join()}`;
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
        // Beside the groups' lines the whole run's is thin; alone it is drawn at the usual width.
        if (plotOverall) lines.push({ values: series(p.key, -1), color: OVERALL_COLOR, width: plotGroups.length > 0 ? 1 : undefined });
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
  /** The first group the table shows (a multiple of TABLE_PAGE). */
  let pageStart = 0;
  const pager = groupTable ? buildPager() : null;
  groupTable?.parentElement.after(pager.box);
  const turn = (by) => {
    pageStart = Math.max(0, pageStart + by * TABLE_PAGE);
    forced = true;
  };
  pager?.previous.addEventListener('click', () => turn(-1));
  pager?.next.addEventListener('click', () => turn(1));
  /** Shows the pager when the groups fill more than one page, saying which ones the table shows. */
  const showPager = (total) => {
    const paged = total > TABLE_PAGE;
    if (pager.box.hidden === paged) pager.box.hidden = !paged;
    if (!paged) return;
    const to = Math.min(pageStart + TABLE_PAGE, total);
    bindText(pager.range, 'metrics.groups.page', { from: WHOLE.format(pageStart + 1), to: WHOLE.format(to), total: WHOLE.format(total) });
    pager.previous.disabled = pageStart === 0;
    pager.next.disabled = to >= total;
  };
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
    const total = m.groups.length;
    pageStart = Math.min(pageStart, Math.max(0, Math.floor((total - 1) / TABLE_PAGE) * TABLE_PAGE));
    const shownGroups = m.groups.slice(pageStart, pageStart + TABLE_PAGE);
    showPager(total);
    while (body.rows.length > shownGroups.length) body.deleteRow(-1);
    while (body.rows.length < shownGroups.length) {
      const row = body.insertRow();
      for (let c = 0; c <= columns.length; c += 1) row.insertCell();
    }
    shownGroups.forEach((g, k) => {
      const i = pageStart + k;
      const row = body.rows[k];
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
