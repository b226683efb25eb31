// The compare page's panes: one canvas each with a header (name, planner picker, label, remove)
// and a parameter form generated from the planner table (`planners_json`), plus the pane's spec
// text for per-group planners. Each pane's frame comes from the simulation worker as pixels
// (drawPanes).

import { drawFrame } from '../core/remote-loop.js';
import { paramControl, paramLabel, paramReadout } from '../core/params-form.js';
import { language, onLanguageChange, t, tOr } from '../core/i18n.js';
import { backingSize } from '../core/view.js';

const el = (tag, props = {}, ...children) => {
  const node = Object.assign(document.createElement(tag), props);
  node.append(...children);
  return node;
};

/** Canvas size for one pane: half the pane area's width (two columns), 16:10. */
export function measurePane() {
  const area = document.getElementById('panes');
  const columns = getComputedStyle(area).gridTemplateColumns.split(' ').length || 2;
  const cssWidth = Math.max(200, (area.clientWidth - 10 * (columns - 1)) / columns);
  return backingSize(cssWidth, cssWidth / 1.6, null);
}

/**
 * Draws a frame of the simulation worker into the pane canvases: one view per pane, all of the
 * frame's size (a canvas whose pane was just added or resized takes that size).
 */
export function drawPanes(frame, canvases) {
  canvases.forEach((canvas, i) => {
    const pixels = frame.panes[i];
    if (!pixels) return;
    if (canvas.width !== frame.width || canvas.height !== frame.height) {
      canvas.width = frame.width;
      canvas.height = frame.height;
    }
    drawFrame(canvas, pixels, frame.width, frame.height);
  });
}

function paramForm(app, index, pane) {
  const spec = app.planners.find((p) => p.name === pane.planner);
  const form = el('div', { className: 'form' });
  for (const p of spec?.params ?? []) {
    const id = `pane-${index}-${p.key}`;
    const value = pane.params?.[p.key];
    const readout = p.choices?.length ? null : el('output', { textContent: paramReadout(p, value) });
    const input = paramControl(p, {
      id,
      value,
      planner: pane.planner,
      onInput: (v) => (readout.textContent = paramReadout(p, v)),
      onChange: (v) => app.change((sim) => sim.set_pane_param(index, p.key, JSON.stringify(v))),
    });
    form.append(el('label', { className: 'param', htmlFor: id }, el('span', { textContent: paramLabel(pane.planner, p) }), input, readout ?? el('span')));
  }
  return form;
}

/**
 * A pane's label in the page's language: the core's words (its planner and up to two parameters
 * that differ from their defaults, or per group `group: planner, …`) on English pages; elsewhere
 * the same composed from the translated planner names and parameter labels (group names are the
 * scene's own).
 */
export function paneLabel(app, pane) {
  if (language() === 'en') return pane.label;
  // Every group's planner as the pane runs it (the scene's, the pane's for all, or per group).
  const groups = pane.groups ?? [];
  if (groups.length === 0) return t('compare.no_groups');
  const configs = groups.map((g) => JSON.stringify([g.planner, g.params]));
  if (configs.every((c) => c === configs[0])) return describe(app, groups[0].planner, groups[0].params) ?? pane.label;
  const parts = groups.map((g) => {
    const planner = describe(app, g.planner, g.params);
    return planner === null ? null : t('compare.label_group', { group: g.name, planner });
  });
  return parts.includes(null) ? pane.label : parts.join(t('list.semicolon'));
}

/** `planner, label value, label value` in the page's language (null for an unknown planner). */
function describe(app, kind, params) {
  const planner = app.planners.find((p) => p.name === kind);
  if (!planner) return null;
  const changed = [];
  for (const spec of planner.params) {
    const value = params?.[spec.key];
    const fallback = spec.choices?.length ? spec.choices[spec.default] : spec.default;
    if (value === undefined || value === fallback) continue;
    if (typeof value === 'number' && Math.abs(value - fallback) <= 1e-6 * Math.max(1, Math.abs(fallback))) continue;
    changed.push(`${paramLabel(planner.name, spec)} ${typeof value === 'string' ? tOr(`choice.${value}`, value) : value}`);
  }
  const name = tOr(`planner.${planner.name}`, planner.label).replace(/\s*[（(].*[)）]$/, '');
  if (changed.length === 0) return name;
  const list = changed.slice(0, 2).join(t('list.comma'));
  return changed.length <= 2
    ? t('compare.label_changed', { name, changed: list })
    : t('compare.label_more', { name, changed: list, n: changed.length - 2 });
}

function paneElement(app, index, pane, count) {
  const label = paneLabel(app, pane);
  const canvas = el('canvas', { className: 'pane-canvas' });
  canvas.setAttribute('role', 'img');
  canvas.setAttribute('aria-label', t('compare.pane_label', { pane: pane.pane, label }));
  // The live description in words (describe.js): the scene's paragraph and this pane's.
  canvas.setAttribute('aria-describedby', `compare-description-scene compare-description-${pane.pane}`);
  const picker = el('select', { title: t('compare.pane_planner_title') });
  picker.setAttribute('aria-label', t('compare.pane_planner_label', { pane: pane.pane }));
  picker.append(el('option', { value: 'scene', textContent: t('compare.scene_planners'), selected: pane.planner === 'scene' }));
  for (const p of app.planners) {
    picker.append(el('option', { value: p.name, textContent: tOr(`planner.${p.name}`, p.label), selected: pane.planner === p.name && !pane.per_group }));
  }
  if (pane.per_group) picker.append(el('option', { value: '', textContent: t('compare.per_group'), selected: true, disabled: true }));
  picker.addEventListener('change', () => app.change((sim) => sim.set_pane_planner(index, picker.value)));
  const remove = el('button', { type: 'button', className: 'small ghost', textContent: '✕', title: t('compare.remove_pane'), disabled: count <= 1 });
  remove.addEventListener('click', () => app.change((sim) => sim.remove_pane(index)));
  const head = el('div', { className: 'pane-head' },
    el('span', { className: 'pane-name', textContent: pane.pane }),
    picker,
    el('span', { className: 'pane-label', textContent: label, title: label }),
    remove);

  const details = el('details', {}, el('summary', { textContent: t('compare.parameters') }));
  if (pane.planner !== 'scene' && !pane.per_group) details.append(paramForm(app, index, pane));
  const specInput = el('input', { type: 'text', value: pane.spec, spellcheck: false,
    title: t('compare.spec_title') });
  specInput.setAttribute('aria-label', t('compare.spec_label', { pane: pane.pane }));
  specInput.addEventListener('change', () => {
    const all = JSON.parse(app.guard((sim) => sim.panes_json()).value ?? '[]').map((p) => p.spec);
    all[index] = specInput.value.trim();
    app.change((sim) => sim.set_spec(`1.${all.join('~')}`));
  });
  details.append(el('div', { className: 'spec-row' }, specInput));

  const node = el('article', { className: 'pane' }, head, canvas, details);
  node.style.setProperty('--pane-color', pane.color);
  node.dataset.pane = pane.pane;
  return { node, canvas };
}

/**
 * Builds the pane elements now and again whenever the panes change; returns a function giving
 * the current canvases (in pane order). Keeps the canvas size in step with the layout.
 */
export function buildPanes(app) {
  const area = document.getElementById('panes');
  let canvases = [];
  const build = () => {
    const result = app.guard((sim) => JSON.parse(sim.panes_json()));
    if (!result.ok) return;
    const panes = result.value;
    area.replaceChildren();
    canvases = [];
    panes.forEach((pane, i) => {
      const { node, canvas } = paneElement(app, i, pane, panes.length);
      area.append(node);
      canvases.push(canvas);
    });
    area.classList.toggle('single', panes.length === 1);
    app.dirty = true;
  };
  app.addEventListener('panes', build);
  onLanguageChange(build);
  build();
  const fit = () => {
    const { width, height } = measurePane();
    if (width !== app.sim.width() || height !== app.sim.height()) {
      app.guard((sim) => sim.resize(width, height));
      app.dirty = true;
    }
  };
  new ResizeObserver(fit).observe(area);
  fit();
  return () => canvases;
}
