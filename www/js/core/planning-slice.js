// How much planning ahead (IGSA paths) one call into the core asks for. The core's slice is a
// number of objective evaluations (`Sim.advance_planning(evaluations)`; it never reads a
// clock), and an evaluation costs microseconds in an empty scene and milliseconds among
// thousands of obstacles. A call also repeats the unfinished iteration's other work (a few ms
// at the largest population), so calls should not be too small either. So the caller times its
// calls and adapts: the budget doubles while a call takes under CALL_MS_LOW and halves above
// CALL_MS_HIGH, and a frame stops before a call that would likely overrun its time. The path
// does not depend on the slices.

/** A call quicker than this (ms) asks for twice the evaluations next time. */
const CALL_MS_LOW = 10;
/** A call slower than this (ms) asks for half. */
const CALL_MS_HIGH = 20;
/** Most evaluations one call asks for. */
const MOST_EVALUATIONS = 1 << 20;

export class PlanningBudget {
  constructor() {
    /** Objective evaluations the next call asks for. */
    this.evaluations = 1;
  }

  /**
   * Calls `advance(evaluations)` (which returns the share planned, 0…1) until planning is done
   * or the next call would likely end after `budgetMs`; at least one call. Returns the last share.
   */
  spend(advance, budgetMs) {
    const end = performance.now() + budgetMs;
    let progress;
    let took;
    do {
      const start = performance.now();
      progress = advance(this.evaluations);
      took = performance.now() - start;
      if (took < CALL_MS_LOW) this.evaluations = Math.min(MOST_EVALUATIONS, this.evaluations * 2);
      else if (took > CALL_MS_HIGH) this.evaluations = Math.max(1, Math.floor(this.evaluations / 2));
    } while (progress < 1 && performance.now() + Math.min(took, CALL_MS_HIGH) < end);
    return progress;
  }
}
