// New scene: an empty world of a chosen size from the Scene menu's "New…" button. The world's
// limits are the core's (a refused size is said beside its field and the running scene stays);
// the new scene keeps the current seed and view options, and is one undo step like any load.

import { t } from '../core/i18n.js';
import { hideMessage, messageOf } from '../core/errors.js';

const $ = (id) => document.getElementById(id);

/** Wires the button and its dialog; `app` is the playground's App. */
export function setupNewScene(app) {
  const button = $('new-scene');
  const dialog = $('new-scene-dialog');
  const form = $('new-scene-form');
  if (!button || !dialog || !form) return;
  const width = $('new-scene-width');
  const height = $('new-scene-height');
  let note = null;
  const say = (message) => {
    note?.remove();
    note = null;
    for (const field of [width, height]) field.removeAttribute('aria-invalid');
    if (message === null) return;
    note = Object.assign(document.createElement('p'), { className: 'field-error', id: 'new-scene-refused', textContent: message });
    form.querySelector('.row-buttons').before(note);
    // The core names the field it refused (`width …` or `height …`).
    const field = /^height\b/.test(message) ? height : width;
    field.setAttribute('aria-invalid', 'true');
    field.setAttribute('aria-describedby', note.id);
  };

  button.addEventListener('click', () => {
    say(null);
    width.value = String(app.scene.width ?? 800);
    height.value = String(app.scene.height ?? 500);
    dialog.showModal();
    width.focus();
  });
  form.addEventListener('submit', async (event) => {
    if (event.submitter?.value !== 'create') return;
    // Checked by the core, not the form: its message names the field and the limit.
    event.preventDefault();
    const scene = {
      name: t('new_scene.name'),
      width: Number(width.value),
      height: Number(height.value),
      seed: app.scene.seed ?? 1,
      obstacles: [],
      goals: [],
      groups: [],
      ...(app.scene.view ? { view: app.scene.view } : {}),
    };
    const result = await app.load(JSON.stringify(scene));
    if (result?.ok) {
      // The refusal of a size tried before in this dialog no longer applies.
      if (note) hideMessage();
      dialog.close();
      return;
    }
    if (result?.error) say(messageOf(result.error));
  });
}
