// The compare page's metrics table (one column per pane) and overlaid time-series plots (one
// colour per pane). The numbers come from the core (`metrics_json`, `series_json`); this module
// only formats them and says what to draw.

import { drawPlot } from '../core/plot.js';
import { t } from '../core/i18n.js';
import { describeMetric, metricsGlossary } from '../core/metric-words.js';

/**
 * [metrics key, label, format, optional]. Units sit in the label, not in every cell, so four
 * panes' columns fit the side card; each label's hover and the card explain the key. An optional
 * row shows only when the panes' metrics have its key.
 */
const ROWS = [
  ['steps', 'compare.row.steps', (m) => m.steps.toLocaleString('en-US')],
  ['agents', 'compare.row.agents', (m) => m.agents.toLocaleString('en-US')],
  ['arrived_share', 'compare.row.arrived', (m) => (100 * m.arrived_share).toFixed(1)],
  ['waiting_agents', 'compare.row.waiting', (m) => m.waiting_agents.toLocaleString('en-US'), true],
  ['mean_time_to_goal_s', 'compare.row.time_to_goal', (m) => (m.mean_time_to_goal_s == null ? '–' : m.mean_time_to_goal_s.toFixed(1))],
  ['collisions_agent_agent', 'compare.row.collisions', (m) => m.collisions_agent_agent.toLocaleString('en-US')],
  ['penetrations_agent_obstacle', 'compare.row.penetrations', (m) => m.penetrations_agent_obstacle.toLocaleString('en-US')],
  ['mean_path_length', 'compare.row.path_length', (m) => m.mean_path_length.toFixed(0)],
  ['mean_turn_deg', 'compare.row.mean_turn', (m) => m.mean_turn_deg.toFixed(2)],
  ['max_turn_deg', 'compare.row.max_turn', (m) => m.max_turn_deg.toFixed(1)],
  ['mean_speed', 'compare.row.mean_speed', (m) => m.mean_speed.toFixed(2)],
  ['stuck_agents', 'compare.row.stuck', (m) => m.stuck_agents.toLocaleString('en-US')],
];

/** Plot titles per series key. */
const TITLES = {
  arrived_share: 'compare.plot.arrived',
  collisions_agent_agent: 'compare.plot.collisions',
  penetrations_agent_obstacle: 'compare.plot.penetrations',
  speed: 'compare.plot.speed',
  stuck_agents: 'compare.plot.stuck',
};

/**
 * Fills the table: a header row of pane names, one row per metric, one column per pane. The same
 * panes and rows only get their cells' text written again, so a focused row name keeps its focus
 * while the run plays.
 */
export function drawTable(table, panes, metrics) {
  const rows = ROWS.filter(([key, , , optional]) => !optional || metrics.some((m) => typeof m[key] === 'number'));
  const shape = `${t('compare.row.steps')}|${panes.map((p) => `${p.pane}:${p.label}:${p.color}`).join()}|${rows.map((r) => r[0]).join()}`;
  if (table.dataset.shape !== shape) {
    table.dataset.shape = shape;
    const head = document.createElement('thead');
    const top = document.createElement('tr');
    top.append(Object.assign(document.createElement('th'), { textContent: '' }));
    for (const p of panes) {
      const th = Object.assign(document.createElement('th'), { textContent: p.pane, title: p.label, scope: 'col' });
      th.style.setProperty('--pane-color', p.color);
      top.append(th);
    }
    head.append(top);
    const body = document.createElement('tbody');
    for (const [key, label] of rows) {
      const tr = document.createElement('tr');
      tr.dataset.key = key;
      tr.append(describeMetric(Object.assign(document.createElement('th'), { textContent: t(label), scope: 'row' }), key));
      for (let i = 0; i < panes.length; i += 1) tr.append(document.createElement('td'));
      body.append(tr);
    }
    table.replaceChildren(head, body);
  }
  rows.forEach(([, , format], r) => {
    const tr = table.tBodies[0].rows[r];
    metrics.forEach((m, i) => {
      const cell = tr.cells[i + 1];
      const text = cell ? format(m) : '';
      if (cell && cell.textContent !== text) cell.textContent = text;
    });
  });
}

/** The metrics keys of the table's rows: what the compare page's card explains. */
export const TABLE_KEYS = ROWS.map(([key]) => key);

/** Puts the "What do these numbers mean?" card for the table's rows after `table`'s box, once. */
export function explainTable(table) {
  const box = table.closest('.table-scroll') ?? table;
  if (box.nextElementSibling?.classList.contains('metrics-glossary')) return;
  box.after(metricsGlossary(TABLE_KEYS));
}

function plotCanvas(container, key) {
  let figure = container.querySelector(`[data-key="${key}"]`);
  if (!figure) {
    figure = document.createElement('figure');
    figure.className = 'plot';
    figure.dataset.key = key;
    const canvas = document.createElement('canvas');
    const title = TITLES[key] ? t(TITLES[key]) : key;
    canvas.setAttribute('aria-label', title);
    const caption = Object.assign(document.createElement('figcaption'), { textContent: title });
    if (TITLES[key]) caption.dataset.i18n = TITLES[key];
    figure.append(caption, canvas);
    container.append(figure);
  }
  return figure.querySelector('canvas');
}

/** Draws one plot per series key with every pane's line overlaid (core/plot.js draws). */
export function drawPlots(container, series) {
  for (const key of series.keys) {
    let maxStep = 1;
    let maxValue = key === 'arrived_share' ? 1 : 0;
    for (const p of series.panes) {
      maxStep = Math.max(maxStep, p.steps[p.steps.length - 1] ?? 0);
      for (const v of p[key]) maxValue = Math.max(maxValue, v);
    }
    if (maxValue <= 0) maxValue = 1;
    drawPlot(plotCanvas(container, key), {
      lines: series.panes.map((p) => ({ xs: p.steps, ys: p[key], color: p.color, width: 2 })),
      x: { min: 0, max: maxStep },
      y: { min: 0, max: maxValue },
      margin: { left: 4, right: 4, top: 4, bottom: 4 },
      note: maxValue.toLocaleString('en-US', { maximumFractionDigits: 2 }),
    });
  }
}
