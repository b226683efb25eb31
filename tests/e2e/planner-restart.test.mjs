// A planner picked in the panel after the agents have arrived restarts the run from the seed, as
// any other group edit does, so its effect shows at once (before, the arrived agents stood still
// until Reset); the page says so beside the picker, and Undo brings the old planner back.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPage, simpleScene } from './helpers.mjs';

test('changing the planner after arrival restarts the run with the new planner', async () => {
  const { page, errors, close } = await openPage();
  try {
    const start = await page.evaluate(async (scene) => {
      await window.flockpath.pause();
      await window.flockpath.load(scene);
      await window.flockpath.reset();
      return window.flockpath.positions();
    }, simpleScene());
    const arrived = await page.evaluate(async () => {
      await window.flockpath.step(1500);
      return window.flockpath.metrics();
    });
    assert.ok(arrived.arrived_share > 0.9, `the flock arrived first (${arrived.arrived_share})`);

    assert.match(await page.textContent('.planner-note'), /new planner restarts the run/);
    await page.selectOption('#planner', 'pso');
    // The planner change goes to the simulation worker: read once it has answered.
    const after = await page.evaluate(async () => {
      await window.flockpath.settled();
      return {
        kind: window.flockpath.scene().groups[0].planner.kind,
        metrics: window.flockpath.metrics(),
        positions: await window.flockpath.positions(),
        timeline: window.flockpath.timeline(),
      };
    });
    assert.equal(after.kind, 'pso');
    assert.equal(after.metrics.steps, 0, 'the run starts again at step 0');
    assert.equal(after.metrics.arrived_share, 0, 'nobody has arrived yet');
    assert.deepEqual(after.positions, start, 'the agents are back at their seeded spawn positions');
    assert.equal(after.timeline.end_step, 0, 'the timeline starts again');

    // The new planner moves them: after a few steps they have left the spawn region.
    const moved = await page.evaluate(async () => {
      await window.flockpath.step(120);
      return window.flockpath.positions();
    });
    const mean = moved.reduce((sum, p, i) => sum + Math.hypot(p[0] - start[i][0], p[1] - start[i][1]), 0) / moved.length;
    assert.ok(mean > 20, `the PSO crowd moves off the spawn (${mean.toFixed(1)} px on average)`);

    // Same run as a fresh PSO start from the same seed.
    const fresh = await page.evaluate(async () => {
      await window.flockpath.reset();
      await window.flockpath.step(120);
      return window.flockpath.positions();
    });
    assert.deepEqual(fresh, moved, 'the restarted run is the seeded run of the new planner');

    await page.click('#undo');
    assert.equal(await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene().groups[0].planner.kind)), 'boids', 'Undo brings Boids back');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
