// The Share dialog's "For students" ticks: which controls students get, which parts of the scene
// they cannot edit, which panels are hidden. The ticks start as the page's own options; Rust turns
// them into link options (`&controls=…&lock=…&hide=…`) and `<flock-path>` attributes, which the
// dialog's link and snippets carry (share.js asks `options()`).

import { readClassroom } from '../core/classroom.js';
import { t } from '../core/i18n.js';

/** The three option lists, each with its legend and the key prefix of its names' labels. */
const FIELDS = [
  { key: 'controls', legend: 'classroom.share.controls', label: 'classroom.control.' },
  { key: 'lock', legend: 'classroom.share.lock', label: 'classroom.part.' },
  { key: 'hide', legend: 'classroom.share.hide', label: 'classroom.panel.' },
];

const STYLE = `
.share-lock { margin: 0.4rem 0 0.8rem; }
.share-lock[hidden] { display: none; }
.share-lock h3 { margin: 0; font-size: 1rem; }
.share-lock fieldset { border: 1px solid var(--line, #d5dbe3); border-radius: 6px; margin: 0.4rem 0; padding: 0.3rem 0.6rem; }
.share-lock .ticks { display: flex; flex-wrap: wrap; gap: 0.2rem 0.9rem; }
.share-lock label { white-space: nowrap; }
`;

/**
 * Adds the ticks to the Share dialog; `changed()` runs after every tick. Returns
 * `{ options() }`: `{fragment, attributes}` of the ticked options (fragment empty, attributes
 * ` controls` when everything is allowed: the snippets are then what they were without ticks).
 */
export function setupShareLock(app, changed) {
  const style = document.createElement('style');
  style.textContent = STYLE;
  document.head.append(style);
  const vocabulary = JSON.parse(app.module.classroom_vocabulary_json());

  // A section shown by a button beside "Copy link" (the dialog stays as tall as it was until the
  // author asks for the ticks: on a phone its Close button must stay on screen).
  const section = document.createElement('section');
  section.className = 'share-lock';
  section.id = 'share-lock';
  section.setAttribute('aria-labelledby', 'share-lock-title');
  const title = Object.assign(document.createElement('h3'), { id: 'share-lock-title', textContent: t('classroom.share.title') });
  const note = document.createElement('p');
  note.className = 'muted small-print';
  note.textContent = t('classroom.share.note');
  section.append(title, note);
  const toggle = Object.assign(document.createElement('button'), {
    type: 'button',
    id: 'share-lock-toggle',
    textContent: t('classroom.share.toggle'),
    title: t('classroom.share.title'),
  });
  toggle.setAttribute('aria-controls', section.id);
  const show = (open) => {
    section.hidden = !open;
    toggle.setAttribute('aria-expanded', String(open));
  };
  toggle.addEventListener('click', () => show(section.hidden));
  const boxes = {};
  for (const field of FIELDS) {
    const fieldset = document.createElement('fieldset');
    const legend = document.createElement('legend');
    legend.textContent = t(field.legend);
    const ticks = document.createElement('div');
    ticks.className = 'ticks';
    boxes[field.key] = vocabulary[field.key].map((name) => {
      const box = Object.assign(document.createElement('input'), { type: 'checkbox', value: name });
      box.dataset.classroom = `${field.key}:${name}`;
      box.addEventListener('change', changed);
      const label = document.createElement('label');
      label.className = 'check';
      label.append(box, ` ${t(field.label + name)}`);
      ticks.append(label);
      return box;
    });
    fieldset.append(legend, ticks);
    section.append(fieldset);
  }
  // The ticks start as the page's own options (lock.js applies them, also after a pasted link),
  // open when there are any: the author sees what the link will carry.
  const startFromPage = () => {
    const page = app.classroom ?? { controls: vocabulary.controls, lock: [], hide: [], open: true };
    for (const field of FIELDS) for (const box of boxes[field.key]) box.checked = page[field.key].includes(box.value);
    show(!page.open);
  };
  startFromPage();
  app.addEventListener('classroom', () => {
    startFromPage();
    changed();
  });
  const intro = document.querySelector('#share-dialog .dialog-body > p');
  intro.after(section);
  document.getElementById('copy-link').after(toggle);

  const ticked = (key) => boxes[key].filter((b) => b.checked).map((b) => b.value);
  return {
    options() {
      const classroom = readClassroom(app.module.classroom_from_ticks(ticked('controls'), ticked('lock'), ticked('hide')));
      classroom.handle.free();
      return { fragment: classroom.view.fragment, attributes: classroom.view.attributes };
    },
  };
}
