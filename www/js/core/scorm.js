// The activity in an LMS: reports to the SCORM 1.2 runtime the LMS provides (the `API` object
// of a parent or opener frame), for a page opened from a SCORM package (`&scorm=1` in its
// fragment, set by the package's launch page; src/package/scorm.rs). Outside an LMS no runtime
// is found and the page works as it always does.
//
// What it sets, through LMSSetValue and LMSCommit:
// - on opening: LMSInitialize; `cmi.core.lesson_status` "incomplete" when the LMS says "not
//   attempted" (a later visit keeps what an earlier one reached); the prediction saved in
//   `cmi.suspend_data` is given back to the card, so a reopened activity shows it;
// - when the prediction is locked in: `cmi.suspend_data` = `{"answer": <choice index>}`;
// - when the check is decided: `cmi.core.lesson_status` (passed / failed) and
//   `cmi.core.score.raw` of 0–100 (`score.min` 0, `score.max` 100), graded by the core's rule
//   (`scorm_grade`: the check, and the prediction when it has an expected answer);
// - when the page goes: `cmi.core.exit` "suspend" (so the LMS resumes with the suspend data),
//   LMSCommit and LMSFinish, once.
//
// This module only finds the runtime and carries values between it and the card; the score is
// the core's.

import { loadWasm } from './boot.js';

/** How many frames up the chain the runtime is looked for (SCORM 1.2's discovery uses 7). */
export const MAX_FRAME_LEVELS = 7;

/** `win`'s chain of parents up to the top, at most MAX_FRAME_LEVELS above it, searched for `API`. */
function apiInChain(win) {
  let w = win;
  for (let level = 0; w && level <= MAX_FRAME_LEVELS; level += 1) {
    try {
      if (w.API && typeof w.API.LMSInitialize === 'function') return w.API;
    } catch {
      // A frame of another origin: its properties cannot be read; its parent still can be.
    }
    if (w.parent === w) break;
    w = w.parent;
  }
  return null;
}

/** The LMS's SCORM 1.2 runtime: `window.API` in this frame, a parent, or the opener's chain. */
export function findScormApi(win = window) {
  const found = apiInChain(win);
  if (found) return found;
  try {
    return win.opener ? apiInChain(win.opener) : null;
  } catch {
    return null;
  }
}

/** SCORM 1.2 answers "true" / "false" as strings (some runtimes as booleans). */
const succeeded = (value) => value === true || value === 'true';

/** The saved answer in `text` (the suspend data), or null. */
export function savedAnswer(text) {
  if (typeof text !== 'string' || text === '') return null;
  try {
    const answer = JSON.parse(text)?.answer;
    return Number.isInteger(answer) ? answer : null;
  } catch {
    return null;
  }
}

/**
 * Connects an activity card (core/activity-card.js) to the LMS's runtime `api` (found when not
 * given). Resolves to `{ api, finish() }`, or null when there is no runtime or it refuses to
 * start (the page then works as without an LMS).
 */
export async function connectScorm(card, { api = findScormApi() } = {}) {
  if (!api || !card) return null;
  if (!succeeded(api.LMSInitialize(''))) return null;
  const { module } = await loadWasm();
  const set = (element, value) => api.LMSSetValue(element, String(value));

  const status = api.LMSGetValue('cmi.core.lesson_status');
  if (status === '' || status === 'not attempted') set('cmi.core.lesson_status', 'incomplete');
  const answer = savedAnswer(api.LMSGetValue('cmi.suspend_data'));
  if (answer !== null) card.restoreAnswer(answer);
  api.LMSCommit('');

  card.element.addEventListener('fp-answer', (event) => {
    set('cmi.suspend_data', JSON.stringify({ answer: event.detail.answer }));
    api.LMSCommit('');
  });

  card.element.addEventListener('fp-decided', (event) => {
    const activity = card.activity();
    if (!activity) return;
    const { report, answer: chosen } = event.detail;
    let grade;
    try {
      grade = JSON.parse(module.scorm_grade(JSON.stringify(activity), report.status, chosen ?? undefined));
    } catch {
      return;
    }
    set('cmi.core.lesson_status', grade.lesson_status);
    if (grade.score_raw !== null && grade.score_raw !== undefined) {
      set('cmi.core.score.min', 0);
      set('cmi.core.score.max', 100);
      set('cmi.core.score.raw', grade.score_raw);
    }
    api.LMSCommit('');
  });

  let finished = false;
  const finish = () => {
    if (finished) return;
    finished = true;
    set('cmi.core.exit', 'suspend');
    api.LMSCommit('');
    api.LMSFinish('');
  };
  addEventListener('pagehide', finish);
  addEventListener('beforeunload', finish);
  return { api, finish };
}
