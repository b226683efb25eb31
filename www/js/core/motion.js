// prefers-reduced-motion: a reader who asked the system for less motion gets pages that start
// paused (the playground, compare, embeds and <flock-path> elements); Play still plays.

/** Whether the reader asked for less motion (`prefers-reduced-motion: reduce`). */
export function prefersReducedMotion() {
  return typeof matchMedia === 'function' && matchMedia('(prefers-reduced-motion: reduce)').matches;
}
