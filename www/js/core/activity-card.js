// The activity card a scene may carry (model/activity.rs): its prompt, the prediction asked
// before the first Play, and the goal's check with the measured values once the run ends. Used by
// the playground (play/activity.js), the compare page (compare/activity.js) and every
// <flock-path> element (so embed.html and course notes show it too).
//
// Every text of the activity is the author's, from a link anyone can write: it is only ever set
// with textContent (never innerHTML), so markup in it shows as the characters it is. The check is
// computed in Rust after every step (sim/activity_check.rs); this module only reads its report,
// pauses the run when the check is decided, and formats the values.

import { t } from './i18n.js';

const STYLE = `
.fp-activity { border: 1px solid #c9d6ea; border-left: 5px solid #2f6fdf; border-radius: 8px; background: #f5f8fe;
  padding: 0.55rem 0.75rem; color: #17202c; font: 14px/1.4 system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; }
.fp-activity[hidden] { display: none; }
.activity > .fp-activity { max-height: 55%; max-height: 45vh; overflow: auto; border-radius: 0; border-width: 1px 0 0 5px; }
.fp-activity h3 { margin: 0 0 0.3rem; font-size: 0.8rem; text-transform: uppercase; letter-spacing: 0.06em; color: #3a4a60; }
.fp-activity .fp-prompt { margin: 0 0 0.4rem; white-space: pre-line; overflow-wrap: anywhere; }
.fp-activity fieldset { border: 0; margin: 0.3rem 0; padding: 0; min-width: 0; }
.fp-activity legend { font-weight: 600; padding: 0; margin-bottom: 0.2rem; overflow-wrap: anywhere; }
.fp-activity label.fp-choice { display: flex; gap: 0.4rem; align-items: baseline; padding: 0.1rem 0; overflow-wrap: anywhere; }
.fp-activity .fp-ask { outline: 3px solid #f0b000; outline-offset: 2px; border-radius: 4px; }
.fp-activity .fp-row { display: flex; gap: 0.4rem; flex-wrap: wrap; align-items: center; margin-top: 0.3rem; }
.fp-activity button { font: inherit; padding: 3px 10px; border: 1px solid #c5cdd8; border-radius: 6px; background: #fff; cursor: pointer; min-height: 28px; color: #17202c; }
.fp-activity button.fp-primary { background: #2f6fdf; border-color: #2f6fdf; color: #fff; font-weight: 600; }
.fp-activity button:focus-visible { outline: 3px solid #8db6ff; outline-offset: 1px; }
.fp-activity .fp-note { color: #5a3d00; margin: 0.2rem 0 0; }
.fp-activity .fp-muted { color: #4a5668; margin: 0.2rem 0 0; overflow-wrap: anywhere; }
.fp-activity .fp-status { font-weight: 600; margin: 0.3rem 0 0.1rem; }
.fp-activity .fp-status.fp-met { color: #0b6b2f; }
.fp-activity .fp-status.fp-missed { color: #a0261b; }
.fp-activity ul { margin: 0.1rem 0 0.2rem; padding-left: 1.1rem; }
.fp-activity li.fp-pass::marker { content: "✓ "; color: #0b6b2f; }
.fp-activity li.fp-fail::marker { content: "✗ "; color: #a0261b; }
`;

let sheet = null;

/** Styles `root` (a document or a shadow root) with the card's sheet, once. */
function adoptStyle(root) {
  if ('adoptedStyleSheets' in root && typeof CSSStyleSheet.prototype.replaceSync === 'function') {
    if (!sheet) {
      sheet = new CSSStyleSheet();
      sheet.replaceSync(STYLE);
    }
    if (!root.adoptedStyleSheets.includes(sheet)) root.adoptedStyleSheets = [...root.adoptedStyleSheets, sheet];
    return;
  }
  const host = root.head ?? root;
  if (host.querySelector?.('style[data-fp-activity]')) return;
  const style = document.createElement('style');
  style.dataset.fpActivity = '';
  style.textContent = STYLE;
  host.append(style);
}

/** Metrics keys whose values are shares (shown in %). */
const SHARES = new Set(['arrived_share', 'queue_order']);
/** Metrics keys that count (shown as whole numbers). */
const COUNTS = new Set(['collisions_agent_agent', 'collisions_moving', 'penetrations_agent_obstacle', 'stuck_agents']);
/** Each comparison as the card writes it (also the Activities page's teacher guide). */
export const OPS = { '>=': '≥', '<=': '≤', '>': '>', '<': '<', '=': '=' };

/** A metric's value in the card's words. */
export function formatValue(metric, value) {
  if (value === null || value === undefined || !Number.isFinite(value)) return t('activity.no_value');
  if (SHARES.has(metric)) return `${Number((100 * value).toFixed(1))} %`;
  if (COUNTS.has(metric)) return Math.round(value).toLocaleString('en-US');
  return String(Number(value.toFixed(2)));
}

const el = (tag, props = {}, ...children) => {
  const node = Object.assign(document.createElement(tag), props);
  node.append(...children);
  return node;
};

/**
 * The card on `host` (a SimHost), inside `container`. Options:
 * - `readActivity()`: the scene's activity (null when absent), read after a new scene;
 * - `readReport()`: the check's report (null without a check), read when the step changes;
 * - `groupName(i)`: a group's name (the scene's);
 * - `paneName(i)`: a pane's label (compare page);
 * - `styleRoot`: where the card's style goes (the document, or a shadow root).
 * Returns `{ refresh(), stop(), element, answer(), activity(), restoreAnswer(i) }`: `refresh()`
 * after a new scene. The card element fires `fp-answer` (detail `{answer}`) when a prediction is
 * locked in and `fp-decided` (detail `{report, answer}`) when the check is decided.
 */
export function mountActivityCard(host, container, { readActivity, readReport, groupName = () => '', paneName = (i) => 'ABCD'[i] ?? String(i + 1), styleRoot = document } = {}) {
  adoptStyle(styleRoot);
  const card = el('section', { className: 'fp-activity', hidden: true });
  card.setAttribute('aria-label', t('activity.title'));
  container.append(card);

  /** Answers by activity (its JSON text): a reset or reloading the same activity keeps them. */
  const answers = new Map();
  let activity = null;
  let key = '';
  let shownReport = '';
  let lastSteps = -1;
  let playAfterAnswer = false;
  let stopped = false;
  let asked = false;
  /** Whether the check was still open at the last look: the run stops when it is decided. */
  let wasRunning = true;

  const title = el('h3', { textContent: t('activity.title') });
  const prompt = el('p', { className: 'fp-prompt' });
  const predictionBox = el('div', { className: 'fp-prediction' });
  const predictedLine = el('p', { className: 'fp-muted fp-predicted' });
  // The goal while the run goes (not announced: its step count changes every frame), then the
  // result in a live region (announced once, when the check is decided).
  const goalBox = el('div', { className: 'fp-goal' });
  const resultBox = el('div', { className: 'fp-result', role: 'status' });
  card.append(title, prompt, predictionBox, predictedLine, goalBox, resultBox);

  const prediction = () => activity?.prediction ?? null;
  const answered = () => answers.has(key);
  const needsPrediction = () => prediction() !== null && !answered();

  const subject = (m) => {
    if (m.pane !== undefined && m.group !== undefined) return t('activity.pane_group', { pane: paneName(m.pane), group: groupLabel(m.group) });
    if (m.pane !== undefined) return t('activity.pane', { name: paneName(m.pane) });
    if (m.group !== undefined) return groupLabel(m.group);
    return t('activity.whole_run');
  };
  const groupLabel = (g) => {
    const name = groupName(g);
    return name ? t('activity.group_named', { n: g + 1, name }) : t('activity.group', { n: g + 1 });
  };
  const who = (s) => (s.pane !== undefined ? t('activity.pane', { name: paneName(s.pane) }) : groupLabel(s.group));

  /** A condition in words ("Arrived ≥ 90 %"). */
  const describe = (c) => {
    if (c.before) {
      return t('activity.before', { first: who(c.before[0]), second: who(c.before[1]), share: formatValue('arrived_share', c.share ?? 0.9) });
    }
    const target = c.pane !== undefined || c.group !== undefined ? ` (${subject(c)})` : '';
    return `${t(`activity.metric.${c.metric}`)} ${OPS[c.op] ?? c.op} ${formatValue(c.metric, c.value)}${target}`;
  };

  const renderPrediction = () => {
    predictionBox.replaceChildren();
    predictedLine.textContent = '';
    const p = prediction();
    if (!p) return;
    if (answered()) {
      predictedLine.textContent = t('activity.your_prediction', { answer: p.choices[answers.get(key)] ?? '' });
      return;
    }
    const fieldset = el('fieldset');
    if (asked) fieldset.classList.add('fp-ask');
    const name = `fp-prediction-${Math.random().toString(36).slice(2)}`;
    fieldset.append(el('legend', { textContent: p.question }));
    p.choices.forEach((choice, i) => {
      const input = el('input', { type: 'radio', name, value: String(i) });
      fieldset.append(el('label', { className: 'fp-choice' }, input, el('span', { textContent: choice })));
    });
    const lock = el('button', { type: 'button', className: 'fp-primary fp-lock', textContent: t('activity.lock_in') });
    const note = el('p', { className: 'fp-note', hidden: !asked, textContent: t('activity.predict_first') });
    lock.addEventListener('click', () => {
      const chosen = fieldset.querySelector('input:checked');
      if (!chosen) {
        note.hidden = false;
        note.textContent = t('activity.choose_one');
        return;
      }
      answers.set(key, Number(chosen.value));
      asked = false;
      renderPrediction();
      renderReport(true);
      // For whoever keeps the answer (core/scorm.js: the LMS's suspend data).
      card.dispatchEvent(new CustomEvent('fp-answer', { detail: { answer: Number(chosen.value) } }));
      if (playAfterAnswer) {
        playAfterAnswer = false;
        host.setPlaying(true);
      }
    });
    predictionBox.append(fieldset, el('div', { className: 'fp-row' }, lock), note);
  };

  /** The check's state: a line while running, the measured values once decided. */
  const renderReport = (force = false) => {
    const report = activity?.check ? readReport() : null;
    const text = JSON.stringify(report);
    if (!force && text === shownReport) return report;
    shownReport = text;
    resultBox.replaceChildren();
    goalBox.replaceChildren();
    if (!report) return report;
    const status = report.status;
    const box = status === 'met' || status === 'missed' ? resultBox : goalBox;
    const line = el('p', { className: `fp-status fp-${status}` });
    const limit = report.limit.toLocaleString('en-US');
    const step = report.step.toLocaleString('en-US');
    line.textContent = t(`activity.status.${status}`, { step, limit });
    box.append(line);
    const list = el('ul');
    for (const c of report.conditions) {
      const item = el('li');
      const measured = c.measured
        .map((m) => {
          if (c.condition.before) {
            const reached = m.reached_step === undefined ? t('activity.not_reached') : t('activity.reached_at', { step: m.reached_step.toLocaleString('en-US') });
            return `${subject(m)}: ${reached}`;
          }
          const whose = c.measured.length > 1 || m.pane !== undefined ? `${subject(m)}: ` : '';
          return `${whose}${formatValue(c.condition.metric, m.value)}`;
        })
        .join('; ');
      let words = describe(c.condition);
      if (!c.applies) words += ` — ${t('activity.not_here')}`;
      else if (status !== 'running' && measured) words += ` — ${t('activity.measured', { values: measured })}`;
      item.textContent = words;
      if (status === 'met' || status === 'missed') item.className = c.holds ? 'fp-pass' : 'fp-fail';
      list.append(item);
    }
    box.append(list);
    if (report.from_step > 1 && status !== 'unavailable') {
      box.append(el('p', { className: 'fp-muted', textContent: t('activity.partial', { step: report.from_step.toLocaleString('en-US') }) }));
    }
    const p = prediction();
    predictedLine.hidden = Boolean(p && (status === 'met' || status === 'missed'));
    if (p && (status === 'met' || status === 'missed')) {
      const mine = answers.get(key);
      box.append(
        el('p', { className: 'fp-muted fp-compare-prediction', textContent: mine === undefined ? t('activity.no_prediction') : t('activity.you_predicted', { answer: p.choices[mine] ?? '' }) }),
      );
      if (p.expected !== undefined && p.expected !== null) {
        box.append(el('p', { className: 'fp-muted', textContent: t('activity.expected', { answer: p.choices[p.expected] ?? '' }) }));
      }
    }
    return report;
  };

  /** Reads the scene's activity again (after a load, an edit, a reset). */
  const refresh = () => {
    if (stopped || host.crashed) return;
    const next = readActivity() ?? null;
    const nextKey = next ? JSON.stringify(next) : '';
    if (nextKey !== key) {
      key = nextKey;
      activity = next;
      asked = false;
      playAfterAnswer = false;
      card.hidden = !activity;
      prompt.textContent = activity?.prompt ?? '';
      renderPrediction();
      // A scene with a question starts paused: the student answers before the run starts, and
      // a run that was meant to play (autoplay, the playground's start) plays once answered.
      if (needsPrediction() && host.playing) {
        host.setPlaying(false);
        playAfterAnswer = true;
      }
    }
    lastSteps = -1;
    wasRunning = true;
    renderReport(true);
  };

  // The first Play asks for the prediction instead of playing.
  host.addEventListener('playing', () => {
    if (stopped || !host.playing || !needsPrediction()) return;
    host.setPlaying(false);
    asked = true;
    playAfterAnswer = true;
    renderPrediction();
    card.querySelector('.fp-prediction input')?.focus({ preventScroll: true });
    card.scrollIntoView?.({ block: 'nearest' });
  });

  // Follows the check while the run goes: when it is decided the run stops there.
  const poll = () => {
    if (stopped) return;
    if (activity?.check && !host.crashed && card.isConnected) {
      const steps = host.guard((sim) => sim.steps()).value;
      if (steps !== lastSteps) {
        lastSteps = steps;
        const report = renderReport();
        const decided = report && (report.status === 'met' || report.status === 'missed');
        if (decided && wasRunning) {
          if (host.playing) host.setPlaying(false);
          // For whoever reports the result (core/scorm.js: the LMS's score and status).
          card.dispatchEvent(new CustomEvent('fp-decided', { detail: { report, answer: answers.has(key) ? answers.get(key) : null } }));
          // Pages that refresh their tables on steps (the compare page) show the final values.
          host.dispatchEvent(new Event('stepped'));
        }
        wasRunning = report?.status === 'running';
      }
    }
    requestAnimationFrame(poll);
  };
  requestAnimationFrame(poll);
  refresh();

  return {
    element: card,
    refresh,
    stop() {
      stopped = true;
      card.parentElement?.remove();
    },
    /** The chosen answer's index, or null. */
    answer: () => (answers.has(key) ? answers.get(key) : null),
    /** The scene's activity as the card shows it (null without one). */
    activity: () => activity,
    /**
     * Takes `index` as the student's answer, as if locked in (a saved answer restored: the LMS's
     * suspend data). Ignored when there is no question, it is answered, or `index` is no choice.
     * A run that waited for the answer plays.
     */
    restoreAnswer(index) {
      const p = prediction();
      if (!p || answered() || !Number.isInteger(index) || index < 0 || index >= p.choices.length) return false;
      answers.set(key, index);
      asked = false;
      renderPrediction();
      renderReport(true);
      if (playAfterAnswer) {
        playAfterAnswer = false;
        host.setPlaying(true);
      }
      return true;
    },
  };
}
