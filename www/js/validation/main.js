// The Validation page: pick planners and tests, run the suite in a Web Worker (progress,
// Cancel), fill the table (each test linked to its scene in the playground), plot the T4
// fundamental diagram per planner against Weidmann's curve (speed–density and flow–density side by
// side) and the T8 sweep, and say how each test is measured. Every number comes from the wasm
// core; this module only lays them out.

import { errorFromData, messageOf, setupBanner, showMessage } from '../core/errors.js';
import { drawPlot } from '../core/plot.js';
import { onLanguageChange, t, tOr } from '../core/i18n.js';
import { messageText } from '../core/messages.js';

/** A row's measurement in the page's language: its message (`words`, a code with its figures) worded from the message files; the core's English when a row has none. */
function measuredText(words, english) {
  return typeof words?.code === 'string' ? messageText(words.code, words.args ?? {}) ?? english : english;
}

const $ = (id) => document.getElementById(id);

/** Line colours of the planners in the plot, in menu order. */
const COLORS = ['#2f6fdf', '#d9482b', '#2b9d48', '#a23bc4', '#d49a1c', '#1c9aa8', '#7a5230', '#555555'];

/** Tests picked by default: the quick ones (the whole suite takes minutes in a browser). */
const DEFAULT_TESTS = new Set(['t1-free-walking', 'juelich-head-on', 't6-corner', 't4-fundamental-diagram']);

/** The fundamental diagram's density axis (persons/m²): Weidmann's curve is drawn at these. */
const CURVE_DENSITIES = Float64Array.from({ length: 60 }, (_, i) => 0.1 * (i + 1));

/**
 * Lines (each `{xs, ys, color, width, dots}`) from 0 up, a tick at each of `xTicks`; the axis
 * labels and the legend are HTML beside the canvas (validation.html), so they are text a reader
 * can select and a screen reader reads.
 */
function plotLines(canvas, lines, xTicks, empty) {
  const finite = (values) => Array.from(values).filter(Number.isFinite);
  const ys = lines.flatMap((l) => finite(l.ys));
  const xs = lines.flatMap((l) => finite(l.xs)).concat(xTicks);
  const top = ys.length ? Math.max(...ys) * 1.05 || 1 : 1;
  drawPlot(canvas, {
    lines: lines.map((l) => ({ xs: l.xs, ys: l.ys, color: l.color, width: l.width ?? 1.5, dots: l.dots ?? true })),
    x: { min: Math.min(0, ...xs), max: Math.max(...xs) },
    y: { min: 0, max: top },
    margin: { left: 38, right: 12, top: 8, bottom: 20 },
    yTicks: [0, top / 2, top].map((v) => ({ value: v, text: v.toFixed(v < 10 ? 2 : 0) })),
    xTicks: xTicks.map((v) => ({ value: v, text: String(v) })),
    empty,
    background: '#ffffff',
  });
}

/** Fills a legend: a line key (with a dot for measured points) and a name per entry. */
function fillLegend(legend, entries) {
  legend.replaceChildren(
    ...entries.map(({ name, color, dots }) => {
      const entry = Object.assign(document.createElement('span'), { className: 'entry' });
      entry.style.color = color;
      const key = Object.assign(document.createElement('span'), { className: dots ? 'key dots' : 'key' });
      key.setAttribute('aria-hidden', 'true');
      const label = Object.assign(document.createElement('span'), { textContent: name });
      label.style.color = 'var(--ink)';
      entry.append(key, label);
      return entry;
    }),
  );
}

/** Column `name` of curve `c` as numbers (NaN where the run gave none). */
function column(c, name) {
  const i = c.columns.indexOf(name);
  return c.rows.map((r) => (i < 0 || r[i] === null ? NaN : r[i]));
}

async function boot() {
  setupBanner();
  const module = await import('../../pkg/flockpath.js');
  await module.default();
  const options = JSON.parse(module.validation_options_json());
  // The tests' titles and criteria in the page's language (keys by test id; the core's words otherwise).
  const titleOf = (test) => tOr(`validation.test.${test.id}`, test.title);
  const criterionOf = (test) => tOr(`validation.test.${test.id}.criterion`, test.criterion);
  const titles = new Map(options.tests.map((test) => [test.id, titleOf(test)]));
  const criteria = new Map(options.tests.map((test) => [test.id, [test.criterion, criterionOf(test)]]));
  const colorOf = new Map(options.planners.map((p, i) => [p.name, COLORS[i % COLORS.length]]));

  const picks = (box, items, checked) => {
    for (const item of items) {
      const label = document.createElement('label');
      label.className = 'check';
      const input = Object.assign(document.createElement('input'), { type: 'checkbox', value: item.value, checked: checked(item.value) });
      label.append(input, ` ${item.label}`);
      label.title = item.title ?? '';
      box.append(label);
    }
  };
  picks($('val-planners'), options.planners.map((p) => ({ value: p.name, label: p.name, title: tOr(`planner.${p.name}`, p.label) })), () => true);
  picks($('val-tests'), options.tests.map((test) => ({ value: test.id, label: test.id, title: `${titleOf(test)} — ${criterionOf(test)}` })), (id) => DEFAULT_TESTS.has(id));
  const checked = (box) => [...$(box).querySelectorAll('input:checked')].map((i) => i.value);

  const state = { worker: null, curves: [], rows: 0, passed: 0 };
  const tbody = $('val-table').querySelector('tbody');

  const addRow = (row) => {
    const tr = document.createElement('tr');
    tr.dataset.test = row.test;
    tr.dataset.planner = row.planner;
    const test = document.createElement('td');
    const link = Object.assign(document.createElement('a'), { textContent: titles.get(row.test) ?? row.test, target: '_blank' });
    if (row.scene) link.href = `index.html#s=${row.scene}`;
    link.className = 'scene-link';
    link.title = t('validation.open_title');
    test.append(link);
    const [coreCriterion, criterion] = criteria.get(row.test) ?? [];
    const shown = row.criterion === coreCriterion ? criterion : row.criterion;
    const cells = [row.planner, measuredText(row.words, row.measured), shown].map((text) => Object.assign(document.createElement('td'), { textContent: text }));
    // The core's English and its message, to word the cell again after a language switch.
    cells[1].dataset.measured = row.measured;
    cells[1].dataset.words = JSON.stringify(row.words ?? null);
    const result = Object.assign(document.createElement('td'), { textContent: row.pass ? t('validation.pass') : t('validation.fail'), className: row.pass ? 'pass' : 'fail' });
    tr.append(test, ...cells, result);
    tbody.append(tr);
    state.rows += 1;
    if (row.pass) state.passed += 1;
  };

  // The T4 curves' columns (src/experiments/validation/suite.rs): the density measured in the
  // area, the mean speed and the specific flow J_s = ρ·v, all computed by the core.
  const DENSITY = 'density_measured_persons_per_m2';
  const SPEED = 'speed_m_s';
  const FLOW = 'specific_flow_persons_m_s';
  const weidmannSpeeds = module.validation_reference_speeds('weidmann', CURVE_DENSITIES);
  const weidmannFlows = module.validation_reference_specific_flows(CURVE_DENSITIES);
  const densityTicks = [0, 1, 2, 3, 4, 5, 6];

  const drawDiagram = () => {
    const diagrams = state.curves.filter((c) => c.test === 't4-fundamental-diagram');
    const reference = { name: t('validation.weidmann'), color: '#111111', dots: false };
    const entries = [reference, ...diagrams.map((c) => ({ name: c.planner, color: colorOf.get(c.planner) ?? '#888', dots: true }))];
    const speedLines = [{ xs: CURVE_DENSITIES, ys: weidmannSpeeds, color: reference.color, width: 2.5, dots: false }];
    const flowLines = [{ xs: CURVE_DENSITIES, ys: weidmannFlows, color: reference.color, width: 2.5, dots: false }];
    for (const c of diagrams) {
      const color = colorOf.get(c.planner) ?? '#888';
      const xs = column(c, DENSITY);
      speedLines.push({ xs, ys: column(c, SPEED), color });
      flowLines.push({ xs, ys: column(c, FLOW), color });
    }
    fillLegend($('val-legend'), entries);
    fillLegend($('val-flow-legend'), entries);
    plotLines($('val-plot'), speedLines, densityTicks, t('plots.empty'));
    plotLines($('val-flow'), flowLines, densityTicks, t('plots.empty'));
  };

  const drawSweep = () => {
    const sweeps = state.curves.filter((c) => c.test === 't8-speed-sweep');
    const speeds = sweeps[0]?.rows.map((r) => r[0]) ?? [0.8, 1.6];
    // Column 1 is the evacuation time (s), null when someone was still inside after 60 s.
    const lines = sweeps.map((c) => ({ xs: speeds, ys: c.rows.map((r) => (r[1] === null ? NaN : r[1])), color: colorOf.get(c.planner) ?? '#888' }));
    fillLegend($('val-sweep-legend'), sweeps.map((c) => ({ name: c.planner, color: colorOf.get(c.planner) ?? '#888', dots: true })));
    plotLines($('val-sweep'), lines, speeds, t('plots.empty'));
  };

  // One paragraph per test: its set-up, how it is measured and its criterion, in
  // docs/validation.md's words (the core holds them; tests/validation_words.rs keeps them equal).
  const describeTests = () => {
    $('val-methods').replaceChildren(
      ...options.tests.map((test) => {
        const p = document.createElement('p');
        p.dataset.test = test.id;
        const title = Object.assign(document.createElement('strong'), { textContent: `${titleOf(test)}. ` });
        const words = t('validation.method', {
          setup: tOr(`validation.test.${test.id}.setup`, test.setup),
          measurement: tOr(`validation.test.${test.id}.measurement`, test.measurement),
          criterion: criterionOf(test),
        });
        p.append(title, words);
        return p;
      }),
    );
  };
  describeTests();

  const finish = (text) => {
    state.worker?.terminate();
    state.worker = null;
    $('val-run').disabled = false;
    $('val-cancel').disabled = true;
    $('val-progress-text').textContent = text;
  };

  $('val-run').addEventListener('click', () => {
    const planners = checked('val-planners');
    const tests = checked('val-tests');
    if (planners.length === 0 || tests.length === 0) {
      showMessage(t('validation.pick'));
      return;
    }
    tbody.replaceChildren();
    state.curves = [];
    state.rows = 0;
    state.passed = 0;
    $('val-summary').textContent = '';
    drawDiagram();
    drawSweep();
    $('val-run').disabled = true;
    $('val-cancel').disabled = false;
    const worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
    state.worker = worker;
    worker.onmessage = ({ data }) => {
      if (data.type === 'progress') {
        $('val-progress').value = data.done / data.total;
        $('val-progress-text').textContent = t('validation.progress', { done: data.done, total: data.total, test: data.test, planner: data.planner });
      } else if (data.type === 'outcome') {
        $('val-progress').value = data.done / data.total;
        for (const row of data.outcome.rows) addRow(row);
        state.curves.push(...data.outcome.curves);
        drawDiagram();
        drawSweep();
      } else if (data.type === 'done') {
        $('val-progress').value = 1;
        $('val-summary').textContent = t('validation.summary', { passed: state.passed, rows: state.rows, seconds: data.seconds.toFixed(1) });
        finish(t('validation.done'));
      } else if (data.type === 'error') {
        showMessage(messageOf(errorFromData(data.error)));
        finish(t('validation.stopped'));
      }
    };
    worker.onerror = (e) => {
      showMessage(messageOf(e));
      finish(t('validation.stopped'));
    };
    worker.postMessage({ tests, planners });
  });

  $('val-cancel').addEventListener('click', () => finish(t('lab.cancelled')));
  drawDiagram();
  drawSweep();
  // The plots' axes and empty notes are drawn on canvases: draw them again in a new language.
  onLanguageChange(() => {
    drawDiagram();
    drawSweep();
    describeTests();
    for (const cell of tbody.querySelectorAll('td[data-measured]')) cell.textContent = measuredText(JSON.parse(cell.dataset.words ?? 'null'), cell.dataset.measured);
  });
  window.flockpathValidation = { rows: () => state.rows, running: () => state.worker !== null };
}

boot().catch((error) => showMessage(messageOf(error)));
