// Undo/redo: two stacks of whole-scene JSON snapshots (scenes are small; agents are not in them).

export class History {
  /** @param {number} limit most undo steps kept */
  constructor(limit = 200) {
    this.limit = limit;
    this.undoStack = [];
    this.redoStack = [];
  }

  /** Records the scene as it was before a change; a new change forgets the redo branch. */
  record(sceneJson) {
    if (this.undoStack[this.undoStack.length - 1] === sceneJson) return;
    this.undoStack.push(sceneJson);
    if (this.undoStack.length > this.limit) this.undoStack.shift();
    this.redoStack.length = 0;
  }

  get canUndo() {
    return this.undoStack.length > 0;
  }

  get canRedo() {
    return this.redoStack.length > 0;
  }
}

/**
 * Wires the Undo/Redo buttons and the on-screen Delete (the Delete key's button, for touch
 * screens), and keeps their enabled state current.
 */
export function setupHistoryButtons(app, editor) {
  const remove = document.getElementById('delete-selection');
  if (remove) {
    remove.addEventListener('click', () => editor.deleteSelection());
    const selected = () => (remove.disabled = app.selection === null);
    app.addEventListener('selection', selected);
    selected();
  }
  const undo = document.getElementById('undo');
  const redo = document.getElementById('redo');
  undo.addEventListener('click', () => app.undo());
  redo.addEventListener('click', () => app.redo());
  const refresh = () => {
    undo.disabled = !app.history.canUndo;
    redo.disabled = !app.history.canRedo;
  };
  app.addEventListener('history', refresh);
  app.addEventListener('scene', refresh);
  refresh();
}
