// A link replays the scene exactly: edit a scene in the page (a drawn obstacle, a parameter, the
// seed, the trail options), read the address bar (rewritten by replaceState, without flooding
// Back), open that URL in a new page, and get the same scene and, after the same steps, the same
// metrics and the same digest.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, frames, openPage, sceneToClient, screenshot, simpleScene } from './helpers.mjs';

const STEPS = 240;

/** Runs `STEPS` steps from the start, paused; returns metrics and digest. */
async function runFromStart(page) {
  return page.evaluate(async (n) => {
    await window.flockpath.pause();
    await window.flockpath.reset();
    await window.flockpath.step(n);
    return { metrics: window.flockpath.metrics(), digest: window.flockpath.digest() };
  }, STEPS);
}

test('an edited scene survives the round trip through the URL', async () => {
  const { page, context, errors, close } = await openPage();
  try {
    await page.evaluate((scene) => window.flockpath.load(scene), simpleScene({ name: 'shared' }));
    const historyBefore = await page.evaluate(() => history.length);

    // Draw a circle obstacle with the mouse (tool 2: drag from centre to radius).
    await page.keyboard.press('2');
    const centre = await sceneToClient(page, 400, 250);
    const edge = await sceneToClient(page, 440, 250);
    await page.mouse.move(centre.x, centre.y);
    await page.mouse.down();
    await page.mouse.move(edge.x, edge.y, { steps: 5 });
    await page.mouse.up();
    // A parameter, the seed and the view options.
    await page.selectOption('#params select[name="arbitration"]', 'priority');
    await page.fill('#seed', '4242');
    await page.press('#seed', 'Enter');
    await page.uncheck('#trails');
    await page.$eval('#fade', (el) => {
      el.value = '0.05';
      el.dispatchEvent(new Event('input', { bubbles: true }));
    });
    const edited = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene()));
    assert.equal(edited.obstacles.length, 1, 'the drawn obstacle is in the scene');
    assert.equal(edited.seed, 4242);
    assert.equal(edited.groups[0].planner.params.arbitration, 'priority');
    assert.deepEqual(edited.view, { trails: false, trail_fade: 0.05 });

    // The address bar catches up after the debounce and holds exactly this scene.
    const expected = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.sceneString()));
    await page.waitForFunction((s) => location.hash === `#s=${s}`, expected, { timeout: 5_000 });
    const url = page.url();
    assert.ok(url.length < 1000, `URL of ${url.length} characters`);
    assert.equal(await page.evaluate(() => history.length), historyBefore, 'replaceState: no new history entries');

    const there = await context.newPage();
    await there.goto(url);
    await there.waitForFunction(() => window.flockpath !== undefined);
    assert.deepEqual(await there.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene())), edited, 'same scene');
    assert.equal(await there.isChecked('#trails'), false, 'the trail checkbox follows the link');
    assert.equal(await there.inputValue('#fade'), '0.05');

    const here = await runFromStart(page);
    const away = await runFromStart(there);
    assert.equal(here.metrics.steps, STEPS);
    assert.deepEqual(away.metrics, here.metrics, 'same metrics after the same steps');
    assert.equal(away.digest, here.digest, 'bit-identical run');
    await frames(there, 2);
    await screenshot(there, 'share-url-roundtrip');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
