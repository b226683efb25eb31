// Draw a circle obstacle and a goal with real mouse events, run, and check through the page API
// that the crowd heads for the new goal without entering the obstacle, leaving trails behind.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  assertNoUnexpectedErrors,
  frames,
  loadPaused,
  openPage,
  pixelsAt,
  sceneToCanvasPixel,
  snapshotCanvas,
  sceneToClient,
  screenshot,
  simpleScene,
} from './helpers.mjs';

const OBSTACLE = { center: [300, 330], radius: 45 };
const NEW_GOAL = [480, 420];

/** Mean distance of the agents to a point, computed here in the test from the page's positions. */
function meanDistance(positions, [gx, gy]) {
  assert.ok(positions.length > 0, 'there are agents');
  return positions.reduce((sum, [x, y]) => sum + Math.hypot(x - gx, y - gy), 0) / positions.length;
}

test('draw a circle obstacle and a goal, then the crowd walks to the new goal around it', async () => {
  const { page, errors, close } = await openPage();
  try {
    await loadPaused(page, simpleScene());
    await frames(page);
    const start = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene()));
    assert.equal(start.obstacles.length, 0);
    assert.equal(start.goals.length, 1);

    // Circle tool: drag from the centre to the radius with the mouse.
    await page.click('[data-tool="circle"]');
    const centre = await sceneToClient(page, ...OBSTACLE.center);
    const rim = await sceneToClient(page, OBSTACLE.center[0] + OBSTACLE.radius, OBSTACLE.center[1]);
    await page.mouse.move(centre.x, centre.y);
    await page.mouse.down();
    await page.mouse.move((centre.x + rim.x) / 2, rim.y, { steps: 4 });
    await page.mouse.move(rim.x, rim.y, { steps: 4 });
    await page.mouse.up();

    // Goal tool: one click; it becomes the active (only) group's goal.
    await page.click('[data-tool="goal"]');
    const goal = await sceneToClient(page, ...NEW_GOAL);
    await page.mouse.click(goal.x, goal.y);

    const edited = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene()));
    assert.equal(edited.obstacles.length, 1, 'the drawn obstacle is in the scene');
    const circle = edited.obstacles[0];
    assert.equal(circle.shape, 'circle');
    const pixel = 1 / (await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.view().scale)));
    assert.ok(Math.abs(circle.center[0] - OBSTACLE.center[0]) <= 2 * pixel, `centre x ${circle.center[0]}`);
    assert.ok(Math.abs(circle.center[1] - OBSTACLE.center[1]) <= 2 * pixel, `centre y ${circle.center[1]}`);
    assert.ok(Math.abs(circle.radius - OBSTACLE.radius) <= 2 * pixel, `radius ${circle.radius}`);
    assert.equal(edited.goals.length, 2, 'the clicked goal is in the scene');
    const placed = edited.goals[1].position;
    assert.ok(Math.hypot(placed[0] - NEW_GOAL[0], placed[1] - NEW_GOAL[1]) <= 2 * pixel, `goal at ${placed}`);
    assert.equal(edited.groups[0].goal, 1, 'the group now heads for the new goal');

    // Run: step in chunks with a painted frame between them, so the trail layer gets segments.
    await frames(page);
    await snapshotCanvas(page, 'before');
    const startDistance = meanDistance(await page.evaluate(() => window.flockpath.positions()), placed);
    let midway = null;
    for (let chunk = 0; chunk < 25; chunk += 1) {
      const steps = await page.evaluate(() => window.flockpath.step(20));
      assert.equal(steps, 20 * (chunk + 1), 'step(n) returns the step count');
      // Trails fade with the steps (by the scene's fade every two steps): positions 180 steps
      // before the end still show; at step 140 (chunk 6) they had faded to ~16 % by step 500.
      if (chunk === 15) midway = await page.evaluate(() => window.flockpath.positions());
      await frames(page);
    }
    const metrics = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.metrics()));
    const endDistance = meanDistance(await page.evaluate(() => window.flockpath.positions()), placed);
    assert.ok(endDistance < startDistance * 0.6, `mean distance to the new goal ${startDistance} → ${endDistance}`);
    assert.equal(metrics.steps, 500);
    assert.equal(metrics.penetrations_agent_obstacle, 0, 'no agent entered an obstacle');
    assert.ok(metrics.mean_path_length > 50, `agents moved (${metrics.mean_path_length} px)`);

    // Trails: where the agents were midway, the canvas differs from the picture before the run.
    await snapshotCanvas(page, 'after');
    const points = [];
    for (const [x, y] of midway) points.push(await sceneToCanvasPixel(page, x, y));
    const before = await pixelsAt(page, 'before', points);
    const after = await pixelsAt(page, 'after', points);
    let changed = 0;
    for (let k = 0; k < points.length; k += 1) {
      if (!before[k] || !after[k]) continue;
      const diff = after[k].reduce((sum, channel, c) => sum + Math.abs(channel - before[k][c]), 0);
      if (diff > 12) changed += 1;
    }
    assert.ok(changed >= midway.length * 0.5, `${changed} of ${midway.length} midway points show a trail`);

    await screenshot(page, 'draw-obstacle-and-goal');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
