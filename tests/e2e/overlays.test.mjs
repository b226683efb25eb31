// Overlay switches change the canvas: the PSO cost landscape of the inspected agent, firefly
// feelers and brightness, and the rings and count of stuck agents in the U-trap.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, frames, openPage, screenshot, snapshotCanvas } from './helpers.mjs';

async function changedPixels(page, a, b) {
  return page.evaluate(([x, y]) => {
    const [p, q] = [window.__e2eSnapshots[x].data, window.__e2eSnapshots[y].data];
    let n = 0;
    for (let i = 0; i < p.length; i += 4) if (p[i] !== q[i] || p[i + 1] !== q[i + 1] || p[i + 2] !== q[i + 2]) n += 1;
    return n;
  }, [a, b]);
}

/**
 * Snapshots the canvas as `name` once its change from snapshot `base` satisfies `enough(n)`
 * (the worker draws a toggled overlay a frame or more after the click), or after 60 frames;
 * returns the last count.
 */
async function snapshotWhen(page, name, base, enough) {
  let n = 0;
  for (let tries = 0; tries < 30; tries += 1) {
    await frames(page, 2);
    await snapshotCanvas(page, name);
    n = await changedPixels(page, base, name);
    if (enough(n)) break;
  }
  return n;
}

test('overlay toggles change the pixels; stuck agents are counted', async () => {
  const { page, errors, close } = await openPage();
  try {
    await page.selectOption('#preset', 'u-trap');
    await page.evaluate(async () => {
      await window.flockpath.pause();
      await window.flockpath.reset();
      await window.flockpath.step(60);
      await window.flockpath.inspect(0);
    });
    await page.uncheck('#trails');
    await frames(page, 2);
    await snapshotCanvas(page, 'plain');

    await page.check('#overlay-landscape');
    const heat = await snapshotWhen(page, 'landscape', 'plain', (n) => n > 5000);
    assert.ok(heat > 5000, `the heat map changed ${heat} px`);
    await screenshot(page, 'overlay-landscape');
    await page.uncheck('#overlay-landscape');

    await page.check('#overlay-fireflies');
    const feelers = await snapshotWhen(page, 'fireflies', 'plain', (n) => n > 300);
    assert.ok(feelers > 300, `feelers and brightness changed ${feelers} px`);
    await page.uncheck('#overlay-fireflies');
    const left = await snapshotWhen(page, 'off-again', 'plain', (n) => n === 0);
    assert.equal(left, 0, 'switching off restores the frame');

    await page.evaluate(() => window.flockpath.step(840));
    await frames(page, 2);
    const stuck = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.stuckAgents().length));
    assert.ok(stuck > 0, 'agents are stuck in the U');
    assert.equal(await page.textContent('#stuck-count'), `${stuck} agents stuck`);
    await snapshotCanvas(page, 'rings');
    await page.uncheck('#overlay-stuck');
    const rings = await snapshotWhen(page, 'no-rings', 'rings', (n) => n > 100);
    assert.ok(rings > 100, `rings mark the stuck agents (${rings} px)`);
    await page.check('#overlay-stuck');
    await frames(page, 2);
    await screenshot(page, 'overlay-stuck');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
