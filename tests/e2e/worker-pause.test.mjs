// The simulation runs in a worker (issue 24): a scene whose every step takes seconds leaves the
// page free. 1,000 Boids among 5,000 circles whose bounding boxes all cover the world (every
// obstacle is a candidate for every agent: seconds per step) is loaded through the page API and
// played; while a step runs, a real click on Pause must change the button's pressed state and the
// page's playing state, and let an animation frame run, within 100 ms, and the page must show the
// slow scene's rate. The Pause the worker cannot answer in time ends it: the page restarts it from
// the scene, says so, and the scene is back at the step shown.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, bannerText, openPage, screenshot, simpleScene } from './helpers.mjs';
import { coveringCircles, timedPause } from './pause-helpers.mjs';

/** Longest a Pause click may take to be answered on the page (ms). */
const ANSWER_MS = 100;
const WORLD = 1000;

/**
 * `count` Boids of radius `radius` among the circles (here, under load: 1,000 ~0.4 s a step,
 * 4,000 ~2.4 s).
 */
const heavy = (count, radius = 4) =>
  simpleScene({
    name: 'heavy-covering-circles',
    width: WORLD,
    height: WORLD,
    obstacles: coveringCircles(5_000, WORLD),
    goals: [{ position: [900, 900], radius: 60 }],
    groups: [{ ...simpleScene().groups[0], count, agent_radius: radius, spawn: { min: [600, 600], max: [980, 980] } }],
  });
const HEAVY = heavy(1_000);
/** Steps of over a second: a Pause during one waits longer than the worker may take. */
const HEAVIER = heavy(6_000, 2);

test('Pause is answered within 100 ms while a step of seconds runs, and the slow rate shows', { timeout: 300_000 }, async () => {
  const { page, errors, close } = await openPage();
  try {
    await page.evaluate(async (scene) => {
      await window.flockpath.pause();
      await window.flockpath.load(scene);
    }, HEAVY);
    const times = [];
    let shownRate = null;
    for (let round = 0; round < 5; round += 1) {
      await page.evaluate(() => window.flockpath.play());
      // A step is running: the page says how slow the scene is while it plays on.
      await page.waitForSelector('#slow-scene:not([hidden])', { timeout: 30_000 });
      shownRate ??= await page.textContent('#slow-scene');
      if (round === 0) await screenshot(page, 'worker-slow-scene');
      times.push(await timedPause(page));
      assert.equal(await page.getAttribute('#play', 'aria-pressed'), 'false');
      // Let the worker finish its step (or be restarted) before the next round.
      await page.evaluate(() => window.flockpath.settled());
    }
    const sorted = [...times].sort((a, b) => a - b);
    const median = sorted[Math.floor(sorted.length / 2)];
    console.log(`Pause answered in ${times.map((t) => t.toFixed(0)).join(', ')} ms (median ${median.toFixed(0)})`);
    assert.ok(median <= ANSWER_MS, `Pause took ${median} ms (median of ${times.join(', ')})`);
    assert.ok(Math.max(...times) <= ANSWER_MS * 3, `the slowest Pause took ${Math.max(...times)} ms`);
    assert.match(shownRate, /^slow scene: [\d.,]+ steps\/s$/);
    // How slow the scene is: the worker's own step time, so the test proves the scene was heavy.
    const stepMs = await page.evaluate(() => Number(document.getElementById('slow-scene').title.match(/\((\d[\d,]*) ms/)[1].replace(/,/g, '')));
    assert.ok(stepMs >= 100, `a step took ${stepMs} ms: the scene is heavy enough to test the rule`);
  } finally {
    await close();
  }
  assertNoUnexpectedErrors(errors);
});

test('a Pause the worker cannot answer for 1 s restarts it at the step shown, with a message', { timeout: 300_000 }, async () => {
  const { page, errors, close } = await openPage();
  try {
    await page.evaluate(async (scene) => {
      await window.flockpath.pause();
      await window.flockpath.load(scene);
      await window.flockpath.step(1);
    }, HEAVIER);
    const before = await page.evaluate(async () => (await window.flockpath.settled(), ({ steps: window.flockpath.metrics().steps, digest: window.flockpath.digest() })));
    await page.evaluate(() => window.flockpath.play());
    // Pause right after a frame arrived: the worker has just begun the next step (over a second
    // long), so it cannot answer within 1 s.
    await page.waitForFunction((n) => window.flockpath.metrics().steps > n, before.steps, { timeout: 60_000, polling: 'raf' });
    await page.waitForSelector('#slow-scene:not([hidden])', { timeout: 5_000 });
    await page.click('#play');
    await page.waitForFunction(() => /restarted/.test(document.getElementById('banner-text')?.textContent ?? ''), null, { timeout: 10_000 });
    assert.match(await bannerText(page), /replays the run to step \d+/);
    // The new worker holds the same scene and, once replayed, the state of the step it names.
    const named = Number((await bannerText(page)).match(/to step ([\d,]+)/)[1].replace(/,/g, ''));
    assert.ok(named >= before.steps, `replays to step ${named} (was ${before.steps} before Play)`);
    await page.waitForFunction((n) => window.flockpath.metrics().steps === n, named, { timeout: 200_000, polling: 500 });
    const after = await page.evaluate(async () => (await window.flockpath.settled(), ({ name: window.flockpath.scene().name, playing: window.flockpath.isPlaying() })));
    assert.equal(after.name, 'heavy-covering-circles');
    assert.equal(after.playing, false);
    if (named === before.steps) {
      assert.equal(await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.digest())), before.digest, 'the same run, bit for bit');
    }
  } finally {
    await close();
  }
  assertNoUnexpectedErrors(errors);
});
