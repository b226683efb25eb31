// Activities (issue #15 item 4): a link whose scene carries an activity shows its prompt, asks
// the prediction before the first Play (Play alone does not start the run), and when the goal is
// decided stops the run and shows the check with the measured values, which are the metrics of
// the deciding step as an independent stepping of the same link finds them. The compare page
// checks "pane B arrives before pane A" over its panes the same way.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, frames, openPage, openPath, screenshot } from './helpers.mjs';
import { linkWithActivity } from './activity-helpers.mjs';

const ACTIVITY = {
  prompt: 'Watch the whisker: do the boids ever enter a pillar?',
  prediction: {
    question: 'How many agents end up inside a pillar?',
    choices: ['Many', 'A few', 'None'],
    expected: 2,
  },
  check: {
    steps: 1500,
    conditions: [
      { metric: 'arrived_share', op: '>=', value: 0.9 },
      { metric: 'penetrations_agent_obstacle', op: '=', value: 0 },
    ],
  },
};

const card = '#activity .fp-activity';

test('a linked activity shows its prompt, asks the prediction before Play and checks the goal at the end', { timeout: 120_000 }, async () => {
  const { page, context, errors, close } = await openPage();
  try {
    const value = await linkWithActivity(page, ACTIVITY);
    const there = await context.newPage();
    const thereErrors = [];
    there.on('pageerror', (e) => thereErrors.push(e.message));
    await there.goto(`${page.url().split('#')[0]}#s=${value}`);
    await there.waitForFunction(() => window.flockpath !== undefined);
    await there.locator(card).waitFor();
    assert.equal(await there.locator(`${card} .fp-prompt`).textContent(), ACTIVITY.prompt);
    assert.deepEqual(await there.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene().activity)), ACTIVITY);

    // The page starts paused: the question comes first.
    await frames(there, 5);
    assert.equal(await there.evaluate(() => window.flockpath.isPlaying()), false);
    assert.equal(await there.evaluate(async () => (await window.flockpath.settled(), window.flockpath.metrics().steps)), 0);
    assert.equal(await there.locator(`${card} legend`).textContent(), ACTIVITY.prediction.question);
    assert.deepEqual(await there.locator(`${card} label.fp-choice`).allTextContents(), ACTIVITY.prediction.choices);

    // Play asks instead of playing; locking in an answer without a choice is refused.
    await there.click('#play');
    await frames(there, 5);
    assert.equal(await there.evaluate(() => window.flockpath.isPlaying()), false);
    assert.equal(await there.evaluate(async () => (await window.flockpath.settled(), window.flockpath.metrics().steps)), 0, 'no step ran before the prediction');
    assert.equal(await there.locator(`${card} fieldset.fp-ask`).count(), 1, 'the question is highlighted');
    await there.click(`${card} .fp-lock`);
    assert.equal(await there.evaluate(() => window.flockpath.isPlaying()), false);

    // Answering plays (the Play press asked for it), at the fastest speed.
    await there.$eval('#spf', (el) => {
      el.value = '20';
      el.dispatchEvent(new Event('input', { bubbles: true }));
    });
    await there.getByRole('radio', { name: 'None', exact: true }).check();
    await there.click(`${card} .fp-lock`);
    assert.equal(await there.evaluate(() => window.flockpath.isPlaying()), true);
    assert.equal(await there.locator(`${card} .fp-predicted`).textContent(), 'Your prediction: None');
    assert.match(await there.locator(`${card} .fp-status`).textContent(), /Goal checked until step 1,500/);

    // The goal is decided: the run stops and the card shows the measured values.
    await there.locator(`${card} .fp-status.fp-met`).waitFor({ timeout: 90_000 });
    await there.waitForFunction(() => !window.flockpath.isPlaying());
    const status = await there.locator(`${card} .fp-status`).textContent();
    const step = Number(/Goal met at step ([\d,]+)\./.exec(status)?.[1].replace(/,/g, ''));
    assert.ok(step > 0 && step <= 1500, status);
    const items = await there.locator(`${card} li`).allTextContents();
    assert.equal(await there.locator(`${card} li.fp-pass`).count(), 2, items.join(' | '));

    // An independent stepping of the same scene finds the same deciding step and values.
    const found = await there.evaluate(async (limit) => {
      await window.flockpath.reset();
      for (let k = 1; k <= limit; k += 1) {
        await window.flockpath.step(1);
        const m = window.flockpath.metrics();
        if (m.arrived_share >= 0.9 && m.penetrations_agent_obstacle === 0) return { k, share: m.arrived_share };
      }
      return null;
    }, 1500);
    assert.equal(found?.k, step, 'deciding step');
    const report = await there.evaluate(async () => (await window.flockpath.settled(), window.flockpath.activityReport()));
    assert.deepEqual([report.status, report.step, report.conditions[0].measured[0].value], ['met', step, found.share],
      'stepping one at a time through the page API decides the same check at the same step');
    assert.equal(items[0], `Arrived ≥ 90 % — measured: ${Number((100 * found.share).toFixed(1))} %`);
    assert.equal(items[1], 'Penetrations (agent-steps) = 0 — measured: 0');
    // The card follows the run on animation frames (the steps above ran between them).
    await frames(there, 3);
    const after = await there.locator(`${card} .fp-result`).textContent();
    assert.match(after, /You predicted: None/);
    assert.match(after, /The author's answer: None/);
    await screenshot(there, 'activity-met');

    // Reset: the check starts over, the prediction is kept (Play plays at once).
    await there.click('#reset');
    await there.waitForFunction(() => document.querySelector('#activity .fp-status')?.textContent.includes('now step 0'));
    await there.click('#play');
    assert.equal(await there.evaluate(() => window.flockpath.isPlaying()), true);
    assert.deepEqual(thereErrors, []);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('the compare page checks "pane B arrives before pane A" over its panes', { timeout: 120_000 }, async () => {
  const activity = {
    prompt: 'PSO against Boids on the same influx.',
    prediction: { question: 'Which planner gets 90 % home first?', choices: ['Boids (pane A)', 'PSO (pane B)'] },
    check: { steps: 2000, conditions: [{ before: [{ pane: 1 }, { pane: 0 }], share: 0.9 }] },
  };
  const { page, errors, close } = await openPage();
  let compare = null;
  try {
    const value = await linkWithActivity(page, activity, 'pso-influx');
    compare = await openPath(`compare.html#s=${value}&c=1.boids~pso`, { ready: () => window.flockpathCompare !== undefined });
    const p = compare.page;
    const box = '#activity .fp-activity';
    await p.locator(box).waitFor();
    assert.equal(await p.locator(`${box} .fp-prompt`).textContent(), activity.prompt);
    await frames(p, 5);
    assert.equal(await p.evaluate(() => window.flockpathCompare.isPlaying()), false, 'paused for the prediction');
    await p.click('#play');
    assert.equal(await p.evaluate(async () => (await window.flockpathCompare.settled(), window.flockpathCompare.steps()[0])), 0);
    await p.getByLabel('PSO (pane B)').check();
    await p.click(`${box} .fp-lock`);
    await p.$eval('#spf', (el) => {
      el.value = '20';
      el.dispatchEvent(new Event('input', { bubbles: true }));
    });
    await p.locator(`${box} .fp-status:is(.fp-met, .fp-missed)`).waitFor({ timeout: 90_000 });
    await p.waitForFunction(() => !window.flockpathCompare.isPlaying());
    const item = await p.locator(`${box} li`).textContent();
    // Both panes' reaching steps are shown; the verdict matches them.
    const reached = [...item.matchAll(/pane ([AB])[^:]*: reached at step ([\d,]+)/g)].map((m) => [m[1], Number(m[2].replace(/,/g, ''))]);
    const status = await p.locator(`${box} .fp-status`).textContent();
    const steps = Object.fromEntries(reached);
    assert.ok(steps.A || steps.B, item);
    const met = steps.B !== undefined && (steps.A === undefined || steps.B < steps.A);
    assert.equal(status.startsWith('Goal met'), met, `${status} ${item}`);
    assert.match(await p.locator(`${box} .fp-result`).textContent(), /You predicted: PSO \(pane B\)/);
    await screenshot(p, 'activity-compare');
    assertNoUnexpectedErrors(compare.errors);
    assertNoUnexpectedErrors(errors);
  } finally {
    await compare?.close();
    await close();
  }
});
