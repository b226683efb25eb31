// <flock-path>: a live flockpath scene for course notes, one ES module to include (it loads its
// imports, js/core/, from next to itself).
//
//   <script type="module" src="flockpath/js/flock-path.js"></script>
//   <flock-path scene="2.ZZHd…" autoplay controls height="360px"></flock-path>
//
// Attributes: `scene` (a link's fragment value, a whole link, scene JSON, or a preset name),
// `autoplay`, `controls` (play/pause, step, reset, planner name), `width` / `height` (CSS lengths;
// by default the element is as wide as its container and as tall as the scene's aspect ratio),
// `fill` (fill the element's box instead, as embed.html does); `controls="play,step,reset,planner"`
// shows only those controls (bare `controls`: all), `lock="obstacles,goals"` and `hide="…"` are
// the teacher's options of a link (checked in Rust; this element has no editor or panels, so they
// only travel on: `classroom().fragment`). Several elements on one page run
// independently: each owns its own simulation; the wasm module is loaded once and shared. It runs on
// the shell's core (js/core/: the wasm loader, the guarded sim host, the frame loop with its
// hidden-tab pause, the blit and the backing-store sizing); every URL, its imports' included, is
// resolved against this module's own URL, so the folder works under any sub-path, offline.
// From a page on another site the server must allow CORS (README, "Hosting"). Children other than
// `slot="actions"` are fallback content: shown until the module upgrades the element, and all a
// reader sees if it never loads (the Share dialog's snippet carries "Loading…" and a link there).
//
// Methods mirror the page API: load(text), play(), pause(), step(n), reset(), metrics(), scene(),
// sceneString(), digest(), settled(); property `playing`, `steps`. The simulation runs in a Web
// Worker (js/core/sim-worker.js; issue 24) so a costly scene never blocks the host page: load,
// play, pause, step and reset return Promises (await them, then read), the reads answer at once
// from the state of the last frame or call. From a page on another site the worker starts from a
// same-origin blob that imports the worker module (core/module-worker.js; a host page's CSP must
// allow `blob:` and its origin in `worker-src`); nothing steps on the host page's thread. Events: `flockpath-ready`,
// `flockpath-error` (detail: message; also when the wasm cannot be loaded, shown in the box too).
// For screen readers the canvas is an image named "Simulated crowd", described by a visually
// hidden polite live region in the shadow root (core/describe.js: the scene and the run in
// words); with prefers-reduced-motion `autoplay` waits for Play.

import { mountActivityCard } from './core/activity-card.js';
import { loadWasm } from './core/boot.js';
import { noticeText } from './core/capacity-words.js';
import { readClassroom } from './core/classroom.js';
import { messageOf } from './core/errors.js';
import { startRemoteLoop } from './core/remote-loop.js';
import { SimHost } from './core/sim-host.js';
import { startsFromBlob } from './core/module-worker.js';
import { RemoteSim, WORKER_URL } from './core/sim-proxy.js';
import { setupDescription } from './core/describe.js';
import { prefersReducedMotion } from './core/motion.js';
import { onLanguageChange, t, translatePage, tOr } from './core/i18n.js';
import { measure, observeSize } from './core/view.js';
// Prints a still of each scene instead of a blank box.
import './core/print.js';

let shared = null;

/** The wasm module and its menus, loaded once for every element on the page. */
function loadModule() {
  shared ??= loadWasm().then(({ module, wasm }) => ({
    module,
    wasm,
    presets: JSON.parse(module.presets_json()),
    planners: JSON.parse(module.planners_json()),
  }));
  return shared;
}

const STYLE = `
:host { display: block; position: relative; font: 14px/1.3 system-ui, -apple-system, "Segoe UI", Roboto, sans-serif;
  color: #17202c; background: #f7f7f4; border: 1px solid #d5dbe3; border-radius: 8px; overflow: hidden; }
:host([hidden]) { display: none; }
.frame { display: flex; flex-direction: column; width: 100%; height: 100%; }
.stage { position: relative; width: 100%; min-height: 80px; }
:host([fill]) .stage, :host([height]) .stage, :host(:fullscreen) .stage { flex: 1; min-height: 0; aspect-ratio: auto !important; }
:host(:fullscreen) { width: 100%; height: 100%; border: 0; border-radius: 0; }
canvas { position: absolute; inset: 0; width: 100%; height: 100%; display: block; }
.bar { display: flex; align-items: center; gap: 6px; padding: 4px 6px; border-top: 1px solid #d5dbe3; background: #fff; flex-wrap: nowrap; overflow: hidden; }
.bar[hidden] { display: none; }
button { font: inherit; padding: 3px 10px; border: 1px solid #c5cdd8; border-radius: 6px; background: #fff; cursor: pointer; min-height: 28px; }
button:hover { border-color: #2f6fdf; }
button:focus-visible { outline: 3px solid #8db6ff; outline-offset: 1px; }
button.play { background: #2f6fdf; border-color: #2f6fdf; color: #fff; min-width: 64px; font-weight: 600; }
.planner { color: #5a6676; min-width: 0; overflow: hidden; text-overflow: ellipsis; white-space: nowrap; }
.steps { margin-left: auto; color: #5a6676; font-variant-numeric: tabular-nums; white-space: nowrap; flex: none; }
.bar button { flex: none; }
.message { position: absolute; left: 8px; right: 8px; top: 8px; margin: 0; padding: 6px 10px; background: #fdecea;
  border-left: 5px solid #b3261e; border-radius: 6px; color: #17202c; }
.message[hidden] { display: none; }
.message.fatal { position: relative; left: 0; right: 0; top: 0; margin: 8px; cursor: auto; }
.notice { margin: 0; padding: 4px 8px; border-top: 1px solid #d5dbe3; background: #fff8e1; color: #17202c; font-size: 13px; }
.notice[hidden] { display: none; }
.loading { position: absolute; inset: 0; display: flex; align-items: center; justify-content: center; color: #5a6676; }
.loading[hidden] { display: none; }
::slotted(a) { color: #2f6fdf; }
/* One line at any width (an embed's frame reserves one bar): the planner's name and the actions give way. */
::slotted(*) { min-width: 0; overflow: hidden; text-overflow: ellipsis; white-space: nowrap; }
.visually-hidden { position: absolute; width: 1px; height: 1px; margin: -1px; padding: 0; overflow: hidden;
  clip-path: inset(50%); white-space: nowrap; border: 0; }
`;

let sheet = null;

/**
 * Styles the shadow root with a constructed sheet where the browser has them: unlike a `<style>`
 * element it is not refused by a host page's Content-Security-Policy without 'unsafe-inline'.
 */
function adoptStyle(root) {
  if (!('adoptedStyleSheets' in root) || typeof CSSStyleSheet.prototype.replaceSync !== 'function') return false;
  if (!sheet) {
    sheet = new CSSStyleSheet();
    sheet.replaceSync(STYLE);
  }
  root.adoptedStyleSheets = [sheet];
  return true;
}

export class FlockPathElement extends HTMLElement {
  static get observedAttributes() {
    return ['scene', 'controls', 'width', 'height', 'autoplay', 'lock', 'hide'];
  }

  constructor() {
    super();
    const root = this.attachShadow({ mode: 'open' });
    root.innerHTML = `${adoptStyle(root) ? '' : `<style>${STYLE}</style>`}
      <div class="frame" part="frame">
        <div class="stage" part="stage">
          <canvas part="canvas" role="img" aria-describedby="description" data-i18n-aria-label="a11y.canvas.label"></canvas>
          <div class="loading" data-i18n="common.loading">Loading…</div>
          <p class="message" role="alert" hidden></p>
        </div>
        <div class="bar" part="controls" hidden>
          <button type="button" class="play" title="Play / pause" data-i18n-title="element.play_title">Play</button>
          <button type="button" class="step" title="Advance one step" data-i18n-title="element.step_title" data-i18n="playback.step">Step</button>
          <button type="button" class="reset" title="Restart from the seed" data-i18n-title="element.reset_title" data-i18n="playback.reset">Reset</button>
          <span class="planner"></span>
          <span class="steps" aria-live="off"></span>
          <button type="button" class="fullscreen" title="Full screen" aria-label="Full screen" data-i18n-title="element.fullscreen" data-i18n-aria-label="element.fullscreen" hidden><svg width="14" height="14" viewBox="0 0 14 14" aria-hidden="true" fill="none" stroke="currentColor" stroke-width="2"><path d="M1 5V1h4M9 1h4v4M13 9v4H9M5 13H1V9"/></svg></button>
          <slot name="actions"></slot>
        </div>
      </div>`;
    this.$ = (selector) => root.querySelector(selector);
    this.$('canvas').setAttribute('aria-label', t('a11y.canvas.label'));
    // The element's own words in the page's language (the page's `?lang=` or the browser's).
    translatePage(root);
    this.retranslate = () => {
      translatePage(root);
      this.refreshBar();
      this.shownSteps = -1;
      this.refreshSteps();
      this.refreshNotice();
    };
    /** The scene's capacity notices (goals too small for their crowd), as the core gave them. */
    this.notices = [];
    /** The simulation behind the core's guarded door (a SimHost), once booted. */
    this.host = null;
    this.module = null;
    /** Whether it should play once booted (play() or autoplay before the wasm arrived). */
    this.wantPlaying = false;
    this.stopLoop = null;
    this.shownSteps = -1;
    this.failed = false;
    /**
     * Resolves with the element once its simulation runs (before `flockpath-ready` fires), or
     * rejects with an Error naming why it cannot run (as `flockpath-error`'s detail says).
     * A host script can `await el.ready` instead of listening for both events.
     */
    this.ready = new Promise((resolve, reject) => {
      this.resolveReady = resolve;
      this.rejectReady = reject;
    });
    // Rejected only for those who await it: no "unhandled rejection" on a page that does not.
    this.ready.catch(() => {});
    this.$('.play').addEventListener('click', () => (this.playing ? this.pause() : this.play()));
    this.$('.step').addEventListener('click', () => {
      this.pause();
      this.step(1);
    });
    this.$('.reset').addEventListener('click', () => this.reset());
    const fullscreen = this.$('.fullscreen');
    fullscreen.hidden = !document.fullscreenEnabled;
    fullscreen.addEventListener('click', () => {
      if (document.fullscreenElement === this) document.exitFullscreen();
      else this.requestFullscreen?.().catch(() => {});
    });
    this.$('.message').title = t('element.dismiss');
    this.$('.message').addEventListener('click', () => this.hideMessage());
  }

  /** The wasm `Sim` handle (null until booted, and after the element is gone). */
  get sim() {
    return this.host?.sim ?? null;
  }

  get playing() {
    return this.host ? this.host.playing : this.wantPlaying;
  }

  get crashed() {
    return this.host?.crashed ?? false;
  }

  connectedCallback() {
    this.offLanguage ??= onLanguageChange(this.retranslate);
    this.applyLayout();
    if (!this.booting) this.booting = this.boot();
    else if (this.host) this.startLoop();
  }

  disconnectedCallback() {
    this.offLanguage?.();
    this.offLanguage = null;
    this.stopLoop?.();
    this.stopLoop = null;
    this.observer?.disconnect();
    // Free the simulation only if the element is really gone (not just moved in the DOM).
    queueMicrotask(() => {
      if (!this.isConnected && this.host) {
        this.activity?.stop();
        this.activity = null;
        this.description?.stop();
        this.description?.element.remove();
        this.description = null;
        this.host.remote.worker?.terminate();
        this.host = null;
        this.booting = null;
      }
    });
  }

  attributeChangedCallback(name, old, value) {
    if (old === value) return;
    if (name === 'scene' && this.host) this.tryLoad(value ?? '', { fallback: false });
    else if (['controls', 'lock', 'hide'].includes(name)) this.applyClassroom();
    else this.applyLayout();
  }

  applyLayout() {
    this.$('.bar').hidden = !this.hasAttribute('controls') || this.classroomView?.controls.length === 0;
    this.style.width = this.getAttribute('width') ?? '';
    this.style.height = this.getAttribute('height') ?? '';
    const stage = this.$('.stage');
    const scene = this.cachedScene;
    const sized = this.hasAttribute('fill') || this.hasAttribute('height');
    stage.style.aspectRatio = !sized && scene ? `${scene.width} / ${scene.height}` : '';
  }

  async boot() {
    let loaded;
    try {
      loaded = await loadModule();
    } catch (error) {
      this.fail(messageOf(error));
      return;
    }
    if (!this.isConnected) return;
    this.module = loaded.module;
    this.presets = loaded.presets;
    this.planners = loaded.planners;
    this.applyClassroom();
    const canvas = this.$('canvas');
    const { width, height } = measure(canvas);
    canvas.width = width;
    canvas.height = height;
    const first = this.module.preset_scene_json(this.presets[0].name);
    const attribute = (this.getAttribute('scene') ?? '').trim();
    // The simulation in a worker, the link's scene loaded there. From a module on another site the
    // worker starts from a same-origin blob that imports it (core/module-worker.js).
    const remote = new RemoteSim();
    let linkError = null;
    try {
      ({ linkError } = await remote.start({ sceneText: first, linked: attribute ? this.sceneText(attribute) : null, width, height }));
    } catch (error) {
      remote.worker?.terminate();
      const hint = startsFromBlob(WORKER_URL) ? t('boot.hint_worker_csp') : '';
      if (this.isConnected) this.fail(t('element.worker_failed', { reason: messageOf(error).replace(/[.?!。]$/, ''), hint }));
      return;
    }
    if (!this.isConnected) {
      remote.worker?.terminate();
      return;
    }
    const sim = remote.handle;
    // Errors and crashes speak in this element's box and events, not in the host page's banner.
    const event = (message) =>
      this.dispatchEvent(new CustomEvent('flockpath-error', { detail: message, bubbles: true, composed: true }));
    this.host = new SimHost(loaded.wasm, this.module, sim, {
      error: event,
      panic: (message) => {
        this.showMessage(t('element.crashed', { message }));
        event(message);
      },
    });
    this.host.remote = remote;
    // `autoplay` waits for Play when the reader asked for less motion; a script's play() does not.
    this.host.playing = this.wantPlaying || (this.hasAttribute('autoplay') && !prefersReducedMotion());
    this.host.afterLoad = () => this.afterLoad();
    this.host.addEventListener('playing', () => this.refreshBar());
    this.host.addEventListener('stepped', () => this.refreshSteps());
    this.linkLoaded(attribute, linkError);
    this.mountActivity();
    this.$('.loading').hidden = true;
    // The scene and the run in words for screen readers, beside the canvas (core/describe.js).
    this.description = setupDescription(this.host, canvas, () =>
      this.host && !this.crashed
        ? {
            scene: this.cachedScene,
            planners: this.planners,
            playing: this.playing,
            metrics: this.host.guard((s) => JSON.parse(s.metrics_json())).value ?? null,
          }
        : null,
    { id: 'description' });
    this.observer = observeSize(canvas, (size) => this.fitCanvas(size));
    this.refreshBar();
    this.startLoop();
    this.resolveReady(this);
    this.dispatchEvent(new CustomEvent('flockpath-ready', { bubbles: true, composed: true }));
  }

  /** The scene's activity card (prompt, prediction, check) between the canvas and the bar. */
  mountActivity() {
    const slot = document.createElement('div');
    slot.className = 'activity';
    slot.setAttribute('part', 'activity');
    this.$('.bar').before(slot);
    // The scene check's notice that a goal cannot hold its crowd, under the activity card.
    const notice = Object.assign(document.createElement('p'), { className: 'notice', hidden: true });
    notice.setAttribute('part', 'notice');
    notice.setAttribute('role', 'status');
    this.$('.bar').before(notice);
    this.refreshNotice();
    const read = (fn) => (this.host && !this.crashed ? JSON.parse(this.call(fn)) : null);
    this.activity = mountActivityCard(this.host, slot, {
      readActivity: () => read((sim) => sim.activity_json()),
      readReport: () => read((sim) => sim.activity_report_json()),
      groupName: (i) => this.cachedScene?.groups?.[i]?.name ?? '',
      styleRoot: this.shadowRoot,
    });
  }

  /** The core's frame loop on this element's canvas (no Speed readout: the element has no slider). */
  startLoop() {
    if (this.stopLoop || !this.host) return;
    const canvas = this.$('canvas');
    const onFrame = () => this.refreshSteps();
    this.stopLoop = startRemoteLoop(this.host, this.host.remote, canvas, onFrame, { readout: false, styleRoot: this.shadowRoot });
  }

  /**
   * Applies the `controls`, `lock` and `hide` attributes (parsed in Rust): only the controls
   * named are shown; a refused attribute is said in the box and by `flockpath-error`, and left
   * allowing everything.
   */
  applyClassroom() {
    if (!this.module) return;
    const value = (name) => (this.hasAttribute(name) ? this.getAttribute(name) : undefined);
    // Without `controls` the element shows no control bar.
    const classroom = readClassroom(new this.module.Classroom(value('controls') ?? 'none', value('lock'), value('hide')));
    classroom.handle.free();
    this.classroomView = classroom.view;
    /** The refusals of the last attributes applied (a host's `setClassroom` answers with them). */
    this.classroomErrors = classroom.errors;
    const shown = classroom.view.controls;
    for (const name of ['play', 'step', 'reset', 'planner']) this.$(`.${name}`).hidden = !shown.includes(name);
    this.$('.fullscreen').hidden = !document.fullscreenEnabled || !shown.includes('fullscreen');
    this.applyLayout();
    if (classroom.errors.length) {
      const text = classroom.errors.join(' ');
      this.showMessage(text);
      this.dispatchEvent(new CustomEvent('flockpath-error', { detail: text, bubbles: true, composed: true }));
    }
  }

  /** The classroom options applied: `{controls, lock, hide, …, fragment, attributes}` (a copy). */
  classroom() {
    return structuredClone(this.classroomView ?? null);
  }

  /** Resolves a scene attribute: a preset name, else JSON / fragment / URL text. */
  sceneText(text) {
    const trimmed = text.trim();
    const preset = this.presets.find((p) => p.name === trimmed);
    return preset ? this.module.preset_scene_json(preset.name) : trimmed;
  }

  /** Loads from an attribute: on failure shows the message and keeps (or falls back to) a scene. */
  async tryLoad(text, { fallback }) {
    if (!text.trim()) {
      this.afterLoad();
      return;
    }
    let error = null;
    try {
      await this.call((sim) => sim.load(this.sceneText(text)));
    } catch (thrown) {
      error = thrown;
    }
    this.linkLoaded(text, error, { fallback });
  }

  /** Says how loading the `scene` attribute went (`error` null: loaded) and shows the scene. */
  linkLoaded(text, error, { fallback = true } = {}) {
    if (error === null) {
      if (text.trim()) this.hideMessage();
    } else {
      const reason = messageOf(error).replace(/[.?!。]$/, '');
      const name = tOr(`preset.${this.presets[0].name}`, this.presets[0].name);
      this.showMessage(t(fallback ? 'element.load_failed_fallback' : 'element.load_failed_kept', { reason, name }));
      // The worker refused it quietly (a start option): the page's listeners still hear of it.
      if (fallback) this.host?.say.error(messageOf(error));
    }
    this.afterLoad();
  }

  afterLoad() {
    if (!this.host) return;
    this.cachedScene = JSON.parse(this.call((sim) => sim.scene_json()));
    this.applyLayout();
    this.host.dirty = true;
    this.activity?.refresh();
    this.refreshBar();
    this.description?.update();
    try {
      this.notices = JSON.parse(this.call((sim) => sim.capacity_notices_json()));
    } catch {
      this.notices = [];
    }
    this.refreshNotice();
  }

  /** Says, under the canvas, which goals cannot hold the crowd heading for them (none: hidden). */
  refreshNotice() {
    const box = this.$('.notice');
    if (!box) return;
    box.textContent = this.notices.map(noticeText).join(' ');
    box.hidden = this.notices.length === 0;
  }

  /**
   * Every wasm call goes through the core's guarded door: an error fires `flockpath-error` and is
   * thrown again; a panic stops this element and says so in its box.
   */
  call(fn) {
    if (!this.host) throw new Error('flock-path is still loading');
    const result = this.host.guard(fn, { rethrow: true });
    // A call answered by the worker: a Promise of its value.
    return typeof result?.then === 'function' ? result.then((settled) => settled.value) : result.value;
  }

  /** The element cannot run: says why in its box and tells the host page. */
  fail(text) {
    this.$('.loading').hidden = true;
    this.showMessage(text);
    // It stays (nothing else would fill the box) and takes the room it needs in the box.
    this.failed = true;
    // Buttons that could only fail go; slotted actions (embed.html's "Open in flockpath") stay.
    for (const button of this.shadowRoot.querySelectorAll('.bar button')) button.hidden = true;
    this.$('.message').classList.add('fatal');
    this.$('.message').title = '';
    this.rejectReady(new Error(text));
    this.dispatchEvent(new CustomEvent('flockpath-error', { detail: text, bubbles: true, composed: true }));
  }

  showMessage(text) {
    const el = this.$('.message');
    el.textContent = text;
    el.hidden = false;
  }

  hideMessage() {
    if (this.failed) return;
    this.$('.message').hidden = true;
  }

  /** The backing store follows the canvas's CSS box (the core's sizing, one pixel cap). */
  fitCanvas({ width, height }) {
    if (!this.host || this.crashed) return;
    const canvas = this.$('canvas');
    if (canvas.width === width && canvas.height === height) return;
    canvas.width = width;
    canvas.height = height;
    this.host.guard((sim) => sim.resize(width, height));
    this.host.dirty = true;
  }

  refreshBar() {
    this.$('.play').textContent = this.playing ? t('playback.pause') : t('playback.play');
    this.$('.play').setAttribute('aria-pressed', String(this.playing));
    const names = [...new Set((this.cachedScene?.groups ?? []).map((g) => g.planner.kind))];
    const label = (name) => tOr(`planner.${name}`, this.planners?.find((p) => p.name === name)?.label ?? name);
    this.$('.planner').textContent = names.map(label).join(', ');
    this.refreshSteps();
  }

  refreshSteps() {
    if (!this.host || this.crashed) return;
    const steps = this.host.sim.steps();
    if (steps === this.shownSteps) return;
    this.shownSteps = steps;
    this.$('.steps').textContent = t('playback.step_count', { n: steps.toLocaleString('en-US') });
  }

  // ---- the page API, per element ----

  /**
   * Loads a scene (JSON text or object, fragment value, URL, preset name); resolves to the scene;
   * rejects and keeps the current one.
   */
  async load(scene) {
    const text = scene !== null && typeof scene === 'object' ? JSON.stringify(scene) : String(scene);
    await this.call((sim) => sim.load(this.sceneText(text)));
    this.hideMessage();
    this.afterLoad();
    return this.scene();
  }

  /** Plays; resolves once the simulation plays. */
  play() {
    this.setPlaying(true);
    return this.settled();
  }

  /** Pauses; resolves once the simulation stopped, the reads showing the step it stopped at. */
  pause() {
    this.setPlaying(false);
    return this.settled();
  }

  /** Resolves once the simulation has answered every call so far. */
  async settled() {
    const remote = this.host?.remote;
    if (!remote) return;
    do {
      await remote.call('steps').catch(() => {});
      await new Promise((resolve) => setTimeout(resolve, 0));
    } while (remote.busy());
  }

  setPlaying(playing) {
    if (this.host) this.host.setPlaying(playing);
    else this.wantPlaying = playing;
    this.refreshBar();
  }

  /** Advances `n` steps now; resolves to the step count. */
  async step(n = 1) {
    const count = Number(n);
    if (!Number.isInteger(count) || count < 0 || count > 0xffffffff) {
      throw new RangeError(`step(n) takes a whole number of steps ≥ 0, not ${n}`);
    }
    if (!this.host) throw new Error('flock-path is still loading');
    return (await this.host.stepNow(count, { rethrow: true })).value;
  }

  /** Back to step 0; resolves once it is. */
  async reset() {
    if (!this.host) throw new Error('flock-path is still loading');
    await this.host.reset({ rethrow: true });
  }

  get steps() {
    return this.call((sim) => sim.steps());
  }

  metrics() {
    return JSON.parse(this.call((sim) => sim.metrics_json()));
  }

  scene() {
    return JSON.parse(this.call((sim) => sim.scene_json()));
  }

  sceneString() {
    return this.call((sim) => sim.scene_string());
  }

  digest() {
    return String(this.call((sim) => sim.digest()));
  }
}

if (!customElements.get('flock-path')) customElements.define('flock-path', FlockPathElement);
