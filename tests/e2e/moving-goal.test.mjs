// A moving goal is drawn where it is at the step shown (issue 23 §2). Regression: the renderer
// drew a goal at its scene `position` (where a moving goal starts), so in `pso-circle-target` the
// crowd chased an empty spot while the ring stayed at the start, 250 px away at step 600. In
// Chromium: after `step(600)` and after a timeline `seek(300)`, `flockpath.goals()` agrees with
// the scene's circular motion (computed here only as a cross-check), and the canvas shows the
// ring round that position and none round the start.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, frames, openPage, pixelsAt, sceneToCanvasPixel, snapshotCanvas } from './helpers.mjs';

const hex = (c) => [1, 3, 5].map((i) => parseInt(c.slice(i, i + 2), 16));
const distance = (a, b) => Math.hypot(...a.map((v, i) => v - b[i]));

/** Where a goal with a circle motion is at `step` (the scene format's definition). */
function onCircle(goal, step) {
  const { center, radius, period_steps: period } = goal.motion;
  const phase = Math.atan2(goal.position[1] - center[1], goal.position[0] - center[0]);
  const angle = phase + ((step / period) % 1) * 2 * Math.PI;
  return [center[0] + radius * Math.cos(angle), center[1] + radius * Math.sin(angle)];
}

/**
 * Share of 48 points on the circle of `radius` scene px round `centre` where snapshot `name`
 * shows `ink`: a pixel of the point's 3×3 neighbourhood nearer to `ink` than a third of the
 * way to the field's colour.
 */
async function ringShare(page, name, centre, radius, ink, field) {
  const points = [];
  for (let k = 0; k < 48; k += 1) {
    const a = (k / 48) * 2 * Math.PI;
    const c = await sceneToCanvasPixel(page, centre[0] + radius * Math.cos(a), centre[1] + radius * Math.sin(a));
    for (let dy = -1; dy <= 1; dy += 1) for (let dx = -1; dx <= 1; dx += 1) points.push({ x: c.x + dx, y: c.y + dy });
  }
  const colours = await pixelsAt(page, name, points);
  const near = distance(ink, field) / 3;
  let inked = 0;
  for (let k = 0; k < 48; k += 1) {
    if (colours.slice(k * 9, k * 9 + 9).some((p) => p && distance(p, ink) < near)) inked += 1;
  }
  return inked / 48;
}

test('pso-circle-target: the goal ring is drawn where the goal is after step(600) and after seek(300)', async () => {
  const { page, errors, close } = await openPage({ hash: '' });
  try {
    await page.selectOption('#preset', 'pso-circle-target');
    await page.evaluate(async () => {
      await window.flockpath.pause();
      await window.flockpath.reset();
    });
    const scene = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene()));
    assert.equal(scene.name, 'pso-circle-target');
    const goal = scene.goals[0];
    assert.equal(goal.motion?.kind, 'circle', 'the preset’s goal moves on a circle');
    const ink = hex(scene.groups[0].color);
    // Trails off: the ring is what is measured, and the crowd's trails (in its colour, drawn
    // legibly since issue 27) cross the spot where the goal started.
    await page.uncheck('#trails');
    await frames(page, 2);
    await snapshotCanvas(page, 'field');
    const [field] = await pixelsAt(page, 'field', [await sceneToCanvasPixel(page, 3, 3)]);

    for (const [how, act, step] of [
      ['step(600)', () => window.flockpath.step(600), 600],
      ['seek(300)', () => window.flockpath.seek(300), 300],
    ]) {
      assert.equal(await page.evaluate(act), step, how);
      await frames(page, 3);
      const [shown] = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.goals()));
      const expected = onCircle(goal, step);
      assert.ok(distance([shown.x, shown.y], expected) < 0.01, `${how}: goals() says (${shown.x}, ${shown.y}), the motion (${expected})`);
      assert.equal(shown.radius, goal.radius);
      const moved = distance(expected, goal.position);
      await snapshotCanvas(page, how);
      const now = await ringShare(page, how, expected, goal.radius, ink, field);
      const start = await ringShare(page, how, goal.position, goal.radius, ink, field);
      console.log(`${how}: goal ${moved.toFixed(1)} px from its start; ring inked ${now.toFixed(2)} round it, ${start.toFixed(2)} round the start`);
      assert.ok(moved > 100, `${how}: the goal moved ${moved} px, too little to tell`);
      assert.ok(now >= 0.9, `${how}: only ${now} of the ring round the goal is drawn`);
      assert.ok(start <= 0.15, `${how}: ${start} of a ring is drawn where the goal started`);
    }
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
