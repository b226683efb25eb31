// The page explains itself: a Help dialog (what flockpath is, three things to try, each planner in
// a paragraph with its paper, what each number means, the keys, sharing and embedding) from the
// header menu, and on a first visit a welcome card at the top of the side panel with the same
// start, dismissed once for this browser. Words come from the string tables (both languages);
// the metric words are the metrics card's own strings.

import { onLanguageChange, setText, t, tOr } from '../core/i18n.js';
import { METRIC_KEYS } from '../core/metric-words.js';

const $ = (id) => document.getElementById(id);
/** Where a browser remembers that the welcome was dismissed. */
const WELCOMED = 'flockpath.welcomed';
const TRIES = ['help.try1', 'help.try2', 'help.try3'];

const el = (tag, props = {}, children = []) => {
  const node = Object.assign(document.createElement(tag), props);
  node.append(...children);
  return node;
};
const text = (tag, key, props = {}) => setText(el(tag, props), key);

/** The three things to try, as a list. */
function tries() {
  return el('ol', { className: 'help-tries' }, TRIES.map((key) => text('li', key)));
}

/** Where the ready activities and the teacher guide are: a line with a link to the Activities page. */
function activitiesLine(id) {
  // Bound to their keys (setText), so a language switch rewords the open card too.
  return el('p', { className: 'help-activities' }, [text('span', 'help.activities'), ' ', text('a', 'help.activities_link', { href: 'activities.html', id })]);
}

/** The Help dialog's contents for `planners` (name, label). */
function helpBody(planners) {
  const keys = [
    ['Space', 'help.key.play'], ['S', 'help.key.step'], ['R', 'help.key.reset'], ['1–7', 'help.key.tools'],
    ['Delete', 'help.key.delete'], ['Esc', 'help.key.cancel'], ['Ctrl+Z / Ctrl+Y', 'help.key.undo'], ['Tab, ←↑→↓, Enter', 'help.key.canvas'],
    ['P', 'help.key.present'], ['+ / − / 0', 'help.key.zoom'], ['Space + drag', 'help.key.pan'],
  ];
  return [
    text('p', 'help.what'),
    text('h3', 'help.try_title'),
    tries(),
    text('h3', 'help.planners_title'),
    el('dl', { className: 'help-planners' }, planners.flatMap((p) => [
      el('dt', { textContent: tOr(`planner.${p.name}`, p.label) }),
      el('dd', { textContent: tOr(`help.planner.${p.name}`, '') }),
    ])),
    text('h3', 'help.metrics_title'),
    el('dl', { className: 'help-metrics' }, METRIC_KEYS.filter((key) => tOr(`metric.def.${key}`, '') !== '').flatMap((key) => [
      text('dt', `metric.name.${key}`),
      el('dd', {}, [text('span', `metric.def.${key}`), ' ', setText(el('span', { className: 'metric-unit' }), 'metrics.glossary_unit', { unit: t(`metric.unit.${key}`) })]),
    ])),
    text('h3', 'help.keys_title'),
    el('dl', { className: 'help-keys' }, keys.flatMap(([key, words]) => [el('dt', {}, [el('kbd', { textContent: key })]), text('dd', words)])),
    text('h3', 'help.activities_title'),
    activitiesLine('help-activities'),
    text('h3', 'help.share_title'),
    text('p', 'help.share'),
  ];
}

/** Wires the Help button and dialog and shows the welcome card on a first visit. */
export function setupHelp(app) {
  const button = $('help');
  const dialog = $('help-dialog');
  const body = $('help-body');
  if (!button || !dialog || !body) return;
  const fill = () => body.replaceChildren(...helpBody(app.planners ?? []));
  button.addEventListener('click', () => {
    fill();
    dialog.showModal();
  });
  onLanguageChange(() => {
    if (dialog.open) fill();
  });
  showWelcome(() => button.click());
}

/** The first-visit card: what this is, three things to try, Help for more; remembered once closed. */
function showWelcome(openHelp) {
  let store = null;
  try {
    store = window.localStorage;
  } catch {
    store = null;
  }
  if (store?.getItem(WELCOMED)) return;
  const panel = document.querySelector('.panel');
  if (!panel) return;
  const title = text('h2', 'help.welcome_title', { id: 'welcome-title' });
  const close = text('button', 'help.welcome_close', { type: 'button', className: 'primary', id: 'welcome-close' });
  const more = text('button', 'help.welcome_more', { type: 'button', id: 'welcome-help' });
  const card = el('section', { className: 'card welcome', id: 'welcome' }, [
    title,
    text('p', 'help.what'),
    tries(),
    activitiesLine('welcome-activities'),
    el('div', { className: 'row-buttons' }, [close, more]),
  ]);
  card.setAttribute('aria-labelledby', 'welcome-title');
  close.addEventListener('click', () => {
    store?.setItem(WELCOMED, '1');
    card.remove();
    $('help')?.focus();
  });
  more.addEventListener('click', openHelp);
  panel.prepend(card);
}
