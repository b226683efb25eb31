// The timeline: scrubbing back and forward gives the same digest as the first pass at that step,
// playing on from a scrubbed step continues the same run, a hidden tab does not step. Also
// prints the time of a scrub jump across 2,000 steps of 1,000 agents (a figure, not a test).

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, frames, openPage, simpleScene } from './helpers.mjs';

/** Moves the timeline slider like a user would (input events), then lets the jump happen. */
async function scrubTo(page, step) {
  await page.$eval('#timeline', (el, value) => {
    el.value = String(value);
    el.dispatchEvent(new Event('input', { bubbles: true }));
    el.dispatchEvent(new Event('change', { bubbles: true }));
  }, step);
  await frames(page, 2);
}

test('scrubbing the timeline back and forward reproduces the first pass', async () => {
  const { page, errors, close } = await openPage();
  try {
    const checkpoints = [0, 1, 99, 100, 101, 250, 437, 600];
    const firstPass = await page.evaluate(async ([scene, ks]) => {
      const api = window.flockpath;
      await api.pause();
      await api.load(scene);
      const digests = {};
      for (const k of ks) {
        await api.step(k - api.metrics().steps);
        digests[k] = api.digest();
      }
      return digests;
    }, [simpleScene({ seed: 11 }), checkpoints]);
    assert.equal(await page.$eval('#timeline', (el) => Number(el.max)), 600, 'the slider spans the run');
    assert.match(await page.textContent('#timeline-step'), /600 of 600/);

    for (const k of [250, 0, 437, 101, 600, 99, 1, 100]) {
      await scrubTo(page, k);
      const now = await page.evaluate(async () => (await window.flockpath.settled(), ({ steps: window.flockpath.metrics().steps, digest: window.flockpath.digest() })));
      assert.equal(now.steps, k, `the slider moved the run to step ${k}`);
      assert.equal(now.digest, firstPass[k], `digest at step ${k} after scrubbing`);
      assert.equal(await page.$eval('#timeline', (el) => Number(el.value)), k);
    }
    // The page API jumps the same way.
    assert.equal(await page.evaluate(() => window.flockpath.seek(437)), 437);
    assert.equal(await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.digest())), firstPass[437]);

    // Play on from a scrubbed step: the same run as the first pass.
    await scrubTo(page, 100);
    await page.evaluate(() => window.flockpath.step(150));
    assert.equal(await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.digest())), firstPass[250], 'stepping on from 100 reaches the same 250');
    await scrubTo(page, 250);
    await page.evaluate(() => window.flockpath.play());
    await page.waitForFunction(() => window.flockpath.metrics().steps > 260);
    await page.evaluate(() => window.flockpath.pause());
    const t = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.timeline()));
    assert.equal(t.end_step, 600, 'the recorded future is kept when nothing changed');
    assert.equal(t.diverged, 0);
    await page.evaluate(() => window.flockpath.seek(437));
    assert.equal(await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.digest())), firstPass[437]);

    // A live parameter change starts a new future from there.
    await page.evaluate(() => window.flockpath.seek(300));
    await page.$eval('#param-max_speed', (el) => {
      el.value = String(Number(el.min) + Number(el.step));
      el.dispatchEvent(new Event('input', { bubbles: true }));
      el.dispatchEvent(new Event('change', { bubbles: true }));
    });
    const edited = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.timeline()));
    assert.equal(edited.end_step, 300, 'the future after an edit is dropped');
    assert.deepEqual(edited.edits, [300]);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('a hidden tab does not step and does not catch up when it comes back', async () => {
  const { page, errors, close } = await openPage();
  try {
    await page.evaluate(async (scene) => {
      await window.flockpath.pause();
      await window.flockpath.load(scene);
    }, simpleScene());
    await page.evaluate(async () => {
      Object.defineProperty(document, 'visibilityState', { value: 'hidden', configurable: true });
      Object.defineProperty(document, 'hidden', { value: true, configurable: true });
      document.dispatchEvent(new Event('visibilitychange'));
      await window.flockpath.play();
    });
    const before = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.metrics().steps));
    await frames(page, 20);
    assert.equal(await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.metrics().steps)), before, 'no steps while hidden');
    await page.evaluate(() => new Promise((resolve) => setTimeout(resolve, 500)));
    await page.evaluate(() => {
      delete document.visibilityState;
      delete document.hidden;
      document.dispatchEvent(new Event('visibilitychange'));
    });
    const spf = await page.$eval('#spf', (el) => Number(el.value));
    const after = await page.evaluate(async () => (await window.flockpath.settled(), new Promise((resolve) => {
      const start = window.flockpath.metrics().steps;
      requestAnimationFrame(() => requestAnimationFrame(() => resolve(window.flockpath.metrics().steps - start)));
    })));
    assert.ok(after > 0 && after <= 2 * spf, `back in view: ${after} steps in two frames, not a catch-up of the hidden time`);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('figure: a scrub jump across 2,000 steps of 1,000 agents', async () => {
  const { page, errors, close } = await openPage();
  try {
    const scene = simpleScene({
      width: 1600,
      height: 1000,
      goals: [{ position: [1450, 500], radius: 120 }],
      groups: [{ ...simpleScene().groups[0], count: 1000, spawn: { min: [40, 200], max: [640, 800] } }],
    });
    const figures = await page.evaluate(async (s) => {
      const api = window.flockpath;
      await api.pause();
      await api.load(s);
      const t0 = performance.now();
      await api.step(2000);
      const recordMs = performance.now() - t0;
      const jumps = [];
      for (const k of [0, 1999, 37, 1950, 1000, 1999]) {
        const from = api.metrics().steps;
        const t = performance.now();
        await api.seek(k);
        jumps.push({ from, to: k, ms: performance.now() - t });
      }
      return { recordMs, jumps, timeline: api.timeline() };
    }, scene);
    const worst = Math.max(...figures.jumps.map((j) => j.ms));
    console.log(`[figure] 1,000 agents: 2,000 recorded steps took ${figures.recordMs.toFixed(0)} ms; ` +
      `checkpoints every ${figures.timeline.checkpoint_every} steps`);
    for (const j of figures.jumps) console.log(`[figure] scrub ${j.from} → ${j.to}: ${j.ms.toFixed(1)} ms`);
    console.log(`[figure] worst scrub jump: ${worst.toFixed(1)} ms (target < 100 ms)`);
    assert.equal(figures.timeline.end_step, 2000);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
