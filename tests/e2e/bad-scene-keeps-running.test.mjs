// Bad input never stops the show: a garbled link, a non-number radius and an obstacle over the goal
// each give a readable message in the page while the previous scene keeps running unchanged.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, bannerText, openPage, screenshot, simpleScene } from './helpers.mjs';

/** Waits until the step count passes `than` (the frame loop is running). */
async function stepsIncrease(page, than) {
  await page.waitForFunction((n) => window.flockpath.metrics().steps > n, than, { timeout: 20_000 });
}

/** Calls load() in the page; returns the thrown message (or null if it loaded). */
async function tryLoad(page, input) {
  return page.evaluate((value) => {
    try {
      window.flockpath.load(value);
      return null;
    } catch (error) {
      return error instanceof Error ? error.message : String(error);
    }
  }, input);
}

test('a garbled #s= link shows a message and the default preset runs', async () => {
  const { page, errors, close } = await openPage({ hash: '#s=1.this-is-not@a*scene' });
  try {
    const text = await bannerText(page);
    assert.ok(text, 'a message is shown');
    assert.match(text, /scene in the link could not be loaded/i);
    assert.match(text, /base64|damaged|truncated|cannot read/);
    const defaultPreset = await page.$eval('#preset option', (o) => o.value);
    assert.equal((await page.evaluate(() => window.flockpath.scene())).name, defaultPreset);
    assert.equal(await page.evaluate(() => window.flockpath.isPlaying()), true);
    await stepsIncrease(page, 10);
    await page.click('#banner-close');
    assert.equal(await bannerText(page), null, 'the message can be dismissed');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('refused scenes keep the previous scene running unchanged', async () => {
  const { page, errors, close } = await openPage();
  try {
    const good = simpleScene({ name: 'good' });
    await page.evaluate((scene) => window.flockpath.load(scene), good);
    const loaded = await page.evaluate(() => window.flockpath.scene());
    await stepsIncrease(page, 5);

    const nanRadius = simpleScene({ obstacles: [{ shape: 'circle', center: [400, 100], radius: 'NaN' }] });
    const overGoal = simpleScene({ obstacles: [{ shape: 'circle', center: [700, 250], radius: 60 }] });
    const cases = [
      ['a radius that is not a number', nanRadius, /radius|invalid type|number/i],
      ['an obstacle over the goal', overGoal, /goal 1 is inside obstacle 1/],
      ['a garbled fragment', '#s=1.%%%garbled', /scene string|base64|cannot read/i],
      ['a fragment of an unknown version', '9.abcdef', /version/],
      ['broken JSON text', '{"width": 800, "height":', /cannot read the scene/],
    ];
    for (const [what, input, expected] of cases) {
      const stepsBefore = await page.evaluate(() => window.flockpath.metrics().steps);
      const message = await tryLoad(page, input);
      assert.ok(message, `${what}: load() throws`);
      assert.match(message, expected, `${what}: readable message`);
      const shown = await bannerText(page);
      assert.ok(shown && shown.toLowerCase().includes(message.toLowerCase()),
        `${what}: the page shows "${message}" (banner: ${shown})`);
      assert.deepEqual(await page.evaluate(() => window.flockpath.scene()), loaded, `${what}: scene unchanged`);
      await stepsIncrease(page, stepsBefore);
    }
    // A link pasted into the address bar of the running page: same rules.
    await page.click('#banner-close');
    const stepsBefore = await page.evaluate(() => window.flockpath.metrics().steps);
    await page.evaluate(() => {
      location.hash = 's=1.garbled~link';
    });
    await page.waitForFunction(() => !document.getElementById('banner').hidden);
    assert.match(await bannerText(page), /scene in the link could not be loaded.*previous scene keeps running/i);
    assert.deepEqual(await page.evaluate(() => window.flockpath.scene()), loaded, 'link: scene unchanged');
    await stepsIncrease(page, stepsBefore);

    // A good link loads.
    const goodLink = await page.evaluate(() => window.flockpath.sceneString());
    await page.evaluate((value) => window.flockpath.load(value), simpleScene({ name: 'other' }));
    // Wait for the address bar to follow the load (it is rewritten 300 ms after a change): setting
    // the hash to the value it already holds fires no hashchange, and a write still pending from
    // before the garbled link could have put the good link back into the address bar.
    await page.waitForFunction(() => location.hash === `#s=${window.flockpath.sceneString()}`);
    await page.evaluate((value) => {
      location.hash = `s=${value}`;
    }, goodLink);
    await page.waitForFunction(() => window.flockpath.scene().name === 'good');
    await screenshot(page, 'bad-scene-keeps-running');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
