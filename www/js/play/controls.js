// Playback, run settings, presets and keyboard shortcuts.

import { TOOLS } from './editor.js';
import { commandAllowed, onPage } from '../core/keys.js';
import { setupPlayback } from '../core/playback.js';
import { onLanguageChange, t, tOr } from '../core/i18n.js';

const $ = (id) => document.getElementById(id);

export function setupControls(app, editor) {
  const playbackKey = setupPlayback(app);

  // Seed: changing it restarts the run (set_seed resets), and is an undoable scene change.
  const seed = $('seed');
  const showSeed = () => {
    if (document.activeElement !== seed) seed.value = String(app.scene.seed ?? 0);
  };
  const setSeed = (value) => {
    if (!Number.isInteger(value) || value < 0 || value > 0xffffffff) {
      app.guard(() => {
        throw new Error(t('run.seed_refused', { value: seed.value || t('run.empty') }));
      });
      seed.value = String(app.scene.seed ?? 0);
      return;
    }
    app.change((sim) => sim.set_seed(value), { clearSelection: false });
  };
  seed.addEventListener('change', () => setSeed(Number(seed.value)));
  // "new seed": drawn in Rust (rng::fresh_seed, the browser's CSPRNG), then set like a typed one.
  $('new-seed').addEventListener('click', () => {
    const fresh = app.guard(() => app.module.fresh_seed());
    if (fresh.ok) setSeed(fresh.value);
  });
  app.addEventListener('scene', showSeed);
  showSeed();

  // Trails are a view option saved with the scene (a shared link shows them the same way).
  const trails = $('trails');
  const fade = $('fade');
  const fadeValue = $('fade-value');
  const showView = () => {
    trails.checked = app.trails;
    if (document.activeElement !== fade) fade.value = String(app.trailFade);
    fadeValue.textContent = app.trailFade.toFixed(3);
  };
  trails.addEventListener('change', () => app.setView({ trails: trails.checked }));
  fade.addEventListener('input', () => app.setView({ trailFade: Number(fade.value) }));
  app.addEventListener('scene', showView);
  showView();
  $('clear-trails').addEventListener('click', () => {
    app.guard((sim) => sim.clear_trails());
    app.dirty = true;
  });

  // Presets: the picker lists names; the line beside it shows the one-line description.
  const preset = $('preset');
  const description = $('preset-description');
  for (const p of app.presets) {
    preset.append(Object.assign(document.createElement('option'), {
      value: p.name,
      textContent: tOr(`preset.${p.name}`, p.name),
      title: tOr(`preset.${p.name}.description`, p.description),
    }));
  }
  const custom = Object.assign(document.createElement('option'), { value: '', textContent: t('play.edited_scene'), disabled: true });
  preset.append(custom);
  const showPreset = () => {
    const match = app.presets.find((p) => p.name === app.scene.name);
    preset.value = match ? match.name : '';
    description.textContent = match
      ? tOr(`preset.${match.name}.description`, match.description)
      : app.scene.name ? t('play.scene_named', { name: app.scene.name }) : '';
  };
  onLanguageChange(() => {
    for (const option of preset.options) {
      const p = app.presets.find((q) => q.name === option.value);
      if (p) Object.assign(option, { textContent: tOr(`preset.${p.name}`, p.name), title: tOr(`preset.${p.name}.description`, p.description) });
    }
    custom.textContent = t('play.edited_scene');
    showPreset();
  });
  preset.addEventListener('change', () => {
    const name = preset.value;
    const text = app.guard(() => app.module.preset_scene_json(name));
    if (text.ok) app.load(text.value);
    showPreset();
  });
  app.addEventListener('scene', showPreset);
  showPreset();

  // Shortcuts never take a focused control's keys (keys.js): Ctrl/⌘ ones act anywhere but in a
  // text field, single keys only while the page or the canvas has focus. On the focused canvas
  // the editor's keyboard cursor (arrows, Enter) gets its keys first.
  document.addEventListener('keydown', (e) => {
    if (app.crashed || e.defaultPrevented) return;
    const key = e.key;
    const ctrl = e.ctrlKey || e.metaKey;
    if (ctrl && !e.altKey) {
      if (!commandAllowed(e)) return;
      const lower = key.toLowerCase();
      if (lower === 'z' && !e.shiftKey) app.undo();
      else if ((lower === 'z' && e.shiftKey) || lower === 'y') app.redo();
      else return;
      e.preventDefault();
      return;
    }
    if (e.altKey || ctrl || !onPage(e)) return;
    if (playbackKey(e)) {
      e.preventDefault();
      return;
    }
    if (key >= '1' && key <= String(TOOLS.length)) editor.setTool(TOOLS[Number(key) - 1]);
    else if (key === 'Delete' || key === 'Backspace') editor.deleteSelection();
    else if (key === 'Escape') {
      editor.cancel();
      app.select(null);
    } else if (key === 'Enter' && ['polygon', 'path'].includes(editor.tool) && editor.polygon.length) editor.closePolygon();
    else return;
    e.preventDefault();
  });
}
