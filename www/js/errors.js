// Messages for the user: a dismissable banner for refused input, a loud panel for a crash.

const banner = () => document.getElementById('banner');

/** The readable text of anything thrown (wasm-bindgen turns Rust errors into `Error`s). */
export function messageOf(error) {
  if (error instanceof Error) return error.message || String(error);
  if (typeof error === 'string') return error;
  try {
    return JSON.stringify(error);
  } catch {
    return String(error);
  }
}

/**
 * Whether an error means the wasm instance is dead: a Rust panic ends in `unreachable`, and after
 * that the module's memory may be inconsistent, so it must not be called again.
 */
export function isPanic(error) {
  return typeof WebAssembly !== 'undefined' && error instanceof WebAssembly.RuntimeError;
}

/** Shows `text` in the banner until the user dismisses it or another message replaces it. */
export function showMessage(text) {
  const el = banner();
  if (!el) return;
  // Rust messages start in lower case (they compose); a sentence on a projector should not.
  document.getElementById('banner-text').textContent = text.charAt(0).toUpperCase() + text.slice(1);
  el.hidden = false;
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
 * simulation cannot continue, and a frozen canvas would look like a hang.
 */
export function showPanic(message) {
  const stage = document.getElementById('stage');
  if (!stage || stage.querySelector('.panic')) return;
  for (const child of [...stage.children]) child.hidden = true;
  const panel = document.createElement('div');
  panel.className = 'panic';
  panel.setAttribute('role', 'alert');
  const title = document.createElement('h2');
  title.textContent = 'The simulation crashed';
  const explain = document.createElement('p');
  explain.textContent =
    'This is a bug in flockpath, not in your scene. Copy the message below into a bug report, then reload.';
  const pre = document.createElement('pre');
  pre.textContent = lastPanicReport ? `${lastPanicReport}\n\n${message}` : message;
  const reload = document.createElement('button');
  reload.type = 'button';
  reload.textContent = 'Reload the page';
  reload.addEventListener('click', () => location.reload());
  panel.append(title, explain, pre, reload);
  stage.append(panel);
}
