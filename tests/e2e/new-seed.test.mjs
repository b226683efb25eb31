// "New seed": the button sets a seed drawn in Rust (the wasm export `fresh_seed`, from the
// browser's CSPRNG), different on each click, shown in the seed field; the run is then a
// function of the scene and that seed alone (typing the seed back replays it bit for bit).

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPage, simpleScene } from './helpers.mjs';

const seedNow = (page) => page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene().seed));
/** The digest after `n` steps from step 0 of the current scene and seed. */
const runDigest = (page, n) =>
  page.evaluate(async (n) => {
    await window.flockpath.reset();
    await window.flockpath.step(n);
    return window.flockpath.digest();
  }, n);

test('new seed gives a different seed each click, and a seed replays the same run', async () => {
  const { page, errors, close } = await openPage();
  try {
    await page.evaluate(async (scene) => {
      await window.flockpath.pause();
      await window.flockpath.load(scene);
    }, simpleScene({ seed: 7 }));
    // The page draws no randomness of its own: Math.random is not how the seed is chosen.
    await page.evaluate(() => {
      Math.random = () => {
        throw new Error('Math.random called by the page');
      };
    });
    assert.equal(await seedNow(page), 7);
    const first = await runDigest(page, 120);
    assert.equal(await runDigest(page, 120), first, 'the same scene and seed replay the same run');

    const seeds = [7];
    for (let click = 0; click < 3; click += 1) {
      await page.click('#new-seed');
      const seed = await seedNow(page);
      assert.ok(Number.isInteger(seed) && seed >= 0 && seed <= 0xffffffff, `a 32-bit seed, got ${seed}`);
      assert.ok(!seeds.includes(seed), `click ${click + 1} gave a seed seen before: ${seed} in ${seeds}`);
      assert.equal(await page.inputValue('#seed'), String(seed), 'the seed field shows the new seed');
      assert.equal(await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.metrics().steps)), 0, 'a new seed restarts');
      seeds.push(seed);
    }
    const fresh = seeds[seeds.length - 1];
    const freshDigest = await runDigest(page, 120);
    assert.notEqual(freshDigest, first, 'another seed gives another run');
    assert.equal(await runDigest(page, 120), freshDigest, 'the new seed replays the same run');

    // Back to seed 7 by typing it, then to the fresh seed again: each replays its own run.
    await page.fill('#seed', '7');
    await page.dispatchEvent('#seed', 'change');
    assert.equal(await seedNow(page), 7);
    assert.equal(await runDigest(page, 120), first, 'seed 7 typed back replays its run');
    await page.fill('#seed', String(fresh));
    await page.dispatchEvent('#seed', 'change');
    assert.equal(await runDigest(page, 120), freshDigest, `seed ${fresh} typed in replays its run`);

    // The seed is drawn by the wasm module, which the page can call directly.
    const direct = await page.evaluate(async () => {
      const module = await import(new URL('pkg/flockpath.js', location.href).href);
      return [module.fresh_seed(), module.fresh_seed()];
    });
    assert.ok(direct.every((s) => Number.isInteger(s) && s >= 0 && s <= 0xffffffff), `${direct}`);
    assert.notEqual(direct[0], direct[1], 'two draws differ');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
