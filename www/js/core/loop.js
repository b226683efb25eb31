// The frame loop: requestAnimationFrame → render() → putImageData over a view of the wasm pixel
// buffer, then the frame's steps in a task of their own right after it. Rust owns simulated
// time; wall-clock time only feeds the FPS and the frame budget below. A hidden tab does not step
// (Page Visibility), and a frame never "catches up" on lost time: it steps at most
// `stepsPerFrame` fixed steps, however long the tab was away.
//
// Stepping apart from drawing: the browser runs waiting input (a click on Pause, a key) between
// the two tasks, so a click waits for the longer of the two, not for both; and a Pause that
// arrives between them stops the steps that were about to run.
//
// Frame budget: the Speed slider asks for `stepsPerFrame` steps per frame, but a frame runs a
// further step only while the simulation work so far plus the last step's cost fits in
// SIM_BUDGET_MS (and no input is waiting), so a big crowd at 10× never freezes the page: it runs
// fewer steps per frame, and the toolbar says so ("→ 1.3× (frame budget)"). The first step of a
// frame always runs. Which steps run is unchanged (fixed steps, same seed, same run); only how
// many run per wall-clock frame.

/** Simulation work a frame may do before it stops stepping (ms): with the render and the panels
 * a 60 Hz frame (16.7 ms) keeps room to spare. */
export const SIM_BUDGET_MS = 10;
/** How often the "steps per frame run" readout may change (ms). */
const PACE_REFRESH_MS = 500;

const STYLE = `
.slider-inline:has(.spf-actual) { position: relative; }
.spf-actual { position: absolute; left: 0; top: 100%; z-index: 1; white-space: nowrap; pointer-events: none;
  font-size: 0.75rem; color: #8a5a00; background: #fff6e0; border-radius: 4px; padding: 0 0.3em;
  font-variant-numeric: tabular-nums; }
.spf-actual.idle { visibility: hidden; }
`;

import { blitSim } from './blit.js';
import { PlanningSlices } from './planning.js';
import { t } from './i18n.js';

/** Whether the browser has input waiting (Chromium's `isInputPending`; false elsewhere). */
function inputPending() {
  return navigator.scheduling?.isInputPending?.() === true;
}

/**
 * Runs up to `wanted` steps within the frame budget; returns `{ done, ok }` (`ok` false when the
 * core refused a step).
 */
export function stepWithinBudget(app, wanted, budgetMs = SIM_BUDGET_MS) {
  const start = performance.now();
  let done = 0;
  while (done < wanted) {
    const before = performance.now();
    if (!app.guard((sim) => sim.step(1)).ok) return { done, ok: false };
    done += 1;
    const after = performance.now();
    // Predict the next step from this one: never start a step that would overrun the budget.
    if (after - start + (after - before) > budgetMs || inputPending()) break;
  }
  return { done, ok: true };
}

/**
 * The "steps per frame run" readout under the Speed slider: shown while frames run fewer steps
 * than Speed asks for. It floats over the page (absolute), so showing it never moves the layout.
 * `app.pace` holds the last window's figures.
 */
export function setupPaceReadout(app) {
  const style = document.createElement('style');
  style.textContent = STYLE;
  document.head.append(style);
  const readout = Object.assign(document.createElement('output'), { id: 'spf-actual', className: 'spf-actual idle' });
  document.getElementById('spf-value')?.after(readout);
  let frames = 0;
  let wanted = 0;
  let done = 0;
  let since = null;
  app.pace = { wanted: app.stepsPerFrame, run: app.stepsPerFrame, limited: false };
  const show = (limited, text, title) => {
    readout.classList.toggle('idle', !limited);
    readout.dataset.limited = String(limited);
    if (readout.textContent !== text) readout.textContent = text;
    if (readout.title !== title) readout.title = title;
  };
  show(false, '', '');
  return {
    /** Notes a frame that stepped `ran` of `asked` steps. */
    note(now, asked, ran) {
      frames += 1;
      wanted += asked;
      done += ran;
      if (since === null) since = now;
      if (now - since < PACE_REFRESH_MS) return;
      const run = done / frames;
      // Limited only when the figure shown is below what Speed asks: a rare short frame (input
      // waiting) must not say "→ 2.0× (frame budget)" under a Speed of 2×.
      const limited = Number(run.toFixed(1)) < wanted / frames;
      app.pace = { wanted: asked, run, limited };
      show(
        limited,
        limited ? t('pace.short', { run: run.toFixed(1) }) : '',
        limited ? t('pace.long', { asked, run: run.toFixed(1), budget: SIM_BUDGET_MS }) : '',
      );
      frames = 0;
      wanted = 0;
      done = 0;
      since = now;
    },
    /** Paused: nothing is limited. */
    idle() {
      if (!app.pace.limited && since === null) return;
      frames = 0;
      wanted = 0;
      done = 0;
      since = null;
      app.pace = { wanted: app.stepsPerFrame, run: app.stepsPerFrame, limited: false };
      show(false, '', '');
    },
  };
}

/** Whether the scene still plans its path ahead (IGSA): then no step may run yet. */
const planningPending = (app) => !(app.guard((sim) => sim.planning_progress()).value >= 1);

const stepping = () => !document.hidden && document.visibilityState !== 'hidden';

/** The pace readout of a loop that shows none (a <flock-path> element has no Speed slider). */
const NO_READOUT = { note() {}, idle() {} };

/**
 * Starts the loop of `app` (a SimHost with `afterLoad()`) drawing into `canvas`; `onFrame(now)`
 * runs after every frame (metrics, FPS, a step counter). With `readout` (the pages with a Speed
 * slider, `#spf-value`) the frame budget's readout shows under the slider. Returns `stop()`.
 */
export function startLoop(app, canvas, onFrame = () => {}, { readout = true } = {}) {
  const ctx = canvas.getContext('2d', { alpha: false });
  const pace = readout ? setupPaceReadout(app) : NO_READOUT;
  let stopped = false;
  // A scene still planning its path gets a time slice per frame instead of steps (a step would
  // finish the planning in one go).
  const planning = new PlanningSlices((fn) => app.guard(fn).value, canvas.parentElement, () => {
    app.afterLoad();
  });
  let planningLeft = false;
  // The frame's steps run in a message task queued by the frame (not a timer: no clamping).
  const channel = new MessageChannel();
  let queued = false;
  channel.port1.onmessage = () => {
    queued = false;
    // A scene loaded since this task was queued may still be planning: a step would finish the
    // planning in one go, so the frame loop's slices take over.
    if (stopped || app.crashed || !app.playing || !stepping() || planningLeft || planningPending(app)) return;
    const wanted = app.stepsPerFrame;
    const { done, ok } = stepWithinBudget(app, wanted);
    // A refused step (not a panic) would repeat every frame: pause and let the banner explain.
    if (!ok) app.setPlaying(false);
    else pace.note(performance.now(), wanted, done);
    app.dirty = true;
  };
  const frame = (now) => {
    if (stopped || app.crashed) return;
    planningLeft = planning.advance();
    if (planningLeft) app.dirty = true;
    if (app.dirty) {
      app.dirty = false;
      app.guard((sim) => {
        sim.render();
        blitSim(ctx, app.wasm, sim);
      });
    }
    onFrame(now);
    if (app.playing && stepping() && !planningLeft) {
      if (!queued) {
        queued = true;
        channel.port2.postMessage(null);
      }
    } else {
      pace.idle();
    }
    request = requestAnimationFrame(frame);
  };
  let request = requestAnimationFrame(frame);
  return () => {
    stopped = true;
    cancelAnimationFrame(request);
  };
}
