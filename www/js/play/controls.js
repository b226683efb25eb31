// Playback, run settings, presets and keyboard shortcuts.

import { TOOLS } from './editor.js';
import { setupPlayback, typingInto } from '../core/playback.js';

const $ = (id) => document.getElementById(id);

/** A fresh seed from the browser's CSPRNG: user input, not simulation randomness. */
export function randomSeed() {
  return crypto.getRandomValues(new Uint32Array(1))[0];
}

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
        throw new Error(`the seed must be a whole number from 0 to 4294967295, not ${seed.value || 'empty'}`);
      });
      seed.value = String(app.scene.seed ?? 0);
      return;
    }
    app.change((sim) => sim.set_seed(value), { clearSelection: false });
  };
  seed.addEventListener('change', () => setSeed(Number(seed.value)));
  $('new-seed').addEventListener('click', () => setSeed(randomSeed()));
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
    preset.append(Object.assign(document.createElement('option'), { value: p.name, textContent: p.name, title: p.description }));
  }
  const custom = Object.assign(document.createElement('option'), { value: '', textContent: '(edited scene)', disabled: true });
  preset.append(custom);
  const showPreset = () => {
    const match = app.presets.find((p) => p.name === app.scene.name);
    preset.value = match ? match.name : '';
    description.textContent = match ? match.description : app.scene.name ? `Scene “${app.scene.name}”` : '';
  };
  preset.addEventListener('change', () => {
    const name = preset.value;
    const text = app.guard(() => app.module.preset_scene_json(name));
    if (text.ok) app.load(text.value);
    showPreset();
  });
  app.addEventListener('scene', showPreset);
  showPreset();

  document.addEventListener('keydown', (e) => {
    if (app.crashed || typingInto(e.target)) return;
    const key = e.key;
    const ctrl = e.ctrlKey || e.metaKey;
    if (ctrl && !e.altKey) {
      const lower = key.toLowerCase();
      if (lower === 'z' && !e.shiftKey) app.undo();
      else if ((lower === 'z' && e.shiftKey) || lower === 'y') app.redo();
      else return;
      e.preventDefault();
      return;
    }
    if (e.altKey) return;
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
  // A Space keyup on a focused button would also click it: the keydown already toggled.
  document.addEventListener('keyup', (e) => {
    if (e.key === ' ' && !typingInto(e.target)) e.preventDefault();
  });
}
