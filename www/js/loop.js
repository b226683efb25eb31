// The frame loop: requestAnimationFrame → step(stepsPerFrame) → render() → putImageData over a
// view of the wasm pixel buffer. Rust owns simulated time; wall-clock time only feeds the FPS.
// A hidden tab does not step (Page Visibility), and a frame never "catches up" on lost time: it
// always steps `stepsPerFrame` fixed steps, however long the tab was away.

import { PlanningSlices } from './planning.js';

/** Copies the Sim's RGBA frame to the canvas (the view is rebuilt: wasm memory may have grown). */
export function blit(app, ctx) {
  const { sim, wasm } = app;
  const width = sim.width();
  const height = sim.height();
  const pixels = new Uint8ClampedArray(wasm.memory.buffer, sim.frame_ptr(), sim.frame_len());
  if (pixels.length !== width * height * 4) return;
  if (ctx.canvas.width !== width || ctx.canvas.height !== height) return;
  ctx.putImageData(new ImageData(pixels, width, height), 0, 0);
}

/** Starts the loop; `onFrame(now)` runs after every frame (metrics, FPS). */
export function startLoop(app, canvas, onFrame) {
  const ctx = canvas.getContext('2d', { alpha: false });
  // A scene still planning its path gets a time slice per frame instead of a step.
  const planning = new PlanningSlices((fn) => app.guard(fn).value, canvas.parentElement, () => {
    app.afterLoad();
  });
  const frame = (now) => {
    if (app.crashed) return;
    if (planning.advance()) {
      app.dirty = true;
    } else if (app.playing && document.visibilityState !== 'hidden') {
      // A refused step (not a panic) would repeat every frame: pause and let the banner explain.
      if (!app.guard((sim) => sim.step(app.stepsPerFrame)).ok) app.setPlaying(false);
      app.dirty = true;
    }
    if (app.dirty) {
      app.dirty = false;
      app.guard((sim) => {
        sim.render();
        blit(app, ctx);
      });
    }
    onFrame(now);
    requestAnimationFrame(frame);
  };
  requestAnimationFrame(frame);
}
