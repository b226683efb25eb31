// What each number on the pages means: a hover on every metric's name (its `title`, and its
// accessible description pointing at the card's entry, reachable with Tab) and the "What do these
// numbers mean?" card that lists the shown metrics with their definitions and units. The words
// live in the string tables (`metric.name.*`, `metric.def.*`, `metric.unit.*`); the README's
// "Metrics keys" list holds the same English words (tests/e2e/metric-words.test.mjs).

import { onLanguageChange, setText, t } from './i18n.js';

/** Every metrics key the pages explain, in the card's order. */
export const METRIC_KEYS = Object.freeze([
  'steps',
  'agents',
  'arrived_share',
  'waiting_agents',
  'waiting_share',
  'mean_time_to_goal_s',
  'collisions_agent_agent',
  'penetrations_agent_obstacle',
  'mean_speed',
  'mean_path_length',
  'mean_turn_deg',
  'max_turn_deg',
  'stuck_agents',
  'queue_order',
  'fitness',
]);

/** The id of `key`'s entry in the card: the target of the names' `aria-describedby`. */
const entryId = (key) => `metric-def-${key}`;

/** The hover text of `key`: its definition and unit in the page's language. */
export function metricHover(key) {
  return t('metrics.hover', { definition: t(`metric.def.${key}`), unit: t(`metric.unit.${key}`) });
}

/**
 * Makes `el` (a metric's name: a `dt`, a column heading, a row heading) explain `key`: the
 * definition and unit as its `title` for the mouse, focusable with Tab, and described by the
 * card's entry for screen readers. Returns `el`.
 */
export function describeMetric(el, key) {
  el.dataset.metric = key;
  el.classList.add('metric-term');
  el.tabIndex = 0;
  el.title = metricHover(key);
  el.setAttribute('aria-describedby', entryId(key));
  return el;
}

/**
 * The "What do these numbers mean?" card for `keys` (a closed disclosure): a name, definition and
 * unit per metric, and a Close button; Escape closes it too and returns focus to its summary.
 */
export function metricsGlossary(keys) {
  const details = document.createElement('details');
  details.className = 'metrics-glossary';
  const summary = setText(document.createElement('summary'), 'metrics.glossary');
  const intro = setText(document.createElement('p'), 'metrics.glossary_intro');
  intro.className = 'small-print';
  const list = document.createElement('dl');
  for (const key of keys) {
    const dt = setText(document.createElement('dt'), `metric.name.${key}`);
    const dd = document.createElement('dd');
    dd.id = entryId(key);
    dd.dataset.metric = key;
    const definition = setText(document.createElement('span'), `metric.def.${key}`);
    definition.className = 'metric-definition';
    const unit = setText(document.createElement('span'), 'metrics.glossary_unit', { unit: t(`metric.unit.${key}`) });
    unit.className = 'metric-unit';
    dd.append(definition, ' ', unit);
    list.append(dt, dd);
  }
  const close = setText(document.createElement('button'), 'common.close');
  close.type = 'button';
  close.className = 'ghost small';
  close.setAttribute('data-i18n-aria-label', 'metrics.glossary_close');
  close.setAttribute('aria-label', t('metrics.glossary_close'));
  const shut = () => {
    details.open = false;
    summary.focus();
  };
  close.addEventListener('click', shut);
  details.addEventListener('keydown', (event) => {
    if (event.key === 'Escape' && details.open) {
      event.preventDefault();
      event.stopPropagation();
      shut();
    }
  });
  details.append(summary, intro, list, close);
  return details;
}

// A language switch: the units inside the card's "Unit: …" lines and the names' hovers are
// composed from two keys, so word them again here.
onLanguageChange(() => {
  for (const el of document.querySelectorAll('.metric-term[data-metric]')) el.title = metricHover(el.dataset.metric);
  for (const el of document.querySelectorAll('.metrics-glossary dd[data-metric] .metric-unit')) {
    const key = el.parentElement.dataset.metric;
    setText(el, 'metrics.glossary_unit', { unit: t(`metric.unit.${key}`) });
  }
});

/**
 * The hover for keyboard users: a `title` shows only under the mouse, so a metric's name focused
 * with Tab shows the same words in a box under it (fixed to the viewport, so a scrolling table
 * does not clip it); it goes with the focus, or with Escape.
 */
function setupFocusTip() {
  if (typeof document === 'undefined') return;
  let tip = null;
  let shownFor = null;
  const hide = () => {
    if (tip) tip.hidden = true;
    shownFor = null;
  };
  /** Puts the tip under `term` (above it when there is no room below), inside the viewport. */
  const place = (term) => {
    const box = term.getBoundingClientRect();
    const width = Math.min(320, window.innerWidth - 16);
    tip.style.width = `${width}px`;
    tip.style.left = `${Math.max(8, Math.min(box.left, window.innerWidth - width - 8))}px`;
    const below = box.bottom + 6;
    tip.style.top = `${below}px`;
    const height = tip.offsetHeight;
    if (below + height > window.innerHeight - 8) tip.style.top = `${Math.max(8, box.top - height - 6)}px`;
  };
  document.addEventListener('focusin', (event) => {
    const term = event.target instanceof Element ? event.target.closest('.metric-term[data-metric]') : null;
    if (!term || !term.matches(':focus-visible')) {
      hide();
      return;
    }
    if (!tip) {
      tip = document.createElement('div');
      tip.className = 'metric-tip';
      tip.setAttribute('role', 'tooltip');
      tip.id = 'metric-tip';
      document.body.append(tip);
    }
    tip.textContent = metricHover(term.dataset.metric);
    tip.hidden = false;
    shownFor = term;
    place(term);
  });
  document.addEventListener('focusout', hide);
  document.addEventListener('keydown', (event) => {
    if (event.key === 'Escape' && tip && !tip.hidden) hide();
  });
  // Focusing a name scrolls it into view: the tip follows its name.
  window.addEventListener(
    'scroll',
    () => {
      if (shownFor && document.activeElement === shownFor) place(shownFor);
      else hide();
    },
    { passive: true, capture: true },
  );
}

setupFocusTip();
