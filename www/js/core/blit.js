// The blit: a frame Rust rendered into wasm memory (RGBA, row by row) copied onto a 2-D canvas
// with putImageData. The view over wasm memory is made afresh every time: memory may have grown
// (and detached the last view) since the previous frame.

/**
 * Copies `len` bytes at `ptr` of `wasm.memory` (a `width`×`height` RGBA frame) onto `ctx`'s canvas.
 * Does nothing and returns false when the frame and the canvas disagree on the size (a resize is
 * on its way).
 */
export function blit(ctx, wasm, ptr, len, width = ctx.canvas.width, height = ctx.canvas.height) {
  if (len !== width * height * 4 || ctx.canvas.width !== width || ctx.canvas.height !== height) return false;
  ctx.putImageData(new ImageData(new Uint8ClampedArray(wasm.memory.buffer, ptr, len), width, height), 0, 0);
  return true;
}

/** Copies the frame of a handle with `frame_ptr()`, `frame_len()`, `width()`, `height()` (a `Sim`). */
export function blitSim(ctx, wasm, sim) {
  return blit(ctx, wasm, sim.frame_ptr(), sim.frame_len(), sim.width(), sim.height());
}
