// Planning ahead (IGSA group paths): a scene whose path is still being planned does not step; the
// simulation worker (core/sim-worker.js) gives the Sim's planning a time budget every frame
// (`Sim.advance_planning`, a few objective evaluations per call, core/planning-slice.js), and the page shows a bar over the
// canvas with the mirrored progress, and Cancel, which goes back to the scene shown before
// (`Sim.cancel_planning`). The path is the same whatever the slices: the core runs the same
// evaluations. Used by core/remote-loop.js (the playground, <flock-path>, the tune preview).

import { setAttr, setText, t } from './i18n.js';

const BOX_STYLE =
  'position:absolute;left:50%;top:12px;transform:translateX(-50%);z-index:5;display:flex;align-items:center;' +
  'gap:8px;padding:6px 10px;background:#fff;border:1px solid #c5cdd8;border-radius:8px;' +
  'box-shadow:0 2px 8px rgba(0,0,0,.15);font:14px/1.3 system-ui,sans-serif;color:#17202c;white-space:nowrap';

export class PlanningSlices {
  /**
   * @param {(fn: (sim: object) => any) => any} call runs `fn(sim)` through the host's guarded door
   * @param {HTMLElement} stage the positioned element the bar is laid over
   * @param {() => void} onCancelled called after Cancel brought the previous scene back
   */
  constructor(call, stage, onCancelled = () => {}) {
    this.call = call;
    this.stage = stage;
    this.onCancelled = onCancelled;
    this.box = null;
  }

  show(progress) {
    if (!this.box) {
      const box = document.createElement('div');
      box.className = 'planning';
      box.setAttribute('role', 'status');
      box.style.cssText = BOX_STYLE;
      const label = document.createElement('span');
      label.className = 'planning-label';
      const bar = document.createElement('progress');
      bar.max = 1;
      const cancel = document.createElement('button');
      cancel.type = 'button';
      cancel.className = 'planning-cancel';
      setText(cancel, 'common.cancel');
      setAttr(cancel, 'title', 'planning.cancel_title');
      cancel.addEventListener('click', () => this.cancel());
      box.append(label, bar, cancel);
      this.stage.append(box);
      this.box = box;
    }
    const percent = Math.floor(progress * 100);
    this.box.querySelector('.planning-label').textContent = t('planning.progress', { percent });
    this.box.querySelector('progress').value = progress;
    this.box.querySelector('.planning-cancel').hidden = !this.call((sim) => sim.can_cancel_planning());
  }

  hide() {
    this.box?.remove();
    this.box = null;
  }

  /** Goes back to the scene shown before the planning began. */
  cancel() {
    // A simulation in a worker answers with a Promise (core/remote-loop.js).
    Promise.resolve(this.call((sim) => sim.cancel_planning())).then((cancelled) => {
      if (!cancelled) return;
      this.hide();
      this.onCancelled();
    });
  }
}
