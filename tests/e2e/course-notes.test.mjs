// examples/course-notes.html: two <flock-path> elements and one iframe of embed.html on one page.
// Each loads its own scene and plays; pausing one leaves the others running (independent Sims
// sharing one wasm module); the iframe plays too.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPath, screenshot } from './helpers.mjs';

const allReady = () => {
  const els = [...document.querySelectorAll('flock-path')];
  return els.length === 2 && els.every((el) => el.sim && el.steps > 0);
};

test('the course-notes page runs three independent embedded scenes', async () => {
  const { page, errors, close } = await openPath('examples/course-notes.html', {
    ready: allReady,
    viewport: { width: 1000, height: 900 },
  });
  try {
    const names = await page.evaluate(() => [...document.querySelectorAll('flock-path')].map((el) => el.scene().name));
    assert.deepEqual(names, ['pillars', 'swap, priority arbitration']);
    const swapView = await page.evaluate(() => document.getElementById('swap').scene().view);
    assert.deepEqual(swapView, { trails: true, trail_fade: 0.004 }, 'the view options came with the scene string');

    // Pause the first: it stops, the second keeps going.
    await page.locator('#pillars button.play').click();
    const stopped = await page.evaluate(() => document.getElementById('pillars').steps);
    const before = await page.evaluate(() => document.getElementById('swap').steps);
    await page.waitForFunction((n) => document.getElementById('swap').steps > n + 20, before);
    assert.equal(await page.evaluate(() => document.getElementById('pillars').steps), stopped, 'paused one stays');
    // Stepping one by hand does not move the other.
    const swapNow = await page.evaluate(async () => {
      const swap = document.getElementById('swap');
      await swap.pause();
      return swap.steps;
    });
    await page.evaluate(() => document.getElementById('pillars').step(7));
    assert.equal(await page.evaluate(() => document.getElementById('pillars').steps), stopped + 7);
    assert.equal(await page.evaluate(() => document.getElementById('swap').steps), swapNow);

    // The iframe of embed.html plays its own scene.
    await page.locator('#corridor').scrollIntoViewIfNeeded();
    const frame = page.frameLocator('#corridor');
    await frame.locator('flock-path').waitFor();
    const inner = page.frames().find((f) => f.url().includes('embed.html'));
    await inner.waitForFunction(() => window.flockpathEmbed && window.flockpathEmbed.steps > 10);
    assert.equal(await inner.evaluate(() => window.flockpathEmbed.scene().name), 'corridor');
    await screenshot(page, 'course-notes');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
