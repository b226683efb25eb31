// Editable IGSA paths in the playground: dragging a waypoint handle moves the group's path (the
// scene, hence the link, carries the edit), a path dragged through an obstacle is flagged red
// with a warning, and undo brings the old path back.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, bannerText, frames, openPage, pixelsAt, sceneToCanvasPixel, sceneToClient, screenshot, snapshotCanvas } from './helpers.mjs';

/** igsa-path-2 with two edited waypoints above the wall. */
async function editedScene(page) {
  return page.evaluate(async () => {
    const module = await import('./pkg/flockpath.js');
    const scene = JSON.parse(module.preset_scene_json('igsa-path-2'));
    scene.groups[0].planner.params.waypoints = [[300, 100], [500, 100]];
    return JSON.stringify(scene);
  });
}

test('dragging a waypoint edits the path; through a wall it turns red and warns; undo restores', async () => {
  const { page, errors, close } = await openPage();
  try {
    await page.evaluate((scene) => window.flockpath.load(scene), await editedScene(page));
    await page.evaluate(() => window.flockpath.pause());
    await frames(page, 3);
    const from = await sceneToClient(page, 300, 100);
    const to = await sceneToClient(page, 400, 430);
    await page.mouse.move(from.x, from.y);
    await page.mouse.down();
    await page.mouse.move((from.x + to.x) / 2, (from.y + to.y) / 2, { steps: 4 });
    await page.mouse.move(to.x, to.y, { steps: 4 });
    await page.mouse.up();
    await frames(page, 3);

    const waypoints = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene().groups[0].planner.params.waypoints));
    assert.equal(waypoints.length, 2);
    assert.ok(Math.abs(waypoints[0][0] - 400) < 2 && Math.abs(waypoints[0][1] - 430) < 2, JSON.stringify(waypoints));
    assert.deepEqual(waypoints[1], [500, 100], 'the other waypoint stays');
    assert.match(await bannerText(page), /crosses an obstacle/);
    // The segment from the start (70, 420) to the dragged point crosses the wall (x 380…425): red.
    await snapshotCanvas(page, 'edited');
    const [x, y] = [300, 420 + ((waypoints[0][1] - 420) * (300 - 70)) / (waypoints[0][0] - 70)];
    const centre = await sceneToCanvasPixel(page, x, y);
    const column = [-2, -1, 0, 1, 2].map((d) => ({ x: centre.x, y: centre.y + d }));
    const colours = await pixelsAt(page, 'edited', column);
    assert.ok(colours.some((c) => c[0] > 180 && c[1] < 90 && c[2] < 90), `crossing segment colours ${JSON.stringify(colours)}`);
    await screenshot(page, 'path-edit-crossing');

    // The link carries the edit.
    const link = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.sceneString()));
    const back = await page.evaluate(async (s) => {
      const module = await import('./pkg/flockpath.js');
      return JSON.parse(module.scene_from_text(s)).groups[0].planner.params.waypoints;
    }, link);
    assert.deepEqual(back, waypoints);

    await page.keyboard.press('Control+z');
    const undone = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene().groups[0].planner.params.waypoints));
    assert.deepEqual(undone, [[300, 100], [500, 100]]);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
