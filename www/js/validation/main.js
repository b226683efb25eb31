// The Validation page: pick planners and tests, run the suite in a Web Worker (progress,
// Cancel), fill the table (each test linked to its scene in the playground) and plot the
// fundamental diagram of T4 per planner against Weidmann's curve and the T8 sweep. Every number comes from
// the wasm core; this module only lays them out.

import { errorFromData, messageOf, setupBanner, showMessage } from '../core/errors.js';
import { drawPlot } from '../core/plot.js';
import { onLanguageChange, t, tOr } from '../core/i18n.js';
import { measuredText } from './measured.js';

const $ = (id) => document.getElementById(id);

/** Line colours of the planners in the plot, in menu order. */
const COLORS = ['#2f6fdf', '#d9482b', '#2b9d48', '#a23bc4', '#d49a1c', '#1c9aa8', '#7a5230', '#555555'];

/** Tests picked by default: the quick ones (the whole suite takes minutes in a browser). */
const DEFAULT_TESTS = new Set(['t1-free-walking', 'juelich-head-on', 't6-corner', 't4-fundamental-diagram']);

/** Lines over shared x values (`xs`) on a linear scale from 0, a tick at each x. */
function plotOver(canvas, xs, lines, title, empty) {
  const finite = lines.flatMap((l) => Array.from(l.ys).filter(Number.isFinite));
  const top = finite.length ? Math.max(...finite) * 1.05 : 1;
  drawPlot(canvas, {
    lines: lines.map((l) => ({ xs, ys: l.ys, color: l.color, width: l.width ?? 1.5, dots: true, name: l.name })),
    x: { min: Math.min(...xs), max: Math.max(...xs) },
    y: { min: 0, max: top },
    margin: { left: 38, right: 10, top: 18, bottom: 20 },
    yTicks: [0, top / 2, top].map((v) => ({ value: v, text: v.toFixed(v < 10 ? 2 : 0) })),
    xTicks: xs.map((v) => ({ value: v, text: String(v) })),
    title,
    empty,
    background: '#ffffff',
  });
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
    const cells = [row.planner, measuredText(row.measured), shown].map((text) => Object.assign(document.createElement('td'), { textContent: text }));
    // The core's words, to word the cell again after a language switch.
    cells[1].dataset.measured = row.measured;
    const result = Object.assign(document.createElement('td'), { textContent: row.pass ? t('validation.pass') : t('validation.fail'), className: row.pass ? 'pass' : 'fail' });
    tr.append(test, ...cells, result);
    tbody.append(tr);
    state.rows += 1;
    if (row.pass) state.passed += 1;
  };

  const drawDiagram = () => {
    const diagrams = state.curves.filter((c) => c.test === 't4-fundamental-diagram');
    const densities = diagrams[0]?.rows.map((r) => r[0]) ?? [0.5, 1, 2, 3, 4, 5, 6];
    const reference = module.validation_reference_speeds('weidmann', Float64Array.from(densities));
    const lines = [{ ys: reference, color: '#111111', width: 2.5, name: 'Weidmann' }];
    const legend = $('val-legend');
    legend.replaceChildren(Object.assign(document.createElement('span'), { textContent: '━ Weidmann (1993)', style: 'color:#111' }));
    for (const c of diagrams) {
      // Column 2 is the measured speed (m/s), null where the run gave none.
      lines.push({ ys: c.rows.map((r) => (r[2] === null ? NaN : r[2])), color: colorOf.get(c.planner) ?? '#888', name: c.planner });
      const span = Object.assign(document.createElement('span'), { textContent: `━ ${c.planner}` });
      span.style.color = colorOf.get(c.planner) ?? '#888';
      legend.append(span);
    }
    plotOver($('val-plot'), densities, lines, t('validation.fd_axes'), t('plots.empty'));
  };

  const drawSweep = () => {
    const sweeps = state.curves.filter((c) => c.test === 't8-speed-sweep');
    if (sweeps.length === 0) {
      plotOver($('val-sweep'), [0.8, 1.6], [], t('validation.sweep_axes'), t('plots.empty'));
      return;
    }
    const speeds = sweeps[0].rows.map((r) => r[0]);
    // Column 1 is the evacuation time (s), null when someone was still inside after 60 s.
    const lines = sweeps.map((c) => ({ ys: c.rows.map((r) => (r[1] === null ? NaN : r[1])), color: colorOf.get(c.planner) ?? '#888', name: c.planner }));
    const legend = $('val-sweep-legend');
    // The planners' legend replaces the hint: a language switch must not write the hint back.
    delete legend.dataset.i18n;
    legend.replaceChildren(...sweeps.map((c) => {
      const span = Object.assign(document.createElement('span'), { textContent: `━ ${c.planner}` });
      span.style.color = colorOf.get(c.planner) ?? '#888';
      return span;
    }));
    plotOver($('val-sweep'), speeds, lines, t('validation.sweep_axes'), t('plots.empty'));
  };

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
    for (const cell of tbody.querySelectorAll('td[data-measured]')) cell.textContent = measuredText(cell.dataset.measured);
  });
  window.flockpathValidation = { rows: () => state.rows, running: () => state.worker !== null };
}

boot().catch((error) => showMessage(messageOf(error)));
