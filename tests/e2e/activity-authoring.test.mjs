// The Share dialog's activity form ("Activity…" beside "Copy link" opens it): a teacher writes a
// prompt, a question with choices and a goal;
// "Put the activity in the link" stores it in the scene, the dialog's link carries it, and that
// link opens the same scene (same fragment, same activity) with the card. A refused activity
// says which field and limit, and changes nothing.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPage, screenshot, settled } from './helpers.mjs';

async function openShare(page) {
  await page.evaluate(() => document.getElementById('share').click());
  await page.locator('#share-dialog[open]').waitFor();
}

test('the authoring form writes an activity into a link that round-trips', { timeout: 90_000 }, async () => {
  const { page, context, errors, close } = await openPage();
  try {
    await page.evaluate(() => window.flockpath.load('two-groups-swap'));
    await openShare(page);
    await page.click('#share-activity-open');
    await page.locator('#activity-dialog[open]').waitFor();
    assert.equal(await page.inputValue('#activity-prompt'), '', 'empty while the scene has no activity');

    const prompt = 'Two groups swap sides.\nWhich one is home first?';
    await page.fill('#activity-prompt', prompt);
    await page.fill('#activity-question', 'Which group arrives first?');
    await page.fill('#activity-choices', 'The left group\nThe right group\nA tie');
    await page.selectOption('#activity-expected', { label: 'A tie' });
    await page.fill('#activity-steps', '900');
    // A metric condition: arrived ≥ 0.8 for the whole run (the defaults, then edited)…
    await page.click('#activity-add-condition');
    const first = page.locator('.activity-condition').nth(0);
    await first.locator('.activity-value').fill('0.8');
    // …and "group 2 arrives before group 1" at half home.
    await page.click('#activity-add-condition');
    const second = page.locator('.activity-condition').nth(1);
    await second.locator('.activity-kind').selectOption('before');
    await second.locator('.activity-first').selectOption('group:1');
    await second.locator('.activity-second').selectOption('group:0');
    await second.locator('.activity-share').fill('0.5');
    await screenshot(page, 'activity-authoring');
    await page.click('#activity-apply');
    await settled(page);
    assert.equal(await page.textContent('#activity-form-status'), 'The activity is in the link (Share dialog).');

    const expected = {
      prompt,
      prediction: { question: 'Which group arrives first?', choices: ['The left group', 'The right group', 'A tie'], expected: 2 },
      check: {
        steps: 900,
        conditions: [
          { metric: 'arrived_share', op: '>=', value: 0.8 },
          { before: [{ group: 1 }, { group: 0 }], share: 0.5 },
        ],
      },
    };
    assert.deepEqual(await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene().activity)), expected);
    // The card on this page follows at once.
    assert.equal(await page.locator('#activity .fp-prompt').textContent(), prompt);

    // The Share dialog's link holds it; opened elsewhere it gives the same scene and the card.
    await page.click('#activity-dialog .row-buttons.end button');
    await page.locator('#activity-dialog:not([open])').waitFor({ state: 'attached' });
    assert.equal(await page.locator('#share-dialog[open]').count(), 1, 'back in the Share dialog');
    const link = await page.inputValue('#share-link');
    const sceneString = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.sceneString()));
    assert.ok(link.endsWith(`#s=${sceneString}`), link);
    const there = await context.newPage();
    await there.goto(link);
    await there.waitForFunction(() => window.flockpath !== undefined);
    assert.deepEqual(await there.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene().activity)), expected);
    assert.equal(await there.evaluate(async () => (await window.flockpath.settled(), window.flockpath.sceneString())), sceneString);
    assert.equal(await there.locator('#activity .fp-prompt').textContent(), prompt);
    assert.deepEqual(await there.locator('#activity label.fp-choice').allTextContents(), expected.prediction.choices);
    // The form there is filled from the link's activity.
    await openShare(there);
    await there.click('#share-activity-open');
    assert.equal(await there.inputValue('#activity-prompt'), prompt);
    assert.equal(await there.locator('.activity-condition').count(), 2);
    assert.equal(await there.locator('.activity-condition').nth(1).locator('.activity-first').inputValue(), 'group:1');

    // Seven choices: refused with the field and its limit; the scene keeps its activity.
    await page.click('#share-activity-open');
    await page.fill('#activity-choices', 'a\nb\nc\nd\ne\nf\ng');
    await page.click('#activity-apply');
    await settled(page);
    const refusal = await page.textContent('#activity-form-status');
    assert.match(refusal, /activity\.prediction\.choices is a list of 7; allowed: 2…6 choices/);
    assert.deepEqual(await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene().activity)), expected);

    // Removing it: the link has no activity, and is the scene's link without one.
    await page.click('#activity-clear');
    await settled(page);
    assert.equal(await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene().activity)), undefined);
    assert.equal(await page.locator('#activity .fp-activity').isHidden(), true);
    const plain = await page.evaluate(async () => {
      const s = window.flockpath.sceneString();
      await window.flockpath.load('two-groups-swap');
      return s === window.flockpath.sceneString();
    });
    assert.equal(plain, true, 'without the activity the link is the preset link again');
    assertNoUnexpectedErrors(errors, [/activity\.prediction\.choices/]);
  } finally {
    await close();
  }
});
