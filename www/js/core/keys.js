// Where the pages' keyboard shortcuts may act. A focused control keeps its own keys: Space ticks a
// focused checkbox or presses a focused button, Enter follows a link, arrows move a slider or a
// radio group, and a text field takes every key. Single-key shortcuts (Space, S, R, 1–7, Delete,
// Enter, Escape) therefore apply only while the page itself (the body) or a canvas has focus
// (WCAG 2.1.4: character-key shortcuts active only on focus); Ctrl/⌘ shortcuts (undo, redo),
// which no control uses, apply anywhere but in a text field.
//
// A control focused by a mouse click or a tap is different: its user is not navigating by keyboard,
// and a button keeps the focus after it is clicked, so without this a click on Pause would switch
// S, R and 1–7 off until the canvas is clicked, and a scene picked from the menu would take the
// next S as type-ahead and switch scenes. There the shortcuts act on every key the control itself
// does not use (Space and Enter press it, arrows and Home/End move it); text fields keep all keys.

/** Keys a focused button, checkbox, radio, slider or select acts on itself. */
const CONTROL_KEYS = new Set(['Space', ' ', 'Enter', 'ArrowLeft', 'ArrowRight', 'ArrowUp', 'ArrowDown', 'Home', 'End', 'PageUp', 'PageDown']);

/** The element last focused by a pointer (mouse, pen, touch), or null after keyboard focus. */
let pointerFocused = null;
let pointerPressed = false;
if (typeof document !== 'undefined') {
  // Capture phase: seen before any page handler and before the focus moves (focus follows pointerdown).
  // A press focuses on pointerdown (a button, a select) or on its click (a label's checkbox); the
  // click follows pointerup in the same task, so the flag is cleared in the next one.
  document.addEventListener('pointerdown', () => (pointerPressed = true), true);
  for (const type of ['pointerup', 'pointercancel']) {
    document.addEventListener(type, () => setTimeout(() => (pointerPressed = false)), true);
  }
  document.addEventListener('keydown', () => (pointerPressed = false), true);
  document.addEventListener('focusin', (e) => (pointerFocused = pointerPressed ? e.target : null), true);
}

/** Whether a key goes into text: a text field, a text area or editable content. */
function textEntry(target) {
  if (target.isContentEditable || target.tagName === 'TEXTAREA') return true;
  return target.tagName === 'INPUT' && !['checkbox', 'radio', 'range', 'button', 'color', 'submit', 'reset'].includes(target.type);
}

/** Whether a key event is typing into a field (no shortcut may take its keys). */
export function typingInto(target) {
  if (!(target instanceof HTMLElement)) return false;
  if (target.isContentEditable || target.tagName === 'TEXTAREA' || target.tagName === 'SELECT') return true;
  return target.tagName === 'INPUT' && !['checkbox', 'radio', 'range', 'button', 'color'].includes(target.type);
}

/**
 * Whether single-key shortcuts may act on a key event: its target (the focused element) is the
 * page itself or a canvas (or an element marked `data-shortcuts`), or a control the pointer
 * focused and the key is not one the control uses; never a control focused by keyboard.
 */
export function onPage(e) {
  const target = e.target;
  if (!(target instanceof Element)) return true;
  if (target === document.body || target === document.documentElement) return true;
  if (target.tagName === 'CANVAS' || target.hasAttribute('data-shortcuts')) return true;
  // Never inside an open dialog: its keys (Escape closes it) are its own, and opening it by a
  // click moves the focus into it within that click.
  if (target.closest('dialog[open]')) return false;
  return target === pointerFocused && target instanceof HTMLElement && !textEntry(target) && !CONTROL_KEYS.has(e.key);
}

/** Whether a Ctrl/⌘ shortcut may act on a key event (anywhere but a text field). */
export function commandAllowed(e) {
  return !typingInto(e.target);
}
