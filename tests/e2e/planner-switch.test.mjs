// Switching a group's planner in the UI changes the motion: the same scene and seed, stepped the
// same number of steps through the page API, ends elsewhere with PSO than with Boids (and the
// Boids run itself replays exactly, so the difference is the planner's).

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPage, simpleScene } from './helpers.mjs';

const STEPS = 150;

async function runFromStart(page) {
  return page.evaluate(async (n) => {
    await window.flockpath.reset();
    await window.flockpath.step(n);
    return window.flockpath.positions();
  }, STEPS);
}

const meanDistance = (a, b) =>
  a.reduce((sum, p, i) => sum + Math.hypot(p[0] - b[i][0], p[1] - b[i][1]), 0) / a.length;

test('switching the planner in the panel changes where the agents go', async () => {
  const { page, errors, close } = await openPage();
  try {
    await page.evaluate(async (scene) => {
      await window.flockpath.pause();
      await window.flockpath.load(scene);
    }, simpleScene());
    const boids = await runFromStart(page);
    const again = await runFromStart(page);
    assert.deepEqual(again, boids, 'the same planner replays the same run');

    await page.selectOption('#planner', 'pso');
    assert.equal(await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene().groups[0].planner.kind)), 'pso');
    const pso = await runFromStart(page);
    assert.equal(pso.length, boids.length);
    const moved = meanDistance(boids, pso);
    assert.ok(moved > 5, `agents end on average ${moved.toFixed(2)} px apart`);

    await page.selectOption('#planner', 'firefly');
    const firefly = await runFromStart(page);
    assert.ok(meanDistance(firefly, pso) > 5 && meanDistance(firefly, boids) > 5, 'firefly differs from both');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
