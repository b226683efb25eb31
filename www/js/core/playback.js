// Playback controls every page with a SimHost shares (the playground and the compare page): the
// Play/Pause button (#play, its label and aria-pressed following the host), Step (#step, pauses
// first), Reset (#reset), the Speed slider (#spf, #spf-value: steps per frame, 1…20) and their
// keys (Space, S, R) while the page or a canvas has focus (keys.js).

import { setText } from './i18n.js';

const $ = (id) => document.getElementById(id);

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
    app.stepsPerFrame = Math.min(20, Math.max(1, Math.round(Number(spf.value)) || 1));
    setText(spfValue, 'playback.times', { n: app.stepsPerFrame });
  };
  spf.value = String(app.stepsPerFrame);
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
