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
    await frames(page, 2);
    await snapshotCanvas(page, 'landscape');
    const heat = await changedPixels(page, 'plain', 'landscape');
    assert.ok(heat > 5000, `the heat map changed ${heat} px`);
    await screenshot(page, 'overlay-landscape');
    await page.uncheck('#overlay-landscape');

    await page.check('#overlay-fireflies');
    await frames(page, 2);
    await snapshotCanvas(page, 'fireflies');
    const feelers = await changedPixels(page, 'plain', 'fireflies');
    assert.ok(feelers > 300, `feelers and brightness changed ${feelers} px`);
    await page.uncheck('#overlay-fireflies');
    await frames(page, 2);
    await snapshotCanvas(page, 'off-again');
    assert.equal(await changedPixels(page, 'plain', 'off-again'), 0, 'switching off restores the frame');

    await page.evaluate(() => window.flockpath.step(840));
    await frames(page, 2);
    const stuck = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.stuckAgents().length));
    assert.ok(stuck > 0, 'agents are stuck in the U');
    assert.equal(await page.textContent('#stuck-count'), `${stuck} agents stuck`);
    await snapshotCanvas(page, 'rings');
    await page.uncheck('#overlay-stuck');
    await frames(page, 2);
    await snapshotCanvas(page, 'no-rings');
    assert.ok((await changedPixels(page, 'rings', 'no-rings')) > 100, 'rings mark the stuck agents');
    await page.check('#overlay-stuck');
    await frames(page, 2);
    await screenshot(page, 'overlay-stuck');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
