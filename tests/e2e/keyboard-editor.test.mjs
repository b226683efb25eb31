// The playground with the keyboard only (issue #15 item 1): Tab reaches the editor canvas, which
// shows a cursor; arrows move it (Shift: further), Enter places with the current tool (circle,
// rectangle, goal, group), Escape cancels a shape in progress; Space plays and pauses on the
// canvas; the live description beside the canvas then names the obstacles, the goal, the groups
// and the run's step and arrivals as the page API reports them. With the select tool Enter picks
// an item up, arrows carry it, Enter puts it down, Delete removes it. The page API only sets the
// scene up and reads the results: every input is a key press.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, loadPaused, openPage, screenshot, settled, simpleScene } from './helpers.mjs';

const scene = (page) => page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene()));
// Read once the simulation worker has answered the keys before (a pick, an edit).
const cursorText = async (page) => {
  await settled(page);
  return page.textContent('#canvas-cursor');
};

/** The cursor position the live region announces ("Cursor at 400, 250. …"). */
async function cursorAt(page) {
  const text = await cursorText(page);
  const m = /Cursor at (\d+), (\d+)\./.exec(text);
  assert.ok(m, `the cursor region says where it is: ${text}`);
  return [Number(m[1]), Number(m[2])];
}

async function press(page, key, times = 1) {
  for (let i = 0; i < times; i += 1) await page.keyboard.press(key);
}

test('keyboard only: draw obstacles, place a goal, add a group, play, read the description', async () => {
  const { page, errors, close } = await openPage();
  try {
    // Setup through the API: an empty field with one group and no goal.
    await loadPaused(page, simpleScene({ goals: [], groups: [{ ...simpleScene().groups[0], goal: null }] }));
    await page.evaluate(() => document.activeElement?.blur());

    // Tab through the page to the editor canvas (the tool buttons are one tab stop).
    let tabs = 0;
    let toolStops = 0;
    while ((await page.evaluate(() => document.activeElement?.id)) !== 'overlay-canvas') {
      await page.keyboard.press('Tab');
      if (await page.evaluate(() => document.activeElement?.matches('button[data-tool]'))) toolStops += 1;
      tabs += 1;
      assert.ok(tabs < 60, 'Tab reaches the editor canvas');
    }
    assert.equal(toolStops, 1, 'the tool radio group is one tab stop');
    const start = await cursorAt(page);
    assert.match(await page.textContent('#hint'), /arrows move the cursor/, 'the hint tells the keys');

    // Circle: Enter sets the centre, three steps right set the radius, Enter draws it.
    await press(page, '2');
    assert.equal(await page.getAttribute('[data-tool="circle"]', 'aria-checked'), 'true', '2 picks the circle on the canvas');
    await press(page, 'Shift+ArrowLeft', 2);
    const centre = await cursorAt(page);
    assert.ok(centre[0] < start[0] && centre[1] === start[1], `Shift+← moves left: ${start} → ${centre}`);
    await press(page, 'Enter');
    await press(page, 'ArrowRight', 3);
    const edge = await cursorAt(page);
    assert.match(await cursorText(page), /Radius \d+/, 'the radius is announced while drawing');
    await press(page, 'Enter');
    let s = await scene(page);
    assert.equal(s.obstacles.length, 1, 'Enter drew a circle');
    assert.equal(s.obstacles[0].shape, 'circle');
    assert.deepEqual(s.obstacles[0].center, centre, 'at the cursor');
    assert.equal(s.obstacles[0].radius, edge[0] - centre[0]);
    assert.match(await cursorText(page), /Circle obstacle added/);

    // Rectangle: Enter, Escape cancels; then Enter, down-right, Enter draws one.
    await press(page, '3');
    await press(page, 'ArrowUp', 8);
    await press(page, 'Enter');
    await press(page, 'ArrowRight', 2);
    await press(page, 'Escape');
    assert.match(await cursorText(page), /Cancelled/);
    assert.equal((await scene(page)).obstacles.length, 1, 'Escape cancelled the rectangle');
    const corner = await cursorAt(page);
    await press(page, 'Enter');
    await press(page, 'Shift+ArrowRight');
    await press(page, 'ArrowDown', 3);
    const opposite = await cursorAt(page);
    await press(page, 'Enter');
    s = await scene(page);
    assert.equal(s.obstacles.length, 2, 'Enter drew a rectangle');
    assert.deepEqual([s.obstacles[1].shape, s.obstacles[1].min, s.obstacles[1].max], ['rect', corner, opposite]);

    // Goal: one Enter; the group heads for it.
    await press(page, '5');
    await press(page, 'Shift+ArrowRight', 4);
    const goalAt = await cursorAt(page);
    await press(page, 'Enter');
    s = await scene(page);
    assert.equal(s.goals.length, 1, 'Enter placed a goal');
    assert.deepEqual(s.goals[0].position, goalAt);
    assert.equal(s.groups[0].goal, 0, 'the active group heads for it');

    // Group: Enter for one corner of the spawn area, Enter for the other.
    await press(page, '6');
    await press(page, 'Shift+ArrowDown', 3);
    await press(page, 'Enter');
    await press(page, 'Shift+ArrowRight', 2);
    await press(page, 'Shift+ArrowDown');
    await press(page, 'Enter');
    s = await scene(page);
    assert.equal(s.groups.length, 2, `Enter added a group: ${await cursorText(page)} / ${await page.textContent('#banner-text')}`);
    assert.equal(s.groups[1].goal, 0, 'the new group takes the active group’s goal');
    assert.equal(await page.evaluate(() => document.activeElement?.id), 'overlay-canvas', 'focus stayed on the canvas');
    await screenshot(page, 'keyboard-editor');

    // Undo by keyboard too, then redo: the same scene.
    await press(page, 'Control+z');
    assert.equal((await scene(page)).groups.length, 1, 'Ctrl+Z undid the group');
    await press(page, 'Control+Shift+z');
    assert.equal((await scene(page)).groups.length, 2);

    // Space plays on the canvas; run a while; Space pauses.
    await press(page, 'Space');
    assert.equal(await page.evaluate(() => window.flockpath.isPlaying()), true, 'Space on the canvas plays');
    await page.waitForFunction(() => window.flockpath.metrics().steps >= 30);
    await press(page, 'Space');
    assert.equal(await page.evaluate(() => window.flockpath.isPlaying()), false, 'Space pauses');

    // The live description: visually hidden, polite, and in step with the page API.
    const region = await page.evaluate(() => {
      const el = document.getElementById('scene-description');
      const box = el.getBoundingClientRect();
      return { live: el.getAttribute('aria-live'), width: box.width, height: box.height };
    });
    assert.equal(region.live, 'polite');
    assert.ok(region.width <= 1 && region.height <= 1, `visually hidden: ${JSON.stringify(region)}`);
    const metrics = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.metrics()));
    const step = metrics.steps.toLocaleString('en-US');
    await page.waitForFunction((want) => document.getElementById('scene-description').textContent.includes(want), `Step ${step}, paused.`);
    const text = await page.textContent('#scene-description');
    assert.match(text, /2 obstacles: 1 circle, 1 rectangle\./, text);
    assert.match(text, /1 goal\./, text);
    assert.match(text, /2 groups: “flock”, 30 agents, planner Boids[^,;]*, heading for goal 1; “group 2”, 30 agents, planner Boids[^,;]*, heading for goal 1\./, text);
    const share = `${Math.round(metrics.arrived_share * 100)}%`;
    assert.ok(text.includes(`${share} of 60 agents arrived.`), `arrivals as the metrics say (${share}): ${text}`);
    assert.ok(text.includes(`${metrics.collisions_agent_agent.toLocaleString('en-US')} in all`), text);
    assert.match(text, metrics.stuck_agents === 0 ? /No agent stuck\./ : /agents? stuck\./, text);
    // The canvases are in the accessibility tree with a role and a name.
    assert.equal(await page.getByRole('img', { name: 'Simulated crowd' }).count(), 1);
    assert.equal(await page.getByRole('application', { name: /Scene editor/ }).count(), 1);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('keyboard only: a polygon point by point, and selecting what is under the cursor', async () => {
  const { page, errors, close } = await openPage();
  try {
    await loadPaused(page, simpleScene());
    await page.focus('#overlay-canvas');
    await press(page, 'ArrowLeft'); // The first arrow shows the cursor (focus came from a script).
    await press(page, '4');
    const points = [];
    for (const key of ['Shift+ArrowUp', 'Shift+ArrowRight', 'Shift+ArrowDown']) {
      await press(page, key);
      points.push(await cursorAt(page));
      await press(page, 'Enter');
    }
    assert.match(await cursorText(page), /3 points/);
    await press(page, 'Enter'); // Enter again on the last point closes the polygon.
    let s = await scene(page);
    assert.equal(s.obstacles.length, 1, 'a polygon was added');
    assert.deepEqual(s.obstacles[0].points, points);

    // Select tool: Enter on the goal selects it; Delete removes it.
    await press(page, '1');
    const [gx, gy] = s.goals[0].position;
    const [cx, cy] = await cursorAt(page);
    const step = 10; // min(800, 500) / 50 scene px per arrow press
    await press(page, gx > cx ? 'ArrowRight' : 'ArrowLeft', Math.round(Math.abs(gx - cx) / step));
    await press(page, gy > cy ? 'ArrowDown' : 'ArrowUp', Math.round(Math.abs(gy - cy) / step));
    await press(page, 'Enter');
    assert.match(await cursorText(page), /Selected goal 1/);
    // The first Enter also picked it up: arrows carry it, Enter puts it down.
    await press(page, 'ArrowLeft', 3);
    assert.match(await cursorText(page), /Moved by -30, 0/);
    await press(page, 'Enter');
    s = await scene(page);
    assert.deepEqual(s.goals[0].position, [gx - 30, gy], 'Enter moved the goal by the cursor’s way');
    // Picked up again, Escape leaves it; Delete removes the selection.
    await press(page, 'Enter');
    await press(page, 'ArrowUp');
    await press(page, 'Escape');
    assert.deepEqual((await scene(page)).goals[0].position, [gx - 30, gy], 'Escape left it in place');
    await press(page, 'Delete');
    s = await scene(page);
    assert.equal(s.goals.length, 0, 'Delete removed the selected goal');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
