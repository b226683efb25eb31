// The activity card and its authoring dialog pass axe-core (no serious or critical violation) on
// the playground: the card with its question (radios in a fieldset with a legend), the result, and
// the Activity dialog with its condition rows.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPage, seriousViolations } from './helpers.mjs';
import { linkWithActivity } from './activity-helpers.mjs';

test('axe: the activity card, its result and the Activity dialog have no serious or critical violation', { timeout: 120_000 }, async () => {
  const activity = {
    prompt: 'Do the boids enter a pillar?',
    prediction: { question: 'How many enter one?', choices: ['Many', 'A few', 'None'], expected: 2 },
    check: { steps: 30, conditions: [{ metric: 'penetrations_agent_obstacle', op: '=', value: 0 }, { metric: 'arrived_share', op: '>=', value: 1, group: 0 }] },
  };
  const { page, context, errors, close } = await openPage();
  try {
    const value = await linkWithActivity(page, activity);
    const there = await context.newPage();
    await there.goto(`${page.url().split('#')[0]}#s=${value}`);
    await there.waitForFunction(() => window.flockpath !== undefined);
    await there.locator('#activity .fp-activity legend').waitFor();
    assert.deepEqual(await seriousViolations(there), [], 'with the question');
    await there.getByRole('radio', { name: 'None', exact: true }).check();
    await there.click('#activity .fp-lock');
    await there.locator('#activity .fp-status.fp-missed').waitFor({ timeout: 60_000 });
    assert.deepEqual(await seriousViolations(there), [], 'with the result');
    await there.evaluate(() => document.getElementById('share').click());
    await there.click('#share-activity-open');
    await there.locator('#activity-dialog[open] .activity-condition').first().waitFor();
    assert.deepEqual(await seriousViolations(there), [], 'the Activity dialog');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
