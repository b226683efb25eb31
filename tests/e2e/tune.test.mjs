// The Tune page: a short GA run in the Web Worker fills the progress bar and the plot, Apply opens
// the playground with the tuned weights in the scene (and its link); a long run can be cancelled
// and the page keeps animating its preview while the worker computes; the playground's own scene
// can be tuned through the header link.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPage, openPath, screenshot, waitReady } from './helpers.mjs';

const tuneReady = () => window.flocktune !== undefined;
const state = (page) => page.evaluate(() => window.flocktune.state());

/** The planner weights of every group of the playground's scene, as [s1…s5]. */
async function playgroundWeights(page) {
  return page.evaluate(() =>
    window.flockpath.scene().groups.map((g) => ({
      kind: g.planner.kind,
      weights: ['separation_weight', 'alignment_weight', 'cohesion_weight', 'following_weight', 'collision_weight']
        .map((k) => g.planner.params[k]),
    })),
  );
}

test('a short run progresses, plots every generation, and Apply opens the tuned scene', async () => {
  const query = '?behaviour=b2&environment=e2&seed=5&population=10&generations=4&frames=60';
  const { page, errors, close } = await openPath(`tune.html${query}`, { ready: tuneReady });
  try {
    // The address preset the fields; nothing ran yet.
    const fields = await page.evaluate(() =>
      ['behaviour', 'environment', 'seed', 'population', 'generations', 'frames'].map((id) => document.getElementById(id).value));
    assert.deepEqual(fields, ['b2', 'e2', '5', '10', '4', '60']);
    assert.equal(await page.locator('#progress').evaluate((p) => p.value), 0);
    assert.equal(await page.locator('#apply').isDisabled(), true);

    await page.click('#tune');
    // Progress arrives generation by generation: the bar and the plot follow each report.
    await page.waitForFunction(() => window.flocktune.state().history.length >= 1, null, { timeout: 60_000 });
    const first = await page.evaluate(() => ({
      bar: document.getElementById('progress').value,
      points: Number(document.getElementById('plot').dataset.points),
      generation: document.getElementById('generation').textContent,
    }));
    assert.ok(first.bar >= 1, `progress bar moved: ${first.bar}`);
    assert.ok(first.points >= 1, `plot has points: ${first.points}`);
    assert.match(first.generation, /of ≤ 4/);

    await page.waitForFunction(() => window.flocktune.state().finished, null, { timeout: 120_000 });
    const done = await state(page);
    assert.equal(done.running, false);
    assert.equal(done.history.length, 4, 'patience 5 > 4 generations: the limit stops the run');
    assert.equal(await page.locator('#plot').evaluate((c) => Number(c.dataset.points)), 4);
    assert.deepEqual(await page.locator('#progress').evaluate((p) => [p.value, p.max]), [4, 4]);
    assert.ok(done.best.gsum >= done.history[0].best_gsum, 'the best never falls below generation 0');
    assert.equal(await page.locator('#best-gsum').textContent(), done.best.gsum.toFixed(2));
    assert.match(await page.locator('#status').textContent(), /Done after 4 generations/);
    // One count everywhere (issue #27 §5: "generation 0" in the preview, "Generation 3 of ≤ 3"
    // over an axis 0–2): generations 1…4 in the status, the preview and the plot's axis.
    assert.equal(await page.locator('#generation').textContent(), '4 of ≤ 4');
    assert.deepEqual(await page.locator('#plot').evaluate((c) => [c.dataset.axis, c.dataset.last]), ['1–4', '4']);
    assert.match(await page.locator('#preview-label').textContent(), /generation [1-4]\b/);
    assert.ok(done.previewSteps > 0 || done.previewFrames > 0, 'the preview runs');
    await screenshot(page, 'tune-finished');

    // Apply: the playground opens with the scene and its link carries the weights.
    await page.click('#apply');
    await page.waitForURL(/index\.html#s=/, { timeout: 30_000 });
    await waitReady(page);
    const groups = await playgroundWeights(page);
    assert.ok(groups.length >= 1);
    for (const g of groups) {
      assert.equal(g.kind, 'forces');
      g.weights.forEach((w, i) => assert.ok(Math.abs(w - done.best.weights[i]) < 1e-6, `s${i + 1}: ${w} vs ${done.best.weights[i]}`));
    }
    const link = await page.evaluate(() => location.hash.slice(3));
    assert.equal(link, done.bestScene, 'the address holds the tuned scene');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('a long run keeps the page responsive and can be cancelled', async () => {
  // Paper-sized generation with long evaluations: generation 0 takes seconds in the worker.
  const query = '?behaviour=b1&environment=e3&seed=2&population=200&generations=30&frames=1200';
  const { page, errors, close } = await openPath(`tune.html${query}`, { ready: tuneReady });
  try {
    await page.click('#tune');
    await page.waitForFunction(() => /Generation 1 of up to/.test(document.getElementById('status').textContent), null,
      { timeout: 30_000 });
    // While the worker scores generation 0 the page keeps painting the preview and answering.
    const before = await state(page);
    await page.waitForTimeout(1000);
    const after = await state(page);
    assert.equal(after.history.length, 0, 'generation 0 is still being computed');
    assert.ok(after.previewFrames - before.previewFrames >= 10,
      `the preview kept animating: ${after.previewFrames - before.previewFrames} frames in 1 s`);
    assert.equal(await page.locator('#behaviour').isDisabled(), true, 'settings are locked during a run');

    await page.click('#cancel');
    const cancelled = await state(page);
    assert.equal(cancelled.running, false);
    assert.equal(cancelled.cancelled, true);
    assert.match(await page.locator('#status').textContent(), /Cancelled/);
    assert.equal(await page.locator('#tune').isDisabled(), false);
    // The worker is gone: no report arrives any more.
    await page.waitForTimeout(1500);
    assert.equal((await state(page)).history.length, cancelled.history.length);

    // The fields are free again and a new, small run works after the cancel.
    await page.fill('#population', '6');
    await page.fill('#generations', '2');
    await page.fill('#frames', '30');
    await page.click('#tune');
    await page.waitForFunction(() => window.flocktune.state().finished, null, { timeout: 60_000 });
    assert.equal((await state(page)).history.length, 2);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('the playground’s scene is tuned through the header link', async () => {
  const { page, errors, close } = await openPage();
  try {
    // Wait until the address bar holds the scene (written 300 ms after a change, or at boot).
    await page.evaluate(() => window.flockpath.load(window.flockpath.scene()));
    await page.waitForFunction(() => location.hash.startsWith('#s='), null, { timeout: 10_000 });
    const original = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene()));
    await page.click('#tune-link');
    await page.waitForURL(/tune\.html#s=/, { timeout: 30_000 });
    await page.waitForFunction(() => window.flocktune !== undefined, null, { timeout: 30_000 });
    assert.equal(await page.locator('#environment').inputValue(), 'scene', 'the playground’s scene is selected');

    await page.fill('#population', '4');
    await page.fill('#generations', '2');
    await page.fill('#frames', '20');
    await page.click('#tune');
    await page.waitForFunction(() => window.flocktune.state().finished, null, { timeout: 120_000 });
    const done = await state(page);
    assert.ok(done.setup.scene, 'the run tuned the linked scene');

    await page.click('#apply');
    await page.waitForURL(/index\.html#s=/, { timeout: 30_000 });
    await waitReady(page);
    const tuned = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene()));
    assert.equal(tuned.obstacles.length, original.obstacles.length, 'same obstacles');
    assert.equal(tuned.groups.length, original.groups.length, 'same groups');
    for (const g of await playgroundWeights(page)) {
      assert.equal(g.kind, 'forces');
      g.weights.forEach((w, i) => assert.ok(Math.abs(w - done.best.weights[i]) < 1e-6));
    }
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
