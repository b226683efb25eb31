// Every preset in the page's Scene menu, run in Chromium for a fixed number of steps: an
// independent recount from the page's `positions()`, `goals()` and `scene()`
// (tests/e2e/recount-helpers.mjs) equals `metrics()` — the agents counted as arrived are the
// ones inside their goal where it is now, no more are counted waiting than stand at rest
// outside their goal, the exited are the ones inside an exit — and no two bodies at rest
// overlap (issue 23 §3; the same definitions as the native tests/arrival_recount.rs, on the
// wasm build the page runs). Regression: `pillars` said "Arrived 100.0 %" with 2 of 80 inside
// the goal ring; the virtual-forces presets ended as a pile with 37–53 pairs overlapping.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPage } from './helpers.mjs';
import { disagreements, recount, runAndRead } from './recount-helpers.mjs';

/** Steps for most presets (25 s of simulated time). */
const STEPS = 1500;

/**
 * The large crowds, the bottleneck and the narrow passage need longer to settle (60 s), as in
 * the native recount.
 */
const HEAVY = new Set([
  'igsa-crowd-1000',
  'pso-hills',
  'social-force-bottleneck',
  'csm-bottleneck',
  'orca-crossing',
  'forces-e2-narrow',
  'pso-static-obstacle',
]);
const HEAVY_STEPS = 3600;

test('every preset: the recount from the page’s positions equals metrics() and nothing at rest overlaps', { timeout: 300_000 }, async () => {
  const { page, errors, close } = await openPage({ hash: '' });
  try {
    const names = await page.$$eval('#preset option', (options) => options.map((o) => o.value).filter(Boolean));
    assert.ok(names.length >= 20, `the Scene menu lists ${names.length} presets`);
    for (const heavy of HEAVY) assert.ok(names.includes(heavy), `the Scene menu lists ${heavy}`);
    const problems = [];
    const rows = [];
    for (const name of names) {
      const started = Date.now();
      await page.selectOption('#preset', name);
      const steps = HEAVY.has(name) ? HEAVY_STEPS : STEPS;
      const read = await runAndRead(page, steps);
      assert.equal(read.scene.name, name, `the menu loaded ${name}`);
      assert.equal(read.step, steps);
      const counted = recount(read.scene, read.goals, read.before, read.after);
      problems.push(...disagreements(name, counted, read.metrics));
      rows.push(
        `${name.padEnd(26)} step ${steps}: ${counted.inside}/${counted.agents} inside (metrics ${Math.round(read.metrics.arrived_share * read.metrics.agents)}), ` +
          `waiting ${read.metrics.waiting_agents} (≤ ${counted.restingOutsideByGroup.reduce((s, v) => s + v, 0)} at rest outside), ` +
          `${counted.atRest} at rest, ${counted.overlappingAtRest} overlapping pairs at rest, digest ${read.digest}, ${Date.now() - started} ms`,
      );
    }
    console.log(rows.join('\n'));
    assert.deepEqual(problems, []);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
