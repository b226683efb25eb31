// Slow motion (issue 27 §2): the Speed slider goes below 1× (0.5, 0.25, 0.1×); the worker then
// steps once every 1 / speed painted frames, so 0.25× runs about a quarter of the steps of 1×
// over the same frames, and the readout says "0.25×".

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, loadPaused, openPage, settled, simpleScene } from './helpers.mjs';

/** Sets the Speed slider as a user would (an `input` event). */
async function setSpeed(page, position) {
  await page.evaluate((v) => {
    const spf = document.getElementById('spf');
    spf.value = String(v);
    spf.dispatchEvent(new Event('input', { bubbles: true }));
  }, position);
}

/** Steps run while the page paints `n` frames of a playing scene (paused again after). */
async function stepsOver(page, n) {
  await page.evaluate(() => window.flockpath.play());
  const counted = await page.evaluate(
    (count) =>
      new Promise((resolve) => {
        // Wait a few frames for the worker to pick up the speed, then count.
        let warm = 5;
        let left = count;
        let start = 0;
        const tick = () => {
          if (warm > 0) {
            warm -= 1;
            if (warm === 0) start = window.flockpath.metrics().steps;
          } else if (--left === 0) {
            resolve(window.flockpath.metrics().steps - start);
            return;
          }
          requestAnimationFrame(tick);
        };
        requestAnimationFrame(tick);
      }),
    n,
  );
  await page.evaluate(() => window.flockpath.pause());
  return counted;
}

test('0.25× steps about a quarter as often as 1× over the same frames, and says 0.25×', async () => {
  const { page, errors, close } = await openPage();
  try {
    await loadPaused(page, simpleScene());
    const range = await page.evaluate(() => {
      const spf = document.getElementById('spf');
      return [Number(spf.min), Number(spf.max)];
    });
    assert.deepEqual(range, [-2, 20], 'the slider reaches below 1× and up to 20×');

    await setSpeed(page, 1);
    assert.equal(await page.textContent('#spf-value'), '1×');
    const FRAMES = 120;
    const normal = await stepsOver(page, FRAMES);
    await settled(page);

    await setSpeed(page, -1);
    assert.equal(await page.textContent('#spf-value'), '0.25×');
    assert.equal(await page.getAttribute('#spf', 'aria-valuetext'), '0.25×', 'a screen reader hears the speed, not the position');
    const slow = await stepsOver(page, FRAMES);
    await settled(page);

    await setSpeed(page, -2);
    assert.equal(await page.textContent('#spf-value'), '0.1×');
    const slowest = await stepsOver(page, FRAMES);
    console.log(`over ${FRAMES} frames: 1× ${normal} steps, 0.25× ${slow}, 0.1× ${slowest}`);
    assert.ok(normal >= FRAMES * 0.6, `1× keeps up: ${normal} steps in ${FRAMES} frames`);
    const ratio = slow / normal;
    assert.ok(ratio > 0.18 && ratio < 0.32, `0.25× ran ${slow} steps where 1× ran ${normal} (ratio ${ratio.toFixed(2)})`);
    const tenth = slowest / normal;
    assert.ok(tenth > 0.06 && tenth < 0.14, `0.1× ran ${slowest} steps where 1× ran ${normal} (ratio ${tenth.toFixed(2)})`);

    // The slow run is the same run: a step is a step (the digest after n steps does not depend
    // on the speed that reached it).
    const steps = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.metrics().steps));
    const digest = await page.evaluate(() => window.flockpath.digest());
    await page.evaluate(async (n) => {
      await window.flockpath.reset();
      await window.flockpath.step(n);
    }, steps);
    assert.equal(await page.evaluate(() => window.flockpath.digest()), digest, 'slow motion reaches the same state');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
