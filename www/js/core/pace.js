// The "steps per frame run" readout under the Speed slider (the playground): the simulation worker
// (core/sim-worker.js) runs a further step in a frame only while the work so far plus the last
// step's cost fits in STEP_BUDGET_MS, so a big crowd at 10× runs fewer steps per frame, and the
// toolbar says so ("→ 1.3× (frame budget)"). Which steps run is unchanged (fixed steps, same
// seed, same run); only how many run per wall-clock frame. Nothing steps on a page's main thread
// (issue 24): core/remote-loop.js draws the worker's frames and feeds this readout.

/** Simulation work a frame may do before the worker stops stepping and shows it (ms). */
export const STEP_BUDGET_MS = 10;
/** How often the "steps per frame run" readout may change (ms). */
const PACE_REFRESH_MS = 500;

const STYLE = `
.slider-inline:has(.spf-actual) { position: relative; }
.spf-actual { position: absolute; left: 0; top: 100%; z-index: 1; white-space: nowrap; pointer-events: none;
  font-size: 0.75rem; color: #8a5a00; background: #fff6e0; border-radius: 4px; padding: 0 0.3em;
  font-variant-numeric: tabular-nums; }
.spf-actual.idle { visibility: hidden; }
`;

import { t } from './i18n.js';

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
        limited ? t('pace.long', { asked, run: run.toFixed(1), budget: STEP_BUDGET_MS }) : '',
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
