// Messages for the user: a dismissable banner for refused input, a loud panel for a crash.

import { t } from './i18n.js';
import { errorText } from './messages.js';

const banner = () => document.getElementById('banner');

/**
 * The parser's own words behind the last error read with `messageOf` (a refused scene's `Error`
 * carries them as `details`): the next banner that quotes that error offers them behind "details",
 * whichever words the caller put around the message.
 */
let lastDetails = null;

/** The readable text of anything thrown (wasm-bindgen turns Rust errors into `Error`s). */
export function messageOf(error) {
  const text = readableText(error);
  lastDetails = typeof error?.details === 'string' && text ? { message: text, details: error.details } : null;
  return text;
}

function readableText(error) {
  // A refusal from the core, worded from its code's template in the page's language.
  const worded = errorText(error);
  if (worded) return worded;
  if (error instanceof Error) return error.message || String(error);
  if (typeof error === 'string') return error;
  try {
    return JSON.stringify(error);
  } catch {
    return String(error);
  }
}

/**
 * What a worker posts for an error it caught: the message and, for a refusal of the core, its
 * `code` and `args`, so the page words it in the page's language (a worker does not know the
 * page's `?lang=`). `errorFromData` makes it an `Error` for `messageOf` again.
 */
export function errorData(error) {
  if (!(error instanceof Error)) return { message: typeof error === 'string' ? error : String(error) };
  const data = { message: error.message };
  if (typeof error.code === 'string' && error.args && typeof error.args === 'object') Object.assign(data, { code: error.code, args: { ...error.args } });
  if (typeof error.details === 'string') data.details = error.details;
  return data;
}

/** The `Error` a worker's `errorData` stands for. */
export function errorFromData(data) {
  const error = new Error(typeof data?.message === 'string' ? data.message : String(data));
  if (typeof data?.code === 'string') Object.assign(error, { code: data.code, args: data.args });
  if (typeof data?.details === 'string') error.details = data.details;
  return error;
}

/**
 * Whether an error means the wasm instance is dead: a Rust panic ends in `unreachable`, and after
 * that the module's memory may be inconsistent, so it must not be called again.
 */
export function isPanic(error) {
  return typeof WebAssembly !== 'undefined' && error instanceof WebAssembly.RuntimeError;
}

/**
 * Shows `text` in the banner until the user dismisses it or another message replaces it, with
 * `details` (or those of the error it quotes) in a closed "details" disclosure.
 */
export function showMessage(text, details = null) {
  const quoted = lastDetails !== null && text.includes(lastDetails.message) ? lastDetails.details : null;
  lastDetails = null;
  const el = banner();
  if (!el) return;
  // Rust messages start in lower case (they compose); a sentence on a projector should not. A
  // message that starts with a field's path (`groups[0].count is -5`) keeps it as the JSON spells it.
  const startsWithPath = /^[^\s]*[[._]/.test(text);
  document.getElementById('banner-text').textContent = startsWithPath ? text : text.charAt(0).toUpperCase() + text.slice(1);
  showDetails(details ?? quoted);
  el.hidden = false;
}

/**
 * Puts `details` in the banner's disclosure (made once, after the text), closed; hides it when
 * there are none. Closed, it is one summary word beside the text, so the banner keeps its height.
 */
function showDetails(details) {
  let box = document.getElementById('banner-details');
  if (!details) {
    if (box) box.hidden = true;
    return;
  }
  if (!box) {
    box = document.createElement('details');
    box.id = 'banner-details';
    const summary = document.createElement('summary');
    summary.dataset.i18n = 'common.details';
    summary.textContent = t('common.details');
    box.append(summary, document.createElement('code'));
    document.getElementById('banner-text')?.after(box);
  }
  box.open = false;
  box.querySelector('code').textContent = details;
  box.hidden = false;
}

/** Hides the banner. */
export function hideMessage() {
  const el = banner();
  if (el) el.hidden = true;
}

/** Wires the banner's dismiss button (once, at boot). */
export function setupBanner() {
  document.getElementById('banner-close')?.addEventListener('click', hideMessage);
}

let lastPanicReport = null;

/**
 * Remembers the panic report Rust's panic hook writes with `console.error` just before the
 * `unreachable` trap: the trap itself only says "unreachable", the report says where and why.
 */
export function capturePanicReports() {
  const original = console.error.bind(console);
  console.error = (...args) => {
    const text = args.map(String).join(' ');
    if (/panicked at/.test(text)) lastPanicReport = text;
    original(...args);
  };
}

/**
 * Replaces the canvas area with a panel naming the crash and offering a reload: after a panic the
 * simulation cannot continue, and a frozen canvas would look like a hang. Returns false on a page
 * without a `#stage` (nothing shown).
 */
export function showPanic(message) {
  const stage = document.getElementById('stage');
  if (!stage) return false;
  if (stage.querySelector('.panic')) return true;
  for (const child of [...stage.children]) child.hidden = true;
  const panel = document.createElement('div');
  panel.className = 'panic';
  panel.setAttribute('role', 'alert');
  const title = document.createElement('h2');
  title.textContent = t('panic.title');
  const explain = document.createElement('p');
  explain.textContent = t('panic.explain');
  const pre = document.createElement('pre');
  pre.textContent = lastPanicReport ? `${lastPanicReport}\n\n${message}` : message;
  const reload = document.createElement('button');
  reload.type = 'button';
  reload.textContent = t('panic.reload');
  reload.addEventListener('click', () => location.reload());
  panel.append(title, explain, pre, reload);
  stage.append(panel);
  return true;
}
