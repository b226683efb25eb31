// The path tool (Boids path following): clicking points and pressing Enter adds a path that the
// active Boids group follows; the group panel offers it in its "Follow path" choice, and deleting
// it with the select tool unlinks the group.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, loadPaused, openPage, sceneToClient, simpleScene } from './helpers.mjs';

const scene = (page) => page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene()));

async function clickAt(page, x, y, options) {
  const p = await sceneToClient(page, x, y);
  await page.mouse.click(p.x, p.y, options);
}

test('a drawn path is followed by the active group and can be deleted', async () => {
  const { page, errors, close } = await openPage();
  try {
    await loadPaused(page, simpleScene());
    await page.keyboard.press('7');
    for (const [x, y] of [[150, 250], [400, 120], [650, 250]]) await clickAt(page, x, y);
    await page.keyboard.press('Enter');
    let s = await scene(page);
    assert.equal(s.paths?.length, 1, 'one path added');
    assert.equal(s.paths[0].points.length, 3);
    assert.equal(s.groups[0].planner.params.path, 1, 'the active Boids group follows path 1');
    assert.equal(await page.locator('#param-path').inputValue(), '1', 'the panel shows the followed path');

    // Agents now walk the arc: halfway along it they are well above the straight line (y = 250)
    // to the goal.
    await page.evaluate(() => window.flockpath.step(200));
    const ys = await page.evaluate(async () => (await window.flockpath.positions()).map(([, y]) => y));
    const meanY = ys.reduce((a, b) => a + b, 0) / ys.length;
    assert.ok(meanY < 215, `mean y ${meanY.toFixed(1)} px: the flock does not follow the arc`);

    // Select the path by clicking its centre line and delete it: the group stops following. First
    // let the flock reach the goal, so no agent on the arc takes the click (agents pick first).
    await page.evaluate(async () => {
      await window.flockpath.pause();
      await window.flockpath.step(1500);
    });
    // Keys go to the editor only when no form field has focus (the group panel re-renders).
    await page.evaluate(() => document.activeElement?.blur());
    await page.keyboard.press('1');
    await clickAt(page, 275, 185);
    await page.evaluate(() => document.activeElement?.blur());
    await page.keyboard.press('Delete');
    s = await scene(page);
    assert.equal(s.paths?.length ?? 0, 0, 'path deleted');
    assert.equal(s.groups[0].planner.params.path, 0, 'the group follows no path');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('a group given a drawn path short of a new goal walks on into the goal', async () => {
  // The goal tool makes a 20 px goal the active group's; the path tool's path ends 150 px
  // before it. Before, the group circled the path's end for ever (none inside the goal).
  const { page, errors, close } = await openPage();
  try {
    const base = simpleScene();
    await loadPaused(page, simpleScene({ groups: [{ ...base.groups[0], count: 10 }] }));
    await page.keyboard.press('5');
    await clickAt(page, 650, 120);
    await page.keyboard.press('7');
    for (const [x, y] of [[150, 250], [300, 150], [500, 120]]) await clickAt(page, x, y);
    await page.keyboard.press('Enter');
    const s = await scene(page);
    assert.equal(s.goals.length, 2, 'a goal added');
    assert.equal(s.groups[0].goal, 1, 'the new goal is the group\'s');
    assert.equal(s.groups[0].planner.params.path, 1, 'the group follows the drawn path');
    const end = s.paths[0].points.at(-1);
    const goal = s.goals[1];
    const gap = Math.hypot(goal.position[0] - end[0], goal.position[1] - end[1]);
    assert.ok(gap >= 140, `the path ends ${gap.toFixed(0)} px from the goal`);

    await page.evaluate(() => window.flockpath.step(2000));
    const positions = await page.evaluate(() => window.flockpath.positions());
    const inside = positions.filter(([x, y]) => Math.hypot(x - goal.position[0], y - goal.position[1]) <= goal.radius);
    const metrics = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.metrics()));
    assert.ok(inside.length >= 9, `${inside.length} of 10 centres inside the new goal at step 2000`);
    assert.ok(metrics.arrived_share >= 0.9, `arrived_share ${metrics.arrived_share}`);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
