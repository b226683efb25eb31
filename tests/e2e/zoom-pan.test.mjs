// Zoom and pan on the playground canvas (issue 27 §2): the wheel zooms about the pointer, + / −
// about the centre, 0 and the Fit button show the whole scene; a drag on empty space with the
// Select tool, or any drag with Space held, pans a zoomed view. The renderer (Rust) draws the
// zoomed view, and the editor maps the pointer through it: a goal clicked while zoomed lands on
// the world point under the pointer. Zooming changes no simulation state (digest unchanged).

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, frames, loadPaused, openPage, settled, simpleScene } from './helpers.mjs';

const view = (page) => page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.view()));

/** The scene point under client point (x, y) in view `v` (device px = CSS px at ratio 1). */
async function sceneAt(page, v, x, y) {
  const rect = await page.evaluate(() => {
    const r = document.getElementById('scene-canvas').getBoundingClientRect();
    return { left: r.left, top: r.top, width: r.width, height: r.height };
  });
  const px = ((x - rect.left) * v.canvasWidth) / rect.width;
  const py = ((y - rect.top) * v.canvasHeight) / rect.height;
  return [(px - v.offsetX) / v.scale, (py - v.offsetY) / v.scale];
}

test('the wheel zooms about the pointer, a click while zoomed places a goal under it, Fit and keys work', async () => {
  const { page, errors, close } = await openPage({ viewport: { width: 1366, height: 768 } });
  try {
    await loadPaused(page, simpleScene());
    const fitted = await view(page);
    const box = await page.locator('#overlay-canvas').boundingBox();
    // Whole CSS px: Chromium reports a wheel event's position in whole pixels.
    const pointer = { x: Math.round(box.x + box.width * 0.3), y: Math.round(box.y + box.height * 0.4) };
    const under = await sceneAt(page, fitted, pointer.x, pointer.y);

    await page.mouse.move(pointer.x, pointer.y);
    await page.mouse.wheel(0, -500);
    await page.waitForFunction((s) => window.flockpath.view().scale > s * 1.5, fitted.scale);
    const zoomed = await view(page);
    const stays = await sceneAt(page, zoomed, pointer.x, pointer.y);
    console.log(`wheel: scale ${fitted.scale.toFixed(3)} → ${zoomed.scale.toFixed(3)}; under the pointer ${under.map((v) => v.toFixed(2))} → ${stays.map((v) => v.toFixed(2))}`);
    assert.ok(Math.abs(zoomed.scale / fitted.scale - Math.E) < 0.05, `one 500 px wheel turn zooms by e: ${zoomed.scale / fitted.scale}`);
    assert.ok(Math.hypot(stays[0] - under[0], stays[1] - under[1]) < 0.5, 'the point under the pointer stays under it');

    // A goal clicked while zoomed lands on the world point under the pointer.
    await page.click('button[data-tool="goal"]');
    const target = { x: Math.round(box.x + box.width * 0.62), y: Math.round(box.y + box.height * 0.7) };
    const expected = await sceneAt(page, zoomed, target.x, target.y);
    const wrong = await sceneAt(page, fitted, target.x, target.y);
    const goalsBefore = (await page.evaluate(() => window.flockpath.scene().goals)).length;
    await page.mouse.click(target.x, target.y);
    await page.waitForFunction((n) => window.flockpath.scene().goals.length > n, goalsBefore);
    const placed = (await page.evaluate(() => window.flockpath.scene().goals)).at(-1).position;
    console.log(`goal clicked at ${expected.map((v) => v.toFixed(1))} (zoomed view), placed at ${placed}; the fitted view would say ${wrong.map((v) => v.toFixed(1))}`);
    assert.ok(Math.hypot(placed[0] - expected[0], placed[1] - expected[1]) < 0.2, `placed at ${placed}, expected ${expected}`);
    assert.ok(Math.hypot(wrong[0] - expected[0], wrong[1] - expected[1]) > 20, 'the test tells the two views apart');

    // The pixels come from the renderer: the goal's ring is drawn zoomed, where it was clicked.
    await frames(page, 3);
    const ink = await page.evaluate(({ x, y }) => {
      const canvas = document.getElementById('scene-canvas');
      const r = canvas.getBoundingClientRect();
      const cx = Math.round(x - r.left);
      const cy = Math.round(y - r.top);
      const data = canvas.getContext('2d').getImageData(cx - 80, cy, 160, 1).data;
      const background = [0xf6, 0xf5, 0xf0];
      let differs = 0;
      for (let i = 0; i < data.length; i += 4) {
        if (Math.abs(data[i] - background[0]) + Math.abs(data[i + 1] - background[1]) + Math.abs(data[i + 2] - background[2]) > 60) differs += 1;
      }
      return differs;
    }, target);
    assert.ok(ink >= 2, `the goal's ring crosses a row through its centre: ${ink} inked pixels`);

    // Keys: + zooms in about the centre, − out, 0 fits; the Fit button fits too.
    await page.click('button[data-tool="select"]');
    await page.evaluate(() => document.activeElement.blur());
    await page.keyboard.press('+');
    await page.waitForFunction((s) => window.flockpath.view().scale > s * 1.4, zoomed.scale);
    await page.keyboard.press('-');
    await page.waitForFunction((s) => Math.abs(window.flockpath.view().scale - s) < 1e-3, zoomed.scale);
    await page.keyboard.press('0');
    await page.waitForFunction((s) => Math.abs(window.flockpath.view().scale - s) < 1e-4, fitted.scale);
    assert.deepEqual(await view(page), fitted, '0 shows the whole scene, fitted as before');
    await page.keyboard.press('+');
    await page.waitForFunction((s) => window.flockpath.view().scale > s * 1.4, fitted.scale);
    await page.click('#zoom-fit');
    await page.waitForFunction((s) => Math.abs(window.flockpath.view().scale - s) < 1e-4, fitted.scale);
    assert.deepEqual(await view(page), fitted, 'Fit shows the whole scene');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('a drag on empty space (Select) or with Space held pans a zoomed view; zoom leaves the run unchanged', async () => {
  const { page, errors, close } = await openPage({ viewport: { width: 1366, height: 768 } });
  try {
    await loadPaused(page, simpleScene());
    await page.evaluate(() => window.flockpath.step(100));
    const digest = await page.evaluate(() => window.flockpath.digest());
    const box = await page.locator('#overlay-canvas').boundingBox();
    const centre = { x: box.x + box.width / 2, y: box.y + box.height / 2 };
    await page.mouse.move(centre.x, centre.y);
    await page.mouse.wheel(0, -700);
    await page.waitForFunction(() => window.flockpath.view().scale > 2);
    const zoomed = await view(page);

    // Empty space (no agent, goal or obstacle at the scene's top-left quarter) with Select: a pan.
    const from = { x: box.x + 60, y: box.y + 60 };
    await page.mouse.move(from.x, from.y);
    await page.mouse.down();
    for (let i = 1; i <= 8; i += 1) await page.mouse.move(from.x + i * 10, from.y + i * 5);
    await page.mouse.up();
    await page.waitForFunction((x) => Math.abs(window.flockpath.view().offsetX - x - 80) < 1, zoomed.offsetX);
    const panned = await view(page);
    console.log(`select-drag by (80, 40) moved the view by (${(panned.offsetX - zoomed.offsetX).toFixed(1)}, ${(panned.offsetY - zoomed.offsetY).toFixed(1)})`);
    assert.ok(Math.abs(panned.offsetY - zoomed.offsetY - 40) < 1);
    assert.equal(panned.scale, zoomed.scale, 'a pan does not zoom');
    assert.equal(await page.evaluate(() => window.flockpath.scene().obstacles.length), 0, 'nothing drawn');

    // Space held: any tool's drag pans (here the Circle tool, which would draw an obstacle), and
    // the Space press's Play/Pause is undone.
    await page.click('button[data-tool="circle"]');
    await page.evaluate(() => document.activeElement.blur());
    const playing = await page.evaluate(() => window.flockpath.isPlaying());
    await page.keyboard.down(' ');
    await page.mouse.move(centre.x, centre.y);
    await page.mouse.down();
    for (let i = 1; i <= 6; i += 1) await page.mouse.move(centre.x - i * 10, centre.y);
    await page.mouse.up();
    await page.keyboard.up(' ');
    await page.waitForFunction((x) => Math.abs(window.flockpath.view().offsetX - (x - 60)) < 1, panned.offsetX);
    assert.equal(await page.evaluate(() => window.flockpath.scene().obstacles.length), 0, 'Space+drag drew no circle');
    await settled(page);
    assert.equal(await page.evaluate(() => window.flockpath.isPlaying()), playing, 'Space used to pan leaves play as it was');
    // The run is the same at any zoom: zoom and pan change pixels, not state.
    assert.equal(await page.evaluate(() => window.flockpath.metrics().steps), 100, 'holding Space to pan did not play');
    assert.equal(await page.evaluate(() => window.flockpath.digest()), digest, 'zooming and panning changed nothing');
    // Space alone still plays or pauses.
    await page.keyboard.press(' ');
    assert.equal(await page.evaluate(() => window.flockpath.isPlaying()), !playing);
    await page.evaluate(() => window.flockpath.pause());
    await page.evaluate(async () => {
      await window.flockpath.reset();
      await window.flockpath.step(40);
    });
    await page.keyboard.press('+');
    await page.evaluate(() => window.flockpath.step(30));
    await page.keyboard.press('0');
    await page.evaluate(() => window.flockpath.step(30));
    assert.equal(await page.evaluate(() => window.flockpath.digest()), digest, 'a run stepped while zooming has the digest of one stepped without');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
