// Teacher-locked scenes on the playground: the link's `controls=`, `lock=` and `hide=` options
// (read and checked in Rust, js/core/classroom.js) applied to the page. Controls not given are
// hidden with their keys; the editor's tools for a locked part are withdrawn, dragging or
// deleting a locked item does nothing, the Groups panel's fields are read-only while groups are
// locked, and while any part is locked the page does not replace the scene (Scene menu, scene
// file). The page API (`flockpath.*`) stays open for scripts. A pasted link with other options
// applies them.

import { classroomMessage, readClassroom } from '../core/classroom.js';
import { showMessage } from '../core/errors.js';
import { t } from '../core/i18n.js';
import { commandAllowed, onPage } from '../core/keys.js';

const $ = (id) => document.getElementById(id);
const closest = (id, selector) => $(id)?.closest(selector) ?? null;

/** The playground's elements each control stands for. */
const CONTROLS = {
  play: () => [$('play')],
  step: () => [$('step')],
  reset: () => [$('reset')],
  speed: () => [closest('spf', 'label')],
  planner: () => [closest('planner', 'label'), document.querySelector('.planner-note'), $('to-planner')],
  params: () => [$('params'), $('params-defaults')],
  seed: () => [closest('seed', '.row')],
  trails: () => [closest('trails', 'label'), closest('fade', '.row'), $('clear-trails')],
  presets: () => [closest('preset', 'label'), $('new-scene')],
  undo: () => [$('undo'), $('redo')],
  share: () => [$('share')],
  export: () => [$('export')],
  views: () => [document.querySelector('nav.pages')],
  fullscreen: () => [],
};

/** The playground's elements each panel stands for. */
const PANELS = {
  metrics: () => [closest('metrics-title', 'section')],
  plots: () => [closest('plots-title', 'section')],
  diagnose: () => [$('diagnose')],
  timeline: () => [document.querySelector('.timeline')],
  groups: () => [closest('groups-title', 'section')],
  keys: () => [closest('keys-title', 'section')],
};

/** The control a key stands for (the playground's shortcuts), or null. */
function keyControl(e) {
  if (e.ctrlKey || e.metaKey) return ['z', 'y'].includes(e.key.toLowerCase()) ? 'undo' : null;
  if (e.altKey) return null;
  if (e.key === ' ') return 'play';
  if (e.key === 's' || e.key === 'S') return 'step';
  if (e.key === 'r' || e.key === 'R') return 'reset';
  return null;
}

const HIDDEN = 'classroom-hidden';

/** Applies the link's classroom options to the playground; returns nothing, keeps them current. */
export function setupLock(app, editor) {
  const style = document.createElement('style');
  style.textContent = `.${HIDDEN} { display: none !important; }`;
  document.head.append(style);

  let current = null;

  const hide = (elements, hidden) => {
    for (const el of elements) el?.classList.toggle(HIDDEN, hidden);
  };

  const readOnlyGroups = () => {
    const locked = current?.view.lock.includes('groups') ?? false;
    for (const field of $('group-editor')?.querySelectorAll('input, select, button') ?? []) field.disabled = locked;
  };

  const apply = (classroom) => {
    current?.handle.free();
    current = classroom;
    const { view } = classroom;
    app.classroom = view;
    for (const [name, elements] of Object.entries(CONTROLS)) hide(elements(), !view.controls.includes(name));
    for (const [name, elements] of Object.entries(PANELS)) hide(elements(), view.hide.includes(name));
    // Cards left without their controls go too.
    hide([closest('planner-title', 'section')], !view.controls.includes('planner') && !view.controls.includes('params'));
    hide([closest('run-title', 'section')], !view.controls.includes('seed') && !view.controls.includes('trails'));
    // Replacing the scene would change locked parts.
    hide([closest('preset', 'label'), $('new-scene')], !view.controls.includes('presets') || !view.can_load);
    hide([$('open-scene')], !view.can_load);
    const tools = [...document.querySelectorAll('[data-tool]')];
    for (const button of tools) {
      const locked = view.locked_tools.includes(button.dataset.tool);
      hide([button], locked);
      button.disabled = locked;
    }
    const noTools = tools.every((b) => b.dataset.tool === 'select' || b.disabled);
    hide([$('tools')], noTools);
    // The Keys card lists only the shortcuts of controls the page shows.
    for (const item of document.querySelectorAll('#keys-list [data-keys-for]')) {
      const control = item.dataset.keysFor;
      hide([item], control === 'tools' ? noTools : !view.controls.includes(control));
    }
    if (view.locked_tools.includes(editor.tool)) editor.setTool('select');
    editor.showHint();
    readOnlyGroups();
    app.dispatchEvent(new Event('classroom'));
    if (classroom.errors.length) showMessage(classroom.errors.join(' '));
  };

  /** The edit the editor may send (Rust's check), or null with the reason in the hint line. */
  const permit = (op) => {
    if (!current) return op;
    try {
      return JSON.parse(current.handle.check_edit(JSON.stringify(op)));
    } catch (error) {
      const hint = $('hint');
      if (hint) hint.textContent = error?.part ? t(`classroom.locked.${error.part}`) : classroomMessage(error);
      return null;
    }
  };
  editor.lock = {
    lockedParts: () => current?.view.lock ?? [],
    toolAllowed: (tool) => !(current?.view.locked_tools.includes(tool) ?? false),
    // Asked when a pointer lands on an item (a refusal says why), and by the waypoint handles.
    movable: (item) => {
      if (!current) return true;
      if (item.kind === 'waypoint') return !current.view.lock.includes('paths');
      return permit({ op: 'move', item, dx: 0, dy: 0 }) !== null;
    },
    permit,
  };

  // Shortcuts of controls not given do nothing (where a shortcut would act: core/keys.js); a
  // focused control still gets its own key.
  window.addEventListener('keydown', (e) => {
    const control = keyControl(e);
    if (!current || !control || current.view.controls.includes(control)) return;
    const shortcut = control === 'undo' ? commandAllowed(e) : onPage(e);
    if (shortcut) e.stopImmediatePropagation();
  }, { capture: true });

  // A dropped scene file would replace locked parts; the browser must not open it either.
  for (const type of ['dragover', 'drop']) {
    document.addEventListener(type, (e) => {
      if (!current || current.view.can_load) return;
      e.preventDefault();
      e.stopPropagation();
    }, { capture: true });
  }

  app.addEventListener('scene', readOnlyGroups);
  addEventListener('hashchange', () => apply(readClassroom(app.module.Classroom.from_link(keptLock(location.hash)))));
  apply(readClassroom(app.module.Classroom.from_link(keptLock(location.hash))));
}

/** Where a tab remembers the classroom options of the link it was opened with. */
const KEPT = 'flockpath.classroom';

/** The classroom options (`controls=`, `lock=`, `hide=`) of a fragment, in its order. */
function classroomOptions(hash) {
  return hash.replace(/^#/, '').split('&').filter((part) => /^(controls|lock|hide)=/.test(part));
}

/**
 * The fragment to apply, keeping a tab's lock: a locked link remembers its options for the tab
 * (sessionStorage: a reload and links opened in it keep them; a new tab does not), and a link
 * without options opened in that tab (pasted, or the options deleted from the address bar) gets
 * them back, in the address bar too, with a message. Not security — it keeps a class focused.
 */
function keptLock(hash) {
  let store = null;
  try {
    store = window.sessionStorage;
  } catch {
    return hash;
  }
  const options = classroomOptions(hash);
  if (options.length) {
    store?.setItem(KEPT, options.join('&'));
    return hash;
  }
  const kept = store?.getItem(KEPT);
  if (!kept) return hash;
  const url = new URL(location.href);
  url.hash = [hash.replace(/^#/, ''), kept].filter(Boolean).join('&');
  history.replaceState(null, '', url);
  showMessage(t('classroom.kept'));
  return url.hash;
}
