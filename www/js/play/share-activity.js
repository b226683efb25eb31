// The Share dialog's activity form (issue #15 item 4): "Activity…" beside "Copy link" opens a
// dialog of its own (the Share dialog keeps its height on a phone) where a teacher writes a
// prompt, an optional prediction question with its choices, and an optional goal checked on the
// metrics; "Put the activity in the link" stores it in the scene (sim.set_activity: Rust
// validates, naming the field and its limit on a refusal), so the Share dialog's link, iframe and
// <flock-path> snippets carry it.

import { t } from '../core/i18n.js';
import { messageOf } from '../core/errors.js';

/** The metrics keys a condition may test (model/activity.rs METRIC_KEYS), in menu order. */
export const METRICS = [
  'arrived_share', 'penetrations_agent_obstacle', 'collisions_agent_agent', 'collisions_moving', 'stuck_agents',
  'mean_time_to_goal', 'mean_time_to_goal_s', 'mean_speed', 'mean_speed_m_s', 'mean_speed_near_obstacles',
  'mean_path_length', 'mean_path_length_m', 'mean_turn_deg', 'max_turn_deg', 'queue_order',
];
const OPS = [['>=', '≥'], ['<=', '≤'], ['>', '>'], ['<', '<'], ['=', '=']];
const PANES = ['A', 'B', 'C', 'D'];

const STYLE = `
.activity-conditions { display: flex; flex-direction: column; gap: 0.4rem; }
.activity-condition { display: flex; flex-wrap: wrap; gap: 0.35rem; align-items: center; padding: 0.4rem 0.5rem;
  border: 1px solid var(--line, #d5dbe3); border-radius: 6px; }
.activity-condition .activity-parts { display: contents; }
.activity-condition select { max-width: 100%; }
.activity-condition .activity-remove-condition { margin-left: auto; }
`;

/** The form's few rules, once (a constructed sheet: no inline <style> for a strict CSP). */
function adoptStyle() {
  const sheet = new CSSStyleSheet();
  sheet.replaceSync(STYLE);
  document.adoptedStyleSheets = [...document.adoptedStyleSheets, sheet];
}

const el = (tag, props = {}, ...children) => {
  const node = Object.assign(document.createElement(tag), props);
  node.append(...children);
  return node;
};
const option = (value, text) => el('option', { value, textContent: text });
const field = (label, control) => el('label', { className: 'field' }, el('span', { textContent: label }), control);

/** The subjects of a condition as `[value, label]`: the run, each group, each pane. */
function subjects(app, { run = true } = {}) {
  const list = run ? [['run', t('activity.whole_run')]] : [];
  (app.scene.groups ?? []).forEach((g, i) => {
    list.push([`group:${i}`, g.name ? t('activity.group_named', { n: i + 1, name: g.name }) : t('activity.group', { n: i + 1 })]);
  });
  PANES.forEach((name, i) => list.push([`pane:${i}`, t('activity.form.pane_compare', { name })]));
  return list;
}

/** `group:2` → `{ group: 2 }`; `run` → `{}`. */
function subjectOf(value) {
  const [kind, index] = value.split(':');
  return kind === 'run' ? {} : { [kind]: Number(index) };
}

const subjectValue = (s) => (s.pane !== undefined ? `pane:${s.pane}` : s.group !== undefined ? `group:${s.group}` : 'run');

/** One condition row: a metric compared with a number, or "arrives before". */
function conditionRow(app, condition = null) {
  const row = el('div', { className: 'activity-condition' });
  const kind = el('select', { className: 'activity-kind' }, option('metric', t('activity.form.kind_metric')), option('before', t('activity.form.kind_before')));
  kind.setAttribute('aria-label', t('activity.form.kind'));
  const parts = el('span', { className: 'activity-parts' });
  const remove = el('button', { type: 'button', className: 'ghost small activity-remove-condition', textContent: t('activity.form.remove_condition') });
  remove.addEventListener('click', () => row.remove());
  const select = (label, options, value) => {
    const s = el('select', {}, ...options.map(([v, text]) => option(v, text)));
    s.setAttribute('aria-label', label);
    if (value !== undefined) s.value = value;
    return s;
  };
  const number = (label, value, step = 'any') => {
    const input = el('input', { type: 'number', step, value: value ?? '' });
    input.setAttribute('aria-label', label);
    input.style.width = '6.5em';
    return input;
  };
  const show = () => {
    parts.replaceChildren();
    if (kind.value === 'before') {
      const [first, second] = condition?.before ?? [{ pane: 1 }, { pane: 0 }];
      const list = subjects(app, { run: false });
      parts.append(
        select(t('activity.form.first'), list, subjectValue(first)),
        el('span', { textContent: t('activity.form.before_word') }),
        select(t('activity.form.second'), list, subjectValue(second)),
        el('span', { textContent: t('activity.form.share_word') }),
        number(t('activity.form.share'), condition?.share ?? 0.9),
      );
      parts.children[0].className = 'activity-first';
      parts.children[2].className = 'activity-second';
      parts.children[4].className = 'activity-share';
    } else {
      const m = condition?.metric ? condition : { metric: 'arrived_share', op: '>=', value: 0.9 };
      const s = select(t('activity.form.subject'), subjects(app), subjectValue(m));
      s.className = 'activity-subject';
      const metric = select(t('activity.form.metric'), METRICS.map((k) => [k, t(`activity.metric.${k}`)]), m.metric);
      metric.className = 'activity-metric';
      const op = select(t('activity.form.op'), OPS, m.op);
      op.className = 'activity-op';
      const value = number(t('activity.form.value'), m.value);
      value.className = 'activity-value';
      parts.append(s, metric, op, value);
    }
  };
  kind.value = condition?.before ? 'before' : 'metric';
  kind.addEventListener('change', () => {
    condition = null;
    show();
  });
  show();
  row.append(kind, parts, remove);
  return row;
}

/** The condition a row describes. */
function readRow(row) {
  const q = (selector) => row.querySelector(selector);
  if (q('.activity-kind').value === 'before') {
    return {
      before: [subjectOf(q('.activity-first').value), subjectOf(q('.activity-second').value)],
      share: Number(q('.activity-share').value),
    };
  }
  return {
    metric: q('.activity-metric').value,
    op: q('.activity-op').value,
    value: Number(q('.activity-value').value),
    ...subjectOf(q('.activity-subject').value),
  };
}

export function setupShareActivity(app) {
  adoptStyle();
  const status = el('p', { id: 'activity-form-status', className: 'muted', role: 'status' });
  const promptInput = el('textarea', { id: 'activity-prompt', rows: 3 });
  const question = el('input', { id: 'activity-question', type: 'text' });
  const choices = el('textarea', { id: 'activity-choices', rows: 3 });
  const expected = el('select', { id: 'activity-expected' });
  const steps = el('input', { id: 'activity-steps', type: 'number', min: '1', max: '1000000', step: '1' });
  const conditions = el('div', { id: 'activity-conditions', className: 'activity-conditions' });
  const add = el('button', { type: 'button', id: 'activity-add-condition', className: 'small', textContent: t('activity.form.add_condition') });
  const apply = el('button', { type: 'button', id: 'activity-apply', className: 'primary', textContent: t('activity.form.apply') });
  const clear = el('button', { type: 'button', id: 'activity-clear', textContent: t('activity.form.clear') });
  const close = el('button', { value: 'close', className: 'ghost', textContent: t('activity.form.close') });
  const dialog = el(
    'dialog',
    { id: 'activity-dialog', className: 'dialog' },
    el(
      'form',
      { method: 'dialog', className: 'dialog-body' },
      el('h2', { id: 'activity-dialog-title', textContent: t('activity.form.title') }),
      el('p', { className: 'muted', textContent: t('activity.form.intro') }),
      field(t('activity.form.prompt'), promptInput),
      field(t('activity.form.question'), question),
      field(t('activity.form.choices'), choices),
      field(t('activity.form.expected'), expected),
      field(t('activity.form.steps'), steps),
      el('p', { className: 'small-print', textContent: t('activity.form.conditions') }),
      conditions,
      el('div', { className: 'row-buttons' }, add),
      el('div', { className: 'row-buttons' }, apply, clear),
      status,
      el('div', { className: 'row-buttons end' }, close),
    ),
  );
  dialog.setAttribute('aria-labelledby', 'activity-dialog-title');
  document.body.append(dialog);
  const open = el('button', { type: 'button', id: 'share-activity-open', textContent: t('activity.form.open') });
  open.title = t('activity.form.open_title');
  document.getElementById('copy-link').after(open);

  const choiceList = () => choices.value.split('\n').map((c) => c.trim()).filter((c) => c !== '');
  const showExpected = (keep = expected.value) => {
    expected.replaceChildren(option('', t('activity.form.expected_none')), ...choiceList().map((c, i) => option(String(i), c)));
    expected.value = [...expected.options].some((o) => o.value === keep) ? keep : '';
  };
  choices.addEventListener('input', () => showExpected());
  add.addEventListener('click', () => conditions.append(conditionRow(app)));

  /** Fills the form from the scene's activity (or empties it). */
  const fill = () => {
    const a = app.guard((sim) => JSON.parse(sim.activity_json())).value ?? null;
    promptInput.value = a?.prompt ?? '';
    question.value = a?.prediction?.question ?? '';
    choices.value = (a?.prediction?.choices ?? []).join('\n');
    showExpected(a?.prediction?.expected === undefined ? '' : String(a.prediction.expected));
    steps.value = a?.check ? String(a.check.steps) : '';
    conditions.replaceChildren(...(a?.check?.conditions ?? []).map((c) => conditionRow(app, c)));
    status.textContent = '';
  };

  /** The activity the form describes. */
  const read = () => {
    const activity = { prompt: promptInput.value };
    if (question.value.trim() !== '' || choiceList().length > 0) {
      activity.prediction = { question: question.value, choices: choiceList() };
      if (expected.value !== '') activity.prediction.expected = Number(expected.value);
    }
    const rows = [...conditions.querySelectorAll('.activity-condition')];
    if (steps.value.trim() !== '' || rows.length > 0) {
      activity.check = { steps: Number(steps.value), conditions: rows.map(readRow) };
    }
    return activity;
  };

  /** Resolves to whether the simulation worker took the activity. */
  const set = async (json, done) => {
    const result = await app.change((sim) => sim.set_activity(json), { clearSelection: false });
    status.textContent = result.ok ? done : t('activity.form.refused', { reason: messageOf(result.error) });
    return result.ok;
  };
  apply.addEventListener('click', () => set(JSON.stringify(read()), t('activity.form.applied')));
  clear.addEventListener('click', async () => {
    if (await set('', t('activity.form.cleared'))) fill();
  });
  open.addEventListener('click', () => {
    fill();
    dialog.showModal();
    promptInput.focus();
  });
  document.getElementById('share').addEventListener('click', fill);
  fill();
}
