// The planner parameter form, built from the core's parameter table (`planners_json`): shared by
// the playground's panel and the compare page's panes. Imports nothing from page folders.
// Labels, help, choices and units are shown in the page's language (keys `param.<planner>.<key>`,
// `choice.<value>`, `unit.<unit>`), falling back to the core's English words.

import { tOr } from './i18n.js';

/** A parameter's label in the page's language. */
export function paramLabel(planner, spec) {
  return tOr(`param.${planner}.${spec.key}`, spec.label);
}

/** A parameter's one-line help in the page's language. */
export function paramHelp(planner, spec) {
  return tOr(`param.${planner}.${spec.key}.help`, spec.help);
}

/** A unit in the page's language (`px` → 像素). */
export function unitText(unit) {
  return unit ? tOr(`unit.${unit}`, unit) : '';
}

/** Shows a number the way its slider step suggests (0.05 → two decimals). */
export function formatValue(value, step) {
  if (typeof value !== 'number') return String(value);
  const decimals = step > 0 && step < 1 ? Math.min(4, Math.ceil(-Math.log10(step) - 1e-9)) : 0;
  return value.toFixed(decimals);
}

/** The readout beside a parameter's control: the value with its unit (none for a choice). */
export function paramReadout(spec, value) {
  return spec.choices?.length ? '' : `${formatValue(value, spec.step)} ${unitText(spec.unit)}`.trim();
}

/**
 * The control of one parameter of the table (`{ key, label, help, min, max, step, unit, choices }`):
 * a select for a choice, else a range slider; `id`, `name` and the current `value` as given.
 * `onInput(value)` runs while a slider moves, `onChange(value)` when a gesture or choice ends.
 */
export function paramControl(spec, { id, value, planner = '', onInput = () => {}, onChange = () => {} }) {
  let input;
  if (spec.choices?.length) {
    input = document.createElement('select');
    for (const c of spec.choices) input.append(Object.assign(document.createElement('option'), { value: c, textContent: tOr(`choice.${c}`, c) }));
  } else {
    input = Object.assign(document.createElement('input'), { type: 'range', min: String(spec.min), max: String(spec.max), step: String(spec.step) });
  }
  Object.assign(input, { id, name: spec.key, title: paramHelp(planner, spec) });
  if (value !== undefined) input.value = String(value);
  const read = () => (input.tagName === 'SELECT' ? input.value : Number(input.value));
  if (input.tagName !== 'SELECT') input.addEventListener('input', () => onInput(read()));
  input.addEventListener('change', () => onChange(read()));
  return input;
}
