// The other editor tools with real mouse events: polygon (close by clicking the first point, by
// double-click; Escape cancels), group (drag a spawn region; edit it in the group panel), moving
// an item with the select tool, and the preset picker with its description.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, loadPaused, openPage, sceneToClient, screenshot, simpleScene } from './helpers.mjs';

const scene = (page) => page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene()));

async function clickAt(page, x, y, options) {
  const p = await sceneToClient(page, x, y);
  await page.mouse.click(p.x, p.y, options);
}

async function dragFrom(page, [x0, y0], [x1, y1]) {
  const a = await sceneToClient(page, x0, y0);
  const b = await sceneToClient(page, x1, y1);
  await page.mouse.move(a.x, a.y);
  await page.mouse.down();
  await page.mouse.move(b.x, b.y, { steps: 6 });
  await page.mouse.up();
}

test('polygon, group and move tools edit the scene through the page', async () => {
  const { page, errors, close } = await openPage();
  try {
    await loadPaused(page, simpleScene());
    const pixel = 1 / (await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.view().scale)));
    const near = (a, b) => Math.abs(a - b) <= 2 * pixel;

    // Polygon closed by clicking its first point.
    await page.keyboard.press('4');
    for (const [x, y] of [[300, 60], [400, 60], [350, 140]]) await clickAt(page, x, y);
    await clickAt(page, 300, 60);
    let s = await scene(page);
    assert.equal(s.obstacles.length, 1);
    assert.equal(s.obstacles[0].shape, 'polygon');
    assert.equal(s.obstacles[0].points.length, 3);
    assert.ok(near(s.obstacles[0].points[1][0], 400) && near(s.obstacles[0].points[1][1], 60));

    // Escape drops a polygon in progress.
    await clickAt(page, 500, 380);
    await clickAt(page, 560, 380);
    await page.keyboard.press('Escape');
    await clickAt(page, 530, 460);
    await page.keyboard.press('Escape');
    assert.equal((await scene(page)).obstacles.length, 1, 'Escape cancelled the polygon');

    // Polygon closed by a double-click on its last point.
    await clickAt(page, 500, 380);
    await clickAt(page, 580, 380);
    await clickAt(page, 560, 460, { clickCount: 2 });
    s = await scene(page);
    assert.equal(s.obstacles.length, 2, 'double-click closes');
    assert.equal(s.obstacles[1].points.length, 3, 'the double-click added no duplicate point');

    // Group tool: a new group with the next palette colour and the active group's goal.
    await page.keyboard.press('6');
    await dragFrom(page, [40, 400], [120, 470]);
    s = await scene(page);
    assert.equal(s.groups.length, 2);
    const added = s.groups[1];
    assert.equal(added.goal, s.groups[0].goal);
    assert.notEqual(added.color.toLowerCase(), s.groups[0].color.toLowerCase(), 'a different colour');
    assert.ok(near(added.spawn.min[0], 40) && near(added.spawn.max[1], 470), JSON.stringify(added.spawn));
    assert.equal(await page.$eval('#group-editor input[name="count"]', (el) => el.value), String(added.count),
      'the group panel shows the new group');

    // Edit the new group's count in the panel.
    await page.fill('#group-editor input[name="count"]', '12');
    await page.press('#group-editor input[name="count"]', 'Enter');
    await page.keyboard.press('Tab');
    s = await scene(page);
    assert.equal(s.groups[1].count, 12);
    assert.equal((await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.metrics()))).agents, 30 + 12);

    // The planner picker lists the planners from the Rust table.
    const planners = await page.$$eval('#planner option', (os) => os.map((o) => o.value));
    assert.ok(planners.includes('boids'), planners.join(','));

    // Select tool: drag the first polygon by (+40, +100). (Keys are shortcuts only while the page
    // or the canvas has focus, not the group panel's field.)
    await page.evaluate(() => document.activeElement?.blur());
    await page.keyboard.press('1');
    const before = s.obstacles[0].points;
    await dragFrom(page, [350, 90], [390, 190]);
    s = await scene(page);
    s.obstacles[0].points.forEach(([x, y], i) => {
      assert.ok(near(x, before[i][0] + 40) && near(y, before[i][1] + 100), `point ${i}: ${x},${y}`);
    });
    await screenshot(page, 'editor-tools');

    // Preset picker: loading one shows its description.
    const second = await page.$eval('#preset', (el) => el.options[1].value);
    await page.selectOption('#preset', second);
    assert.equal((await scene(page)).name, second);
    const description = await page.textContent('#preset-description');
    assert.ok(description.length > 10, `description: ${description}`);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('a crash replaces the canvas with a loud panel and a reload button', async () => {
  const { page, errors, close } = await openPage();
  try {
    // What a Rust panic surfaces as: a RuntimeError escaping to the window.
    await page.evaluate(() => {
      setTimeout(() => {
        throw new WebAssembly.RuntimeError('unreachable executed');
      });
    });
    await page.waitForSelector('.panic', { timeout: 10_000 });
    assert.match(await page.textContent('.panic'), /crashed[\s\S]*unreachable executed/);
    assert.ok(await page.isVisible('.panic button'), 'a reload button');
    assert.equal(await page.isVisible('#scene-canvas'), false, 'the canvas is replaced');
    assert.equal(await page.evaluate(() => window.flockpath.isPlaying()), false, 'the loop stopped');
    assert.equal(await page.textContent('#play'), 'Play');
    await screenshot(page, 'crash-panel');
    assertNoUnexpectedErrors(errors, [/unreachable executed/]);
  } finally {
    await close();
  }
});

// Issue #27 §1: New scene — an empty world of a chosen size from the Scene menu's "New…" button;
// a size the core refuses is said beside the field and the running scene stays; the new scene is
// one undo step.
test('New… makes an empty world of the chosen size; a refused size keeps the scene', async () => {
  const { page, errors, close } = await openPage();
  try {
    await page.evaluate(async (s) => {
      await window.flockpath.pause();
      await window.flockpath.load(s);
    }, simpleScene());
    const before = await page.evaluate(() => window.flockpath.sceneString());
    await page.click('#new-scene');
    assert.equal(await page.evaluate(() => document.getElementById('new-scene-dialog').open), true);
    assert.equal(await page.inputValue('#new-scene-width'), '800', 'the current size to start from');
    await page.fill('#new-scene-width', '5');
    await page.click('#new-scene-create');
    await page.waitForSelector('#new-scene-refused');
    assert.match(await page.textContent('#new-scene-refused'), /^width is 5; allowed: a number in 10…20000 px$/);
    assert.equal(await page.getAttribute('#new-scene-width', 'aria-invalid'), 'true');
    assert.equal(await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.sceneString())), before, 'the scene stays');

    await page.fill('#new-scene-width', '1200');
    await page.fill('#new-scene-height', '600');
    await page.click('#new-scene-create');
    await page.waitForFunction(() => !document.getElementById('new-scene-dialog').open);
    const made = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene()));
    assert.deepEqual([made.width, made.height, made.obstacles.length, made.goals.length, made.groups.length], [1200, 600, 0, 0, 0]);
    assert.equal(made.seed, 7, 'the seed carries over');
    assert.equal(await page.isHidden('#banner'), true, 'the earlier refusal is gone');
    await page.click('#undo');
    assert.equal(await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.sceneString())), before, 'one undo step back');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
