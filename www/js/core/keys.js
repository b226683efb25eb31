// Where the pages' keyboard shortcuts may act. A focused control keeps its own keys: Space ticks a
// focused checkbox or presses a focused button, Enter follows a link, arrows move a slider or a
// radio group, and a text field takes every key. Single-key shortcuts (Space, S, R, 1–7, Delete,
// Enter, Escape) therefore apply only while the page itself (the body) or a canvas has focus
// (WCAG 2.1.4: character-key shortcuts active only on focus); Ctrl/⌘ shortcuts (undo, redo),
// which no control uses, apply anywhere but in a text field.

/** Whether a key event is typing into a field (no shortcut may take its keys). */
export function typingInto(target) {
  if (!(target instanceof HTMLElement)) return false;
  if (target.isContentEditable || target.tagName === 'TEXTAREA' || target.tagName === 'SELECT') return true;
  return target.tagName === 'INPUT' && !['checkbox', 'radio', 'range', 'button', 'color'].includes(target.type);
}

/**
 * Whether single-key shortcuts may act on a key event: its target (the focused element) is the
 * page itself or a canvas (or an element marked `data-shortcuts`), never a control.
 */
export function onPage(e) {
  const target = e.target;
  if (!(target instanceof Element)) return true;
  if (target === document.body || target === document.documentElement) return true;
  return target.tagName === 'CANVAS' || target.hasAttribute('data-shortcuts');
}

/** Whether a Ctrl/⌘ shortcut may act on a key event (anywhere but a text field). */
export function commandAllowed(e) {
  return !typingInto(e.target);
}
