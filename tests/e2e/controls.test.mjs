// Playback buttons and keys, undo/redo of an edit, a live parameter slider, HiDPI backing store
// and viewport resizing, all observed through the page API and the DOM.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, frames, loadPaused, openPage, sceneToClient, screenshot, simpleScene } from './helpers.mjs';

// Read once the simulation worker has answered the clicks and keys before (settled()).
const steps = (page) =>
  page.evaluate(async () => {
    await window.flockpath.settled();
    return window.flockpath.metrics().steps;
  });
const sceneNow = (page) =>
  page.evaluate(async () => {
    await window.flockpath.settled();
    return window.flockpath.scene();
  });

test('play, pause, step and reset by button and by key', async () => {
  const { page, errors, close } = await openPage();
  try {
    await page.evaluate((scene) => window.flockpath.load(scene), simpleScene());
    assert.equal(await page.evaluate(() => window.flockpath.isPlaying()), true, 'the page starts playing');
    await page.waitForFunction(() => window.flockpath.metrics().steps > 0);

    await page.click('#play');
    assert.equal(await page.evaluate(() => window.flockpath.isPlaying()), false, 'the button pauses');
    const paused = await steps(page);
    await frames(page, 10);
    assert.equal(await steps(page), paused, 'no steps while paused');

    await page.click('#step');
    assert.equal(await steps(page), paused + 1, 'Step advances one step');
    // Single-key shortcuts act while the canvas or the page has focus, never on a focused button
    // (issue #15: Space presses the focused button); a click on a button leaves focus on it.
    await page.focus('#overlay-canvas');
    await page.keyboard.press('s');
    assert.equal(await steps(page), paused + 2, 'S advances one step');

    await page.click('#reset');
    assert.equal(await steps(page), 0, 'Reset goes back to step 0');
    await page.evaluate(() => window.flockpath.step(5));
    await page.focus('#overlay-canvas');
    await page.keyboard.press('r');
    assert.equal(await steps(page), 0, 'R resets');

    await page.keyboard.press('Space');
    assert.equal(await page.evaluate(() => window.flockpath.isPlaying()), true, 'Space plays');
    await page.waitForFunction(() => window.flockpath.metrics().steps > 3);
    await page.keyboard.press('Space');
    assert.equal(await page.evaluate(() => window.flockpath.isPlaying()), false, 'Space pauses');
    const still = await steps(page);
    await frames(page, 5);
    assert.equal(await steps(page), still);

    await page.click('#play');
    assert.equal(await page.evaluate(() => window.flockpath.isPlaying()), true, 'the button plays again');
    assert.equal(await page.textContent('#play'), 'Pause');

    // Number keys pick tools.
    await page.focus('#overlay-canvas');
    await page.keyboard.press('3');
    assert.equal(await page.getAttribute('[data-tool="rect"]', 'aria-checked'), 'true');
    await page.keyboard.press('1');
    assert.equal(await page.getAttribute('[data-tool="select"]', 'aria-checked'), 'true');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('undo and redo an edit; a slider changes the group parameters live', async () => {
  const { page, errors, close } = await openPage();
  try {
    await loadPaused(page, simpleScene());
    const original = await sceneNow(page);

    // Draw a rectangle with the mouse.
    await page.keyboard.press('3');
    const a = await sceneToClient(page, 300, 60);
    const b = await sceneToClient(page, 420, 140);
    await page.mouse.move(a.x, a.y);
    await page.mouse.down();
    await page.mouse.move(b.x, b.y, { steps: 6 });
    await page.mouse.up();
    const edited = await sceneNow(page);
    assert.equal(edited.obstacles.length, 1);
    assert.equal(edited.obstacles[0].shape, 'rect');

    await page.keyboard.press('Control+z');
    assert.deepEqual(await sceneNow(page), original, 'Ctrl+Z undoes');
    await page.keyboard.press('Control+Shift+z');
    assert.deepEqual(await sceneNow(page), edited, 'Ctrl+Shift+Z redoes');
    await page.click('#undo');
    assert.deepEqual(await sceneNow(page), original, 'Undo button');
    await page.keyboard.press('Control+y');
    assert.deepEqual(await sceneNow(page), edited, 'Ctrl+Y redoes');

    // Select the rectangle and delete it with the Delete key; undo brings it back.
    await page.focus('#overlay-canvas');
    await page.keyboard.press('1');
    const inside = await sceneToClient(page, 360, 100);
    await page.mouse.click(inside.x, inside.y);
    await page.keyboard.press('Delete');
    assert.equal((await sceneNow(page)).obstacles.length, 0, 'Delete removes');
    await page.click('#undo');
    assert.deepEqual(await sceneNow(page), edited);

    // Parameter sliders are generated from the planner table, with label, value and unit.
    const slider = '#param-max_speed';
    assert.ok(await page.$(slider), 'a max speed slider exists');
    const label = await page.$eval(slider, (el) => el.closest('.param').textContent);
    assert.match(label, /px\/step/, 'the unit is shown');
    const before = (await sceneNow(page)).groups[0].planner.params.max_speed;
    const target = await page.$eval(slider, (el) => {
      const value = Number(el.max) - Number(el.step);
      el.value = String(value);
      el.dispatchEvent(new Event('input', { bubbles: true }));
      el.dispatchEvent(new Event('change', { bubbles: true }));
      return Number(el.value);
    });
    assert.notEqual(target, before);
    const after = (await sceneNow(page)).groups[0].planner.params.max_speed;
    assert.ok(Math.abs(after - target) < 1e-6, `max_speed ${before} → ${after}, slider ${target}`);
    assert.match(await page.$eval(slider, (el) => el.closest('.param').querySelector('output').textContent), /px\/step/);
    await page.click('#undo');
    const undone = (await sceneNow(page)).groups[0].planner.params.max_speed;
    assert.ok(Math.abs(undone - before) < 1e-6, 'undo restores the parameter');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('HiDPI backing store and resizing keep the scene', async () => {
  const { page, errors, close } = await openPage({ deviceScaleFactor: 2 });
  try {
    await page.evaluate((scene) => window.flockpath.load(scene), simpleScene());
    const size = () =>
      page.$eval('#scene-canvas', (c) => {
        const rect = c.getBoundingClientRect();
        return { width: c.width, height: c.height, cssWidth: rect.width, cssHeight: rect.height };
      });
    const first = await size();
    assert.ok(Math.abs(first.width - 2 * first.cssWidth) <= 1, `backing ${first.width} vs CSS ${first.cssWidth}`);
    assert.ok(Math.abs(first.height - 2 * first.cssHeight) <= 1, `backing ${first.height} vs CSS ${first.cssHeight}`);
    assert.deepEqual(await page.evaluate(async () => (await window.flockpath.settled(), [window.flockpath.view().canvasWidth, window.flockpath.view().canvasHeight])),
      [first.width, first.height], 'the simulation renders at the backing-store size');

    const scene = await sceneNow(page);
    const stepsBefore = await steps(page);
    await page.setViewportSize({ width: 1000, height: 640 });
    await page.waitForFunction((w) => document.getElementById('scene-canvas').width !== w, first.width);
    await frames(page, 3);
    const second = await size();
    assert.ok(second.width < first.width, 'the canvas followed the viewport');
    assert.ok(Math.abs(second.width - 2 * second.cssWidth) <= 1);
    assert.deepEqual(await sceneNow(page), scene, 'same scene after resizing');
    assert.ok((await steps(page)) >= stepsBefore, 'the run was not restarted');
    assert.deepEqual(await page.evaluate(async () => (await window.flockpath.settled(), [window.flockpath.view().canvasWidth, window.flockpath.view().canvasHeight])),
      [second.width, second.height]);
    await screenshot(page, 'controls-hidpi-resized');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
