// The frame loop of a page whose simulation runs in a worker (core/sim-worker.js, through
// core/sim-proxy.js): every animation frame draws the newest frame the worker rendered
// (putImageData over its transferred pixels) and acknowledges it, which lets the worker step the
// next one. The main thread steps nothing, so Pause, Step, a slider or a tool is answered at once
// whatever a step costs; the worker picks up the change after the step it is in.
//
// A step slower than SLOW_STEP_MS shows "slow scene: N steps/s" over the canvas while the scene
// plays on. A Pause the worker leaves unanswered for RESTART_AFTER_MS (it is inside one long step)
// ends the worker: a new one starts from the scene and replays the run to the step shown, with a
// message (sim-proxy.js `restart`).

import { setupPaceReadout } from './pace.js';
import { PlanningSlices } from './planning.js';
import { RESTART_AFTER_MS } from './sim-proxy.js';
import { formatNumber, t } from './i18n.js';

/** A step slower than this (ms) makes the scene "slow": its rate is shown. */
export const SLOW_STEP_MS = 100;
/** Waiting this long (ms) for the next frame of a playing scene shows the rate too. */
const SLOW_WAIT_MS = 500;
/** The steps-per-second figure covers the frames of the last this many ms. */
const RATE_WINDOW_MS = 10_000;

const SLOW_STYLE = `
.slow-scene { position: absolute; right: 8px; bottom: 8px; z-index: 4; padding: 2px 8px; border-radius: 6px;
  background: #fff6e0; color: #6b4500; border: 1px solid #e0b860; font: 13px/1.4 system-ui, sans-serif;
  font-variant-numeric: tabular-nums; pointer-events: none; }
.slow-scene[hidden] { display: none; }
`;

/** Steps per second in words: two significant digits below 10, whole numbers above. */
function rateText(rate) {
  if (rate >= 10) return formatNumber(Math.round(rate));
  if (rate >= 0.1) return formatNumber(Number(rate.toFixed(1)));
  return formatNumber(Number(rate.toFixed(2)));
}

let slowSheet = null;

/**
 * Adds the slow-scene style to `root` (the document's head, or an element's shadow root); returns
 * its removal. A shadow root gets a constructed sheet where the browser has them: unlike a
 * `<style>` element it is not refused by a host page's Content-Security-Policy (<flock-path> on a
 * course page, README "Hosting").
 */
function addStyle(root) {
  if (root instanceof ShadowRoot && 'adoptedStyleSheets' in root && typeof CSSStyleSheet.prototype.replaceSync === 'function') {
    if (!slowSheet) {
      slowSheet = new CSSStyleSheet();
      slowSheet.replaceSync(SLOW_STYLE);
    }
    root.adoptedStyleSheets = [...root.adoptedStyleSheets, slowSheet];
    return () => {
      root.adoptedStyleSheets = root.adoptedStyleSheets.filter((sheet) => sheet !== slowSheet);
    };
  }
  const style = document.createElement('style');
  style.textContent = SLOW_STYLE;
  root.append(style);
  return () => style.remove();
}

/** Draws a frame's one view onto `canvas` (nothing while a resize is on its way). */
export function drawFrame(canvas, pixels, width, height) {
  if (width !== canvas.width || height !== canvas.height) return;
  canvas.getContext('2d', { alpha: false }).putImageData(new ImageData(new Uint8ClampedArray(pixels), width, height), 0, 0);
  // For benchmarks and tests (scripts/bench-cold-load.mjs): when the page first showed a scene.
  if (!firstFrameMarked) {
    firstFrameMarked = true;
    performance.mark('flockpath-first-frame');
  }
}
let firstFrameMarked = false;

/**
 * Starts drawing `remote`'s frames (a RemoteSim) into `canvas` for `app` (a SimHost whose `sim` is
 * `remote.handle`); `onFrame(now)` runs after every animation frame. `readout`: the Speed slider's
 * frame-budget readout (pages with one); `styleRoot`: where the loop's style goes (a shadow root
 * for <flock-path>); `stage`: the positioned element the slow-scene rate and the planning bar go
 * over (the canvas's parent by default); `draw(frame)`: draws a frame (the compare page's panes;
 * by default its one view onto `canvas`). Returns `stop()`, which removes what the loop added.
 */
export function startRemoteLoop(
  app,
  remote,
  canvas,
  onFrame = () => {},
  { readout = true, styleRoot = document.head, stage = canvas.parentElement, draw = null } = {},
) {
  const pace = readout ? setupPaceReadout(app) : { note() {}, idle() {} };
  let stopped = false;

  const unstyle = addStyle(styleRoot);
  const slow = Object.assign(document.createElement('output'), { className: 'slow-scene', hidden: true });
  if (styleRoot === document.head) slow.id = 'slow-scene';
  slow.setAttribute('role', 'status');
  slow.setAttribute('part', 'slow-scene');
  // The rate sits in the stage's corner: the stage must be its containing block.
  if (getComputedStyle(stage).position === 'static') stage.style.position = 'relative';
  stage.append(slow);

  // The planning bar (IGSA): the worker plans in slices; the bar shows the mirrored progress.
  const planning = new PlanningSlices(
    (fn) => {
      const result = app.guard(fn);
      return typeof result?.then === 'function' ? result.then((r) => r.value) : result.value;
    },
    stage,
    () => app.afterLoad(),
  );

  /** Frames of the last RATE_WINDOW_MS as [time, steps]. */
  const recent = [];
  let lastFrameAt = performance.now();
  let lastStepMs = 0;
  const noteSteps = (now, steps) => {
    recent.push([now, steps]);
    while (recent.length > 2 && now - recent[0][0] > RATE_WINDOW_MS) recent.shift();
  };
  const showSlow = (now) => {
    const waiting = now - lastFrameAt;
    const isSlow = app.playing && !app.crashed && (lastStepMs > SLOW_STEP_MS || waiting > SLOW_WAIT_MS);
    if (!isSlow) {
      if (!slow.hidden) slow.hidden = true;
      return;
    }
    const [t0, s0] = recent[0] ?? [now, 0];
    const [, s1] = recent.at(-1) ?? [now, 0];
    const rate = now > t0 ? ((s1 - s0) * 1000) / (now - t0) : 0;
    const text = t('slow.scene', { rate: rateText(rate) });
    if (slow.textContent !== text) slow.textContent = text;
    const title = t('slow.title', { ms: formatNumber(Math.round(Math.max(lastStepMs, waiting))) });
    if (slow.title !== title) slow.title = title;
    slow.dataset.rate = String(rate);
    if (slow.hidden) slow.hidden = false;
  };

  // Play and pause go to the worker at once; a pause it leaves unanswered restarts it.
  let watchdog = null;
  // A hidden tab does not step (Page Visibility), and does not catch up when it comes back.
  const visible = () => !document.hidden && document.visibilityState !== 'hidden';
  const sendPlaying = () => {
    const seq = remote.control({ playing: app.playing && visible(), stepsPerFrame: app.stepsPerFrame });
    clearTimeout(watchdog);
    if (app.playing) {
      lastFrameAt = performance.now();
      return;
    }
    const asked = performance.now();
    let answered = false;
    const onAck = (event) => {
      if (event.detail.seq >= seq) answered = true;
    };
    remote.addEventListener('control-ack', onAck);
    watchdog = setTimeout(() => {
      remote.removeEventListener('control-ack', onAck);
      // A call in flight (a load, the API's step(n)) is the caller's to wait for.
      if (answered || stopped || app.crashed || app.playing || remote.busy() || remote.lastHeard > asked) return;
      const steps = remote.restart('stopped');
      app.say.error(t('worker.restarted', { seconds: RESTART_AFTER_MS / 1000, steps: formatNumber(steps) }));
      app.dirty = true;
    }, RESTART_AFTER_MS);
  };
  const onVisibility = () => {
    if (app.playing) sendPlaying();
  };
  const onRefused = (event) => {
    app.guard(() => {
      throw event.detail;
    });
    app.setPlaying(false);
  };
  const onPanic = (event) => app.crash(String(event.detail?.message ?? event.detail));
  const onStarted = () => {
    // A restarted worker: the page's state goes with it.
    if (remote.restarts > 0) sendPlaying();
  };
  app.addEventListener('playing', sendPlaying);
  document.addEventListener('visibilitychange', onVisibility);
  remote.addEventListener('refused', onRefused);
  remote.addEventListener('panic', onPanic);
  remote.addEventListener('started', onStarted);
  sendPlaying();

  const show = draw ?? ((frame) => drawFrame(canvas, frame.pixels, frame.width, frame.height));

  const tick = (now) => {
    if (stopped || app.crashed) return;
    if (remote.stepsPerFrame !== app.stepsPerFrame) remote.control({ stepsPerFrame: app.stepsPerFrame });
    if (app.dirty) {
      app.dirty = false;
      remote.control({ render: true });
    }
    const frame = remote.takeFrame();
    if (frame) {
      show(frame);
      // putImageData copied the pixels: their buffer goes back to the worker for the next frame.
      remote.ack(frame.panes);
      lastFrameAt = now;
      if (frame.done > 0) {
        lastStepMs = frame.stepMs ?? 0;
        noteSteps(now, remote.mirror.get('steps')?.value ?? 0);
        if (!frame.replaying) pace.note(now, frame.asked, frame.done);
      }
    }
    if (!app.playing) {
      pace.idle();
      recent.length = 0;
      lastStepMs = 0;
    } else if (recent.length === 0) {
      noteSteps(now, remote.mirror.get('steps')?.value ?? 0);
    }
    showSlow(now);
    // Planning ahead (IGSA) is a `Sim`'s: other handles have no progress to show.
    const progress = remote.mirror.get('planning_progress')?.value ?? 1;
    if (progress < 1) planning.show(progress);
    else planning.hide();
    onFrame(now);
    request = requestAnimationFrame(tick);
  };
  let request = requestAnimationFrame(tick);
  return () => {
    stopped = true;
    clearTimeout(watchdog);
    cancelAnimationFrame(request);
    app.removeEventListener('playing', sendPlaying);
    document.removeEventListener('visibilitychange', onVisibility);
    remote.removeEventListener('refused', onRefused);
    remote.removeEventListener('panic', onPanic);
    remote.removeEventListener('started', onStarted);
    unstyle();
    slow.remove();
    planning.hide();
  };
}
