// The Activities page: the activity library (./library.js) listed by topic, easiest first, each
// with its level, the time it takes and a link that opens the playground with its scene (the
// link of the page's language, from ./measured.js); and the teacher guide, one printed page per
// activity: the question, the choices with the expected one, the goal in words, what to expect,
// why, what the check measured on the scene and on the "try next" variant, and what to ask next.
// The page prints the guide (activities.css); "Print teacher guide" only calls print().

import { language, onLanguageChange, setText, t, translatePage } from '../core/i18n.js';
import { OPS, formatValue } from '../core/activity-card.js';
import { ACTIVITIES, LEVELS, TOPICS } from './library.js';
import { MEASURED } from './measured.js';

const $ = (id) => document.getElementById(id);

const el = (tag, props = {}, ...children) => {
  const node = Object.assign(document.createElement(tag), props);
  node.append(...children);
  return node;
};
const text = (tag, key, vars, props = {}) => setText(el(tag, props), key, vars);

/** The playground link of `activity` in the page's language. */
export function activityHref(activity, lang = language()) {
  const links = MEASURED[activity.id]?.links ?? {};
  return `index.html#s=${links[lang] ?? links.en}`;
}

/** The words of `activity` in the page's language. */
const words = (activity) => activity[language()] ?? activity.en;

/** "Arrived ≥ 90 % and Collisions ≤ 1,000 by step 1,500" */
function goalText(activity) {
  const parts = activity.check.conditions.map((c) => {
    const who = c.group === undefined ? '' : ` (${t('activity.group', { n: c.group + 1 })})`;
    return `${t(`activity.metric.${c.metric}`)}${who} ${OPS[c.op]} ${formatValue(c.metric, c.value)}`;
  });
  return t('activities.goal_by', { conditions: parts.join(t('activities.and')), steps: activity.check.steps.toLocaleString('en-US') });
}

/** "Missed at step 1,500: Arrived 100 %, Collisions 66,554" from a measured report. */
function measuredText(activity, report) {
  const values = activity.check.conditions
    .map((c, i) => `${t(`activity.metric.${c.metric}`)} ${formatValue(c.metric, report.values[i])}`)
    .join(', ');
  return t(`activities.measured_${report.status}`, { step: report.step.toLocaleString('en-US'), values });
}

function listing() {
  const byLevel = (a, b) => LEVELS.indexOf(a.level) - LEVELS.indexOf(b.level) || a.minutes - b.minutes;
  return TOPICS.flatMap((topic) => {
    const rows = ACTIVITIES.filter((a) => a.topic === topic).sort(byLevel);
    if (rows.length === 0) return [];
    const id = `topic-${topic}`;
    const head = el('tr', {}, ...['activities.col_activity', 'activities.col_level', 'activities.col_time', 'activities.col_open'].map((k) => text('th', k, undefined, { scope: 'col' })));
    const body = rows.map((a) => {
      const w = words(a);
      const open = el('a', { className: 'button activity-open', href: activityHref(a) }, t('activities.open'));
      open.dataset.activity = a.id;
      open.setAttribute('aria-label', t('activities.open_named', { title: w.title }));
      return el(
        'tr',
        { id: `activity-${a.id}` },
        el('td', {}, el('span', { className: 'activity-title' }, w.title), el('span', { className: 'activity-question' }, w.question)),
        el('td', {}, text('span', `activities.level.${a.level}`, undefined, { className: `level-badge ${a.level}` })),
        text('td', 'activities.minutes', { n: a.minutes }, { className: 'minutes' }),
        el('td', {}, open),
      );
    });
    const table = el('table', { className: 'activity-table' }, el('thead', {}, head), el('tbody', {}, ...body));
    table.setAttribute('aria-labelledby', id);
    return [text('h2', `activities.topic.${topic}`, undefined, { id }), table];
  });
}

function guidePage(activity) {
  const w = words(activity);
  const measured = MEASURED[activity.id];
  const section = (key, ...content) => [text('h4', key), ...content];
  const choices = el('ol', {}, ...w.choices.map((c, i) => {
    const li = el('li', {}, c);
    if (i === activity.expected) {
      li.className = 'expected-choice';
      li.append(' ', t('activities.expected_mark'));
    }
    return li;
  }));
  const page = el(
    'article',
    { className: 'guide-page', id: `guide-${activity.id}` },
    el('h3', {}, w.title),
    el('p', { className: 'guide-meta' }, [t(`activities.topic.${activity.topic}`), t(`activities.level.${activity.level}`), t('activities.minutes', { n: activity.minutes })].join(' · ')),
    ...section('activities.guide.prompt', el('p', {}, w.prompt)),
    ...section('activities.guide.question', el('p', {}, w.question), choices),
    ...section('activities.guide.goal', el('p', {}, goalText(activity))),
    ...section('activities.guide.expect', el('p', {}, w.expect)),
    ...section('activities.guide.why', el('p', {}, w.why)),
  );
  if (measured) {
    const lines = [el('p', { className: 'guide-measured-check' }, measuredText(activity, measured.check))];
    if (measured.variant && w.variant) lines.push(el('p', { className: 'guide-measured-variant' }, t('activities.variant_measured', { change: w.variant, result: measuredText(activity, measured.variant) })));
    page.append(...section('activities.guide.measured', el('div', { className: 'guide-measured' }, ...lines)));
  }
  page.append(...section('activities.guide.next', el('p', {}, w.next)));
  const href = new URL(activityHref(activity), location.href).href;
  page.append(...section('activities.guide.link', el('p', { className: 'guide-link' }, href)));
  return page;
}

function render() {
  $('activity-list').replaceChildren(...listing());
  $('guide-pages').replaceChildren(...ACTIVITIES.map(guidePage));
}

translatePage(document);
render();
onLanguageChange(render);
$('print-guide').addEventListener('click', () => window.print());
/** For tests and scripts: the library as this page lists it. */
window.flockpathActivities = { ids: ACTIVITIES.map((a) => a.id), href: (id) => activityHref(ACTIVITIES.find((a) => a.id === id)) };
