// Playback controls every page with a SimHost shares (the playground and the compare page): the
// Play/Pause button (#play, its label and aria-pressed following the host), Step (#step, pauses
// first), Reset (#reset), the Speed slider (#spf, #spf-value: steps per frame, 0.1…20) and their
// keys (Space, S, R) while the page or a canvas has focus (keys.js).

import { formatNumber, setText } from './i18n.js';

const $ = (id) => document.getElementById(id);

/**
 * Slow motion: the Speed slider's positions below 1 (its `min` is −2), as steps per frame. The
 * worker runs one step every 1 / speed frames (core/sim-worker.js), so a class can follow single
 * steps of a crowd; from 1 on a position is that many steps per frame, as before.
 */
export const SLOW_SPEEDS = Object.freeze({ '-2': 0.1, '-1': 0.25, 0: 0.5 });
/** The fastest speed (steps per frame). */
export const MAX_SPEED = 20;

/** Steps per frame of a Speed slider position (−2 … 20; anything else is clamped). */
export function speedOf(position) {
  const p = Math.min(MAX_SPEED, Math.max(-2, Math.round(Number(position)) || 0));
  return p >= 1 ? p : SLOW_SPEEDS[p];
}

/** The Speed slider position showing `speed` steps per frame (the nearest one). */
export function sliderOf(speed) {
  if (speed >= 1) return Math.min(MAX_SPEED, Math.round(speed));
  const [position] = Object.entries(SLOW_SPEEDS).sort(([, a], [, b]) => Math.abs(a - speed) - Math.abs(b - speed))[0];
  return Number(position);
}

/**
 * Wires the playback buttons and the Speed slider to `app`; returns `key(e)`, which runs the
 * playback shortcut of a key event and says whether it was one (the page calls preventDefault).
 */
export function setupPlayback(app) {
  const play = $('play');
  const refreshPlay = () => {
    setText(play, app.playing ? 'playback.pause' : 'playback.play');
    play.setAttribute('aria-pressed', String(app.playing));
  };
  app.addEventListener('playing', refreshPlay);
  refreshPlay();
  const toggle = () => app.setPlaying(!app.playing);
  const stepOnce = () => {
    app.setPlaying(false);
    app.stepNow(1);
  };
  play.addEventListener('click', toggle);
  $('step').addEventListener('click', stepOnce);
  $('reset').addEventListener('click', () => app.reset());

  const spf = $('spf');
  const spfValue = $('spf-value');
  const applySpeed = () => {
    app.stepsPerFrame = speedOf(spf.value);
    setText(spfValue, 'playback.times', { n: formatNumber(app.stepsPerFrame) });
    spf.setAttribute('aria-valuetext', spfValue.textContent);
  };
  spf.value = String(sliderOf(app.stepsPerFrame));
  spf.addEventListener('input', applySpeed);
  applySpeed();

  return (e) => {
    if (e.key === ' ') toggle();
    else if (e.key === 's' || e.key === 'S') stepOnce();
    else if (e.key === 'r' || e.key === 'R') app.reset();
    else return false;
    return true;
  };
}
