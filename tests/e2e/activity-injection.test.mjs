// Activity text is the author's, from a link anyone can write: markup in every text field (the
// prompt, the question, each choice, a group's name shown in a condition) must show as the very
// characters, create no element and run no script — on the playground, in the Share dialog's
// form, in <flock-path> (embed.html) and on the compare page.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, frames, openPage, openPath } from './helpers.mjs';

const IMG = '<img src=x onerror="window.__pwned=1">';
const SCRIPT = '<script>window.__pwned=2</script>';
const EVIL = {
  prompt: `${IMG} prompt ${SCRIPT}\n<b>bold?</b> & &amp;`,
  prediction: {
    question: `${SCRIPT}<svg onload="window.__pwned=3"> question`,
    choices: [IMG, SCRIPT, '<a href="javascript:window.__pwned=4">link</a>'],
    expected: 0,
  },
  check: { steps: 5, conditions: [{ metric: 'arrived_share', op: '>=', value: 2, group: 0 }] },
};
const GROUP_NAME = `${IMG}group`;

/** Elements inside `root` an activity card may hold: nothing an author's text could have made. */
const ALLOWED = new Set(['SECTION', 'H3', 'P', 'DIV', 'FIELDSET', 'LEGEND', 'LABEL', 'INPUT', 'SPAN', 'BUTTON', 'UL', 'LI']);

/** Checks the card under `root` (in the page): literal text, only the card's own elements. */
function inspectCard([rootSelector, shadowHost = null]) {
  const host = shadowHost ? document.querySelector(shadowHost) : null;
  const scope = host ? host.shadowRoot : document;
  const cardEl = scope.querySelector(rootSelector);
  return {
    text: cardEl?.textContent ?? null,
    tags: [...(cardEl?.querySelectorAll('*') ?? [])].map((e) => e.tagName),
    pwned: window.__pwned ?? null,
  };
}

function assertLiteral(result, where) {
  assert.notEqual(result.text, null, `${where}: the card is there`);
  for (const text of [IMG, SCRIPT, '<b>bold?</b> & &amp;', EVIL.prediction.choices[2], '<svg onload="window.__pwned=3"> question']) {
    assert.ok(result.text.includes(text), `${where}: shows ${text} literally`);
  }
  const foreign = result.tags.filter((tag) => !ALLOWED.has(tag));
  assert.deepEqual(foreign, [], `${where}: no element made from the text`);
  assert.equal(result.pwned, null, `${where}: no script ran`);
}

test('markup in every activity text field is shown as text on every page that shows it', { timeout: 120_000 }, async () => {
  const { page, context, errors, close } = await openPage();
  let embed = null;
  let compare = null;
  try {
    const value = await page.evaluate(
      async ([a, name]) => {
        await window.flockpath.load('pillars');
        const scene = window.flockpath.scene();
        scene.groups[0].name = name;
        await window.flockpath.load({ ...scene, activity: a });
        return window.flockpath.sceneString();
      },
      [EVIL, GROUP_NAME],
    );
    const before = await page.evaluate(() => document.querySelectorAll('img, script').length);

    // The playground: the card, then the result (after the 5-step check) with the choice and group.
    const there = await context.newPage();
    await there.goto(`${page.url().split('#')[0]}#s=${value}`);
    await there.waitForFunction(() => window.flockpath !== undefined);
    await there.locator('#activity .fp-activity').waitFor();
    // Before the answer: the prompt, the question and every choice.
    assertLiteral(await there.evaluate(inspectCard, ['#activity .fp-activity']), 'playground, question');
    await there.locator('#activity label.fp-choice').first().click();
    await there.click('#activity .fp-lock');
    // The playground meant to play from the start: the answer starts the run.
    assert.equal(await there.evaluate(() => window.flockpath.isPlaying()), true);
    await there.locator('#activity .fp-status.fp-missed').waitFor({ timeout: 30_000 });
    // After the check: the answer given, the author's answer and the group's name.
    const onPlay = await there.evaluate(inspectCard, ['#activity .fp-activity']);
    assert.deepEqual(onPlay.tags.filter((tag) => !ALLOWED.has(tag)), []);
    assert.equal(onPlay.pwned, null);
    assert.ok(onPlay.text.includes(`You predicted: ${IMG}`));
    assert.ok(onPlay.text.includes(`group 1 (${GROUP_NAME})`), 'the group name in the condition, literally');
    assert.ok(onPlay.text.includes(`The author's answer: ${IMG}`));
    assert.equal(await there.evaluate(() => document.querySelectorAll('img, script').length), before);

    // The Share dialog's form holds the same text in its fields (values, not markup).
    await there.click('#menu-toggle').catch(() => {});
    await there.evaluate(() => document.getElementById('share').click());
    assert.equal(await there.inputValue('#activity-prompt'), EVIL.prompt);
    assert.equal(await there.inputValue('#activity-question'), EVIL.prediction.question);
    assert.equal(await there.inputValue('#activity-choices'), EVIL.prediction.choices.join('\n'));
    const options = await there.locator('#activity-expected option').allTextContents();
    assert.deepEqual(options.slice(1), EVIL.prediction.choices);
    assert.equal(await there.evaluate(() => document.querySelectorAll('#share-activity img, #share-activity script').length), 0);
    assert.equal(await there.evaluate(() => window.__pwned ?? null), null);

    // <flock-path> in embed.html.
    embed = await openPath(`embed.html#s=${value}`, { ready: () => document.querySelector('flock-path')?.sim });
    await embed.page.waitForFunction(() => document.querySelector('flock-path').shadowRoot.querySelector('.fp-activity:not([hidden])'));
    await frames(embed.page, 3);
    assertLiteral(await embed.page.evaluate(inspectCard, ['.fp-activity', 'flock-path']), 'embed');

    // The compare page.
    compare = await openPath(`compare.html#s=${value}`, { ready: () => window.flockpathCompare !== undefined });
    await compare.page.locator('#activity .fp-activity').waitFor();
    assertLiteral(await compare.page.evaluate(inspectCard, ['#activity .fp-activity']), 'compare');

    assertNoUnexpectedErrors(errors);
    assertNoUnexpectedErrors(embed.errors);
    assertNoUnexpectedErrors(compare.errors);
  } finally {
    await embed?.close();
    await compare?.close();
    await close();
  }
});
