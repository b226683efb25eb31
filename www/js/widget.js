// The anywidget front end of flockpath (issue 28): `render({ model, el })` shows a <flock-path>
// element (js/flock-path.js: the embed view, its wasm and js/core/ modules, its worker) in `el`
// and keeps it in step with the model's synced state. Hosts that speak the anywidget contract
// (JupyterLab, Jupyter Notebook 7, VS Code, marimo; MyST's `{anywidget}` directive with no
// kernel) import this module by URL, so its relative imports and the wasm resolve against where
// it is served (the Python package serves its copy of www/ from the kernel: python/).
//
// Model state, set by the author (Python traitlets, or the directive's JSON, where an absent key
// takes the default named here):
//   scene     a preset name, a link's fragment value or whole link, or scene JSON ('' : the first preset)
//   controls  'all' (default), 'none' or a list such as 'play,step,reset' (the element's `controls`)
//   lock, hide  the teacher's options of a link, as the element takes them ('' : none)
//   theme     'standard' (default) or 'projector' (the canvas as the playground's projector theme draws it)
//   playing   whether it runs (default false); the widget writes it back when the reader presses Play / Pause
//   height    a CSS length for the box ('' : as tall as the scene's aspect ratio)
// Written by the widget: steps, metrics (the metrics object), digest (16 hex digits, as the CLI's
// `flockpath run` prints), activity_report (null without an activity), error ('' : none).
// Custom messages from the kernel: {type: 'step', n}, {type: 'reset'}; each is answered by
// writing the state above once the simulation has done it.
//
// Each render makes its own element, so several widgets on one page (or two views of one model)
// each run their own simulation; the wasm is loaded once per page (js/flock-path.js).

import './flock-path.js';

/** How often a playing widget writes its step, metrics and digest back to the model (ms). */
const REPORT_EVERY_MS = 500;

/** The element's `controls` attribute for a model's `controls` value (null: no bar; unset: all). */
function controlsAttribute(value) {
  const text = String(value ?? 'all').trim();
  if (text === 'none' || text === '') return null;
  return text === 'all' ? '' : text;
}

/** Listens to each of `names` (one event each: a host's model need not split a list). */
function listen(model, names, fn) {
  for (const name of names) model.on(name, fn);
  return () => {
    for (const name of names) model.off(name, fn);
  };
}

const OPTION_EVENTS = ['change:controls', 'change:lock', 'change:hide', 'change:height'];

/** Sets or removes an attribute (null or '': removed, except where '' means something). */
function setAttribute(element, name, value, { keepEmpty = false } = {}) {
  if (value === null || value === undefined || (value === '' && !keepEmpty)) element.removeAttribute(name);
  else element.setAttribute(name, value);
}

/** Reads the element's run into the model (one save), when it changed since the last report. */
function reporter(model, element) {
  let last = '';
  return async () => {
    if (!element.host || element.crashed) return;
    await element.settled();
    const metrics = element.metrics();
    const digest = element.digest();
    const step = element.steps;
    const report = element.call((sim) => sim.activity_report_json());
    const key = `${step}:${digest}:${report}`;
    if (key === last) return;
    last = key;
    model.set('steps', step);
    model.set('metrics', metrics);
    model.set('digest', digest);
    model.set('activity_report', report ? JSON.parse(report) : null);
    model.save_changes();
  };
}

function render({ model, el }) {
  const element = document.createElement('flock-path');
  const applyOptions = () => {
    setAttribute(element, 'controls', controlsAttribute(model.get('controls')), { keepEmpty: true });
    setAttribute(element, 'lock', model.get('lock') || null);
    setAttribute(element, 'hide', model.get('hide') || null);
    setAttribute(element, 'height', model.get('height') || null);
  };
  applyOptions();
  setAttribute(element, 'scene', model.get('scene') || null);
  el.append(element);

  const report = reporter(model, element);
  const fail = (message) => {
    model.set('error', String(message));
    model.save_changes();
  };
  element.addEventListener('flockpath-error', (event) => fail(event.detail));

  const applyTheme = () => {
    if (!element.host || element.crashed) return;
    Promise.resolve(element.host.sim.set_theme(model.get('theme') || 'standard')).catch(() => {});
    element.host.dirty = true;
  };
  const applyPlaying = () => (model.get('playing') ? element.play() : element.pause()).then(report);
  // The reader's Play / Pause button: the model hears of it.
  const followButton = () => {
    if (element.playing === model.get('playing')) return;
    model.set('playing', element.playing);
    model.save_changes();
  };

  const onScene = async () => {
    try {
      await element.load(model.get('scene') || element.presets[0].name);
      model.set('error', '');
      model.save_changes();
      await report();
    } catch (error) {
      fail(error?.message ?? error);
    }
  };
  const onMessage = async (message) => {
    try {
      if (message?.type === 'step') {
        await element.pause();
        if (model.get('playing')) {
          model.set('playing', false);
          model.save_changes();
        }
        await element.step(message.n);
      } else if (message?.type === 'reset') {
        await element.reset();
      } else {
        return;
      }
      await report();
    } catch (error) {
      fail(error?.message ?? error);
    }
  };

  let timer = null;
  let stopped = false;
  const unlisten = [];
  element.ready
    .then(async () => {
      if (stopped) return;
      applyTheme();
      await applyPlaying();
      element.host.addEventListener('playing', followButton);
      // The reader's Step and Reset buttons (and the element's own API) report like a message.
      element.host.addEventListener('stepped', report);
      unlisten.push(
        listen(model, ['change:scene'], onScene),
        listen(model, OPTION_EVENTS, applyOptions),
        listen(model, ['change:theme'], applyTheme),
        listen(model, ['change:playing'], applyPlaying),
        listen(model, ['msg:custom'], onMessage),
      );
      // While it plays, the step, metrics and digest follow a few times a second.
      timer = setInterval(() => {
        if (element.playing) report();
      }, REPORT_EVERY_MS);
      await report();
    })
    .catch((error) => fail(error?.message ?? error));

  return () => {
    stopped = true;
    clearInterval(timer);
    element.host?.removeEventListener('stepped', report);
    element.host?.removeEventListener('playing', followButton);
    for (const off of unlisten) off();
    element.remove();
  };
}

export default { render };
