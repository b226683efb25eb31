// embed.html: one <flock-path> filling the iframe, its scene from the fragment (`#s=…`,
// `&autoplay=1`, `&controls=0`; the teacher's `&controls=play,step`, `&lock=…`, `&hide=…` become
// the element's attributes; `&scorm=1`, from a SCORM package's launch page, reports the activity
// to the LMS: core/scorm.js), an "open in flockpath" link carrying the current scene and those
// options (so the playground it opens is locked the same way), and a
// postMessage API so the host page can script the iframe like the page API:
//
//   iframe.contentWindow.postMessage({ flockpath: 1, id: 7, method: 'step', args: [60] }, '*');
//   // reply to the sender: { flockpath: 1, id: 7, ok: true, result: 60 }
//   //                   or { flockpath: 1, id: 7, ok: false, error: 'readable message' }
//
// Methods: load(scene), play(), pause(), step(n), reset(), metrics(), scene(), sceneString(),
// digest(), isPlaying(), classroom(). The reply to load, play, pause, step and reset comes once
// the simulation (in a worker) did it, so a read sent after it shows its effect. When it is ready the embed posts { flockpath: 1, event: 'ready' } to
// its parent; when it cannot load (wasm missing or refused) it posts { flockpath: 1, event:
// 'error', error } instead, and answers every request, waiting or new, with ok: false and that
// message.

import '../flock-path.js';
import { decodeValue, fragmentOptions } from '../core/fragment.js';
import { connectScorm } from '../core/scorm.js';

/** The methods a host may call, each mirroring the page API of the same name. */
const METHODS = {
  load: (el, scene) => el.load(scene),
  play: (el) => el.play(),
  pause: (el) => el.pause(),
  step: (el, n = 1) => el.step(n),
  reset: (el) => el.reset(),
  metrics: (el) => el.metrics(),
  scene: (el) => el.scene(),
  sceneString: (el) => el.sceneString(),
  digest: (el) => el.digest(),
  isPlaying: (el) => el.playing,
  classroom: (el) => el.classroom(),
  setClassroom: (el, options) => setClassroom(el, options),
};

/** The options a host may set with `setClassroom`. */
const CLASSROOM_OPTIONS = ['controls', 'lock', 'hide', 'openLink'];

/**
 * The teacher's options set by the host page instead of the iframe's URL (issue 27 §4), so a
 * student never meets them in an address bar: `{controls, lock, hide}` as comma lists or arrays
 * (null: back to everything allowed), `openLink: false` hides the "Open in flockpath" link (the
 * one way out to an editable link). Resolves to `classroom()`; a refused name is an error naming
 * the option and the allowed names (the other options still apply, as on the element).
 */
function setClassroom(el, options) {
  if (!options || typeof options !== 'object' || Array.isArray(options)) {
    throw new Error(`setClassroom expects one object {${CLASSROOM_OPTIONS.join(', ')}}`);
  }
  const unknown = Object.keys(options).find((key) => !CLASSROOM_OPTIONS.includes(key));
  if (unknown !== undefined) throw new Error(`setClassroom: unknown option ${JSON.stringify(unknown)}; known: ${CLASSROOM_OPTIONS.join(', ')}`);
  for (const name of ['controls', 'lock', 'hide']) {
    if (!(name in options)) continue;
    const value = options[name];
    // Back to everything allowed: a bare `controls` shows them all; no `lock`/`hide`, nothing.
    if (value === null && name === 'controls') el.setAttribute(name, '');
    else if (value === null) el.removeAttribute(name);
    else el.setAttribute(name, Array.isArray(value) ? value.join(',') : String(value));
  }
  if ('openLink' in options) openLink.hidden = options.openLink === false;
  refreshOpenLink();
  if (el.classroomErrors?.length) throw new Error(el.classroomErrors.join(' '));
  return el.classroom();
}

const el = document.getElementById('embedded');
const openLink = document.getElementById('open-full');
const options = fragmentOptions();
if (options.s) el.setAttribute('scene', decodeValue(options.s));
if (options.autoplay === '1' || options.autoplay === 'true') el.setAttribute('autoplay', '');
if (options.controls === '0' || options.controls === 'false') el.removeAttribute('controls');
else if (options.controls !== undefined) el.setAttribute('controls', decodeValue(options.controls));
for (const name of ['lock', 'hide']) {
  if (options[name] !== undefined) el.setAttribute(name, decodeValue(options[name]));
}
/** Opened from a SCORM package (its launch page adds `&scorm=1`): the playground is not in it. */
const inPackage = options.scorm === '1';
if (inPackage) openLink.remove();

/** Points the link at the full page with the scene as it is now (edits via the API included). */
function refreshOpenLink() {
  try {
    const url = new URL('index.html', location.href);
    const classroom = el.classroom()?.fragment;
    url.hash = `s=${el.sceneString()}${classroom ? `&${classroom}` : ''}`;
    openLink.href = url.href;
  } catch {
    // Not ready or crashed: the link keeps its last target.
  }
}
openLink.addEventListener('pointerenter', refreshOpenLink);
openLink.addEventListener('focus', refreshOpenLink);
openLink.addEventListener('click', refreshOpenLink);

/**
 * Resolves when the element can take calls; rejects with the load failure's message when it
 * never will (its `ready` stays pending then, and `flockpath-error` also reports refused calls,
 * so only an error that leaves the element `failed` counts).
 */
const booted = new Promise((resolve, reject) => {
  el.ready.then(resolve);
  const failure = (text) => reject(new Error(text));
  if (el.failed) failure(el.shadowRoot.querySelector('.message')?.textContent ?? 'flockpath could not be loaded');
  el.addEventListener('flockpath-error', (event) => {
    if (el.failed) failure(String(event.detail));
  });
});

// Messages that arrive before the simulation is ready wait for it (or for its load failure).
window.addEventListener('message', async (event) => {
  const data = event.data;
  if (!data || data.flockpath !== 1 || typeof data.method !== 'string' || !event.source) return;
  const reply = (body) => {
    // An opaque origin (a file:// host page) can only be answered with '*'.
    const target = event.origin && event.origin !== 'null' ? event.origin : '*';
    event.source.postMessage({ flockpath: 1, id: data.id, ...body }, target);
  };
  const method = METHODS[data.method];
  if (!Object.hasOwn(METHODS, data.method)) {
    reply({ ok: false, error: `unknown method ${JSON.stringify(data.method)}; known: ${Object.keys(METHODS).join(', ')}` });
    return;
  }
  try {
    await booted;
    // The element's simulation runs in a worker: calls that change it resolve once it did.
    const result = await method(el, ...(Array.isArray(data.args) ? data.args : []));
    if (data.method === 'load') refreshOpenLink();
    reply({ ok: true, result: result === undefined ? null : result });
  } catch (error) {
    reply({ ok: false, error: error instanceof Error ? error.message : String(error) });
  }
});

booted.then(
  () => {
    refreshOpenLink();
    // In an LMS the activity reports its completion and score to the LMS's SCORM runtime.
    if (inPackage) window.flockpathScorm = connectScorm(el.activity);
    window.flockpathEmbed = el;
    if (window.parent !== window) window.parent.postMessage({ flockpath: 1, event: 'ready' }, '*');
  },
  (error) => {
    if (window.parent !== window) window.parent.postMessage({ flockpath: 1, event: 'error', error: error.message }, '*');
  },
);
