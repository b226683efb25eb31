// The course notes' three activities (one per planner family: Boids steering, the PSO swarm,
// IGSA group paths), each an iframe of embed.html: every one shows its card with the prompt and
// the question before any step runs, on a scene of the right planner; answering one and playing it
// to its end shows the check with the measured values.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPath, screenshot } from './helpers.mjs';

const FRAMES = [
  ['activity-boids', 'boids', /whisker/],
  ['activity-pso', 'pso', /probability/],
  ['activity-igsa', 'igsa', /gravitational search/],
];

test('the course notes show three activity cards, one per planner family', { timeout: 180_000 }, async () => {
  const { page, errors, close } = await openPath('examples/course-notes.html', {
    ready: () => document.getElementById('activity-igsa') !== null,
    viewport: { width: 1000, height: 900 },
  });
  try {
    for (const [id, planner, words] of FRAMES) {
      await page.locator(`#${id}`).scrollIntoViewIfNeeded();
      const handle = await page.locator(`#${id}`).elementHandle();
      const inner = await handle.contentFrame();
      await inner.waitForFunction(() => document.querySelector('flock-path')?.sim, null, { timeout: 60_000 });
      await inner.waitForFunction(() => document.querySelector('flock-path').shadowRoot.querySelector('.fp-activity:not([hidden])'));
      const seen = await inner.evaluate(() => {
        const el = document.querySelector('flock-path');
        const card = el.shadowRoot.querySelector('.fp-activity');
        return {
          planners: [...new Set(el.scene().groups.map((g) => g.planner.kind))],
          prompt: card.querySelector('.fp-prompt').textContent,
          question: card.querySelector('legend')?.textContent ?? null,
          choices: card.querySelectorAll('label.fp-choice').length,
          visible: card.getBoundingClientRect().height > 40,
          steps: el.steps,
          playing: el.playing,
        };
      });
      assert.deepEqual(seen.planners, [planner], id);
      assert.match(seen.prompt, words, id);
      assert.ok(seen.question && seen.choices >= 2 && seen.visible, `${id}: ${JSON.stringify(seen)}`);
      assert.equal(seen.steps, 0, `${id}: nothing runs before the prediction`);
      assert.equal(seen.playing, false, id);
    }

    // The Boids activity played to its end: the whisker keeps everyone out, the goal is met.
    const inner = await (await page.locator('#activity-boids').elementHandle()).contentFrame();
    await inner.evaluate(() => {
      const root = document.querySelector('flock-path').shadowRoot;
      root.querySelectorAll('label.fp-choice input')[2].click();
      root.querySelector('.fp-lock').click();
      document.querySelector('flock-path').play();
    });
    await inner.waitForFunction(() => document.querySelector('flock-path').shadowRoot.querySelector('.fp-status.fp-met, .fp-status.fp-missed'), null, { timeout: 120_000 });
    const result = await inner.evaluate(() => document.querySelector('flock-path').shadowRoot.querySelector('.fp-result').textContent);
    assert.match(result, /Goal met at step [\d,]+\./);
    assert.match(result, /Penetrations \(agent-steps\) = 0 — measured: 0/);
    assert.match(result, /You predicted: None: the whisker turns every agent in time/);
    await page.locator('#activity-boids').scrollIntoViewIfNeeded();
    await screenshot(page, 'activity-course-notes');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
