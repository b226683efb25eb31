// The timeline: a slider over the run's recorded history. Dragging it jumps to any step (Rust
// restores the nearest checkpoint and re-simulates, bit-identical to the original run); playing
// goes on from the step shown. The recording's budget and any thinning are stated under it.

import { formatNumber, language, onLanguageChange, setAttr, setText, t } from '../core/i18n.js';

/** How often the slider follows the run (ms, display only). */
const REFRESH_MS = 100;

const STYLE = `
.timeline { display: flex; align-items: center; gap: 0.6rem; padding: 0.25rem 1rem; background: var(--surface, #fff);
  border-bottom: 1px solid var(--line, #d5dbe3); font-size: 0.9rem; flex-wrap: wrap; }
.timeline input[type=range] { flex: 1; min-width: 12rem; }
.timeline output { font-variant-numeric: tabular-nums; min-width: 11rem; color: var(--muted, #5a6676); }
.timeline .timeline-note { flex-basis: 100%; margin: 0; color: #8a5a00; background: #fff6e0; border-radius: 6px;
  padding: 0.2rem 0.5rem; }
.timeline .timeline-note[hidden] { display: none; }
.timeline .timeline-seek { display: inline-flex; align-items: center; gap: 0.4rem; color: var(--muted, #5a6676);
  font-variant-numeric: tabular-nums; }
.timeline .timeline-seek[hidden] { display: none; }
`;

/** The timeline's state from the Sim (`timeline_json`), or null when the call was refused. */
export function timelineInfo(app) {
  const result = app.guard((sim) => JSON.parse(sim.timeline_json()));
  return result.ok ? result.value : null;
}

/**
 * Jumps to `step` (clamped to the recorded history) and tells the UI. Resolves to the guarded
 * result (the number of steps re-simulated). `rethrow` as in `app.guard`.
 */
export async function seekTo(app, step, options = {}) {
  const result = await app.guard((sim) => sim.seek(step), options);
  if (!result.ok) return result;
  app.dirty = true;
  // An edit made during the run (an obstacle, a parameter) is part of the history: the scene
  // shown may have changed with the jump.
  const info = timelineInfo(app);
  if (info && info.edits.length > 0) app.sceneChanged();
  app.dispatchEvent(new Event('stepped'));
  return result;
}

/**
 * The timeline's note (thinned positions or checkpoints, a replay that differed): the core's
 * words on English pages, else composed from the same numbers in the page's language.
 */
function noteText(app, info) {
  if (info.note === null || language() === 'en') return info.note;
  const agents = (app.scene.groups ?? []).reduce((sum, g) => sum + (g.count ?? 0), 0);
  const parts = [];
  if (info.frames_thinned > 0) {
    parts.push(t('timeline.note_frames', {
      every: info.frame_every,
      mb: Math.floor(info.frame_budget_bytes / 1e6),
      capacity: info.capacity_steps,
      agents,
    }));
  }
  if (info.checkpoints_thinned > 0) {
    parts.push(t('timeline.note_checkpoints', { every: info.checkpoint_every, resimulated: info.checkpoint_every - 1 }));
  }
  if (info.diverged > 0) parts.push(t('timeline.note_diverged', { n: info.diverged }));
  return parts.length ? t('timeline.note', { text: parts.join(t('list.semicolon')) }) : info.note;
}

export function setupTimeline(app) {
  const style = document.createElement('style');
  style.textContent = STYLE;
  document.head.append(style);

  const bar = document.createElement('div');
  bar.className = 'timeline';
  bar.setAttribute('role', 'group');
  setAttr(bar, 'aria-label', 'timeline.label');
  const label = setText(Object.assign(document.createElement('label'), { htmlFor: 'timeline' }), 'timeline.label');
  const slider = Object.assign(document.createElement('input'), {
    id: 'timeline',
    type: 'range',
    min: '0',
    max: '0',
    step: '1',
    value: '0',
  });
  setAttr(slider, 'title', 'timeline.title');
  const readout = Object.assign(document.createElement('output'), { id: 'timeline-step' });
  readout.setAttribute('for', 'timeline');
  const note = Object.assign(document.createElement('p'), { id: 'timeline-note', className: 'timeline-note', hidden: true });
  note.setAttribute('role', 'status');
  // A long jump (a scene whose steps take a second) re-simulates in slices in the worker: its
  // progress, as the worker reports it (core/sim-proxy.js `seeking`).
  const seek = Object.assign(document.createElement('span'), { id: 'timeline-seek', className: 'timeline-seek', hidden: true });
  seek.setAttribute('role', 'status');
  const seekBar = Object.assign(document.createElement('progress'), { max: 1, value: 0 });
  const seekText = document.createElement('span');
  seek.append(seekBar, seekText);
  bar.append(label, slider, readout, seek, note);
  document.querySelector('.toolbar')?.after(bar);

  let dragging = false;
  let resumeAfterDrag = false;
  let pending = null;

  // Attributes and text are written only when they change: every write restyles the page.
  const set = (node, key, value) => {
    if (node[key] !== value) node[key] = value;
  };
  const show = () => {
    const info = timelineInfo(app);
    if (!info) return;
    set(slider, 'min', String(info.first_step));
    set(slider, 'max', String(info.end_step));
    if (!dragging) set(slider, 'value', String(info.step));
    set(readout, 'textContent', t('timeline.step_of', { step: formatNumber(info.step), end: formatNumber(info.end_step) }));
    set(
      readout,
      'title',
      t('timeline.memory', {
        used: (info.frame_bytes / 1e6).toFixed(1),
        budget: (info.frame_budget_bytes / 1e6).toFixed(0),
        capacity: formatNumber(info.capacity_steps),
        checkpoints: info.checkpoints,
        every: info.checkpoint_every,
      }),
    );
    const jump = app.remote?.seeking ?? null;
    set(seek, 'hidden', jump === null);
    if (jump) {
      set(seekBar, 'value', jump.total > 0 ? jump.done / jump.total : 0);
      set(seekText, 'textContent', t('timeline.seeking', { step: formatNumber(jump.step), done: formatNumber(jump.done), total: formatNumber(jump.total) }));
    }
    note.hidden = info.note === null;
    const text = noteText(app, info);
    if (text !== null && note.textContent !== text) note.textContent = text;
  };

  // Jumps are coalesced to one per animation frame: a fast drag asks for many.
  const flush = () => {
    const step = pending;
    pending = null;
    if (step !== null) seekTo(app, step);
  };
  slider.addEventListener('input', () => {
    if (pending === null) requestAnimationFrame(flush);
    pending = Number(slider.value);
  });
  slider.addEventListener('pointerdown', () => {
    dragging = true;
    resumeAfterDrag = app.playing;
    if (app.playing) app.setPlaying(false);
  });
  const endDrag = () => {
    if (!dragging) return;
    dragging = false;
    if (resumeAfterDrag) app.setPlaying(true);
    resumeAfterDrag = false;
  };
  slider.addEventListener('pointerup', endDrag);
  slider.addEventListener('pointercancel', endDrag);
  slider.addEventListener('change', endDrag);

  app.addEventListener('stepped', show);
  app.addEventListener('scene', show);
  // Also while paused: the worker's last frames and a jump's progress arrive after the click.
  setInterval(() => {
    if (!app.crashed && !document.hidden) show();
  }, REFRESH_MS);
  show();
  onLanguageChange(show);
}
