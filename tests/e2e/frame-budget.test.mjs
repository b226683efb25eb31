// The frame budget: when Speed asks for more steps per frame than fit in a frame, the page runs
// fewer (never a frame of 20 big steps), says so beside the Speed slider, and the run is the
// same run. The crowd is chosen so that 20 steps can never fit in the budget: 20,000 Boids
// agents on the 800×500 px field have ~400 neighbours each, so 20 steps are some 160 million
// neighbour visits, far beyond 10 ms on any machine (no timing is asserted: only that fewer than
// the requested steps ran, which is what the readout reports). Showing the readout moves nothing.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, frames, loadPaused, openPage, simpleScene } from './helpers.mjs';

const BIG = simpleScene({
  // Small bodies: the spawn keeps bodies apart, and 20,000 of radius 4 px do not fit the field.
  // No goal: 20,000 small bodies parking round a goal in their midst would be over the jam limit
  // (src/sim/cost.rs); wandering, they are as crowded and within the ordinary one.
  groups: [{ ...simpleScene().groups[0], count: 20000, agent_radius: 1.5, goal: null, spawn: { min: [10, 10], max: [790, 490] } }],
});

/** Sets the Speed slider as a user would (an `input` event). */
async function setSpeed(page, value) {
  await page.evaluate((v) => {
    const spf = document.getElementById('spf');
    spf.value = String(v);
    spf.dispatchEvent(new Event('input', { bubbles: true }));
  }, value);
}

const readout = (page) =>
  page.evaluate(() => {
    const el = document.getElementById('spf-actual');
    return {
      limited: el.dataset.limited,
      text: el.textContent,
      visible: getComputedStyle(el).visibility !== 'hidden',
    };
  });

test('a crowd too big for the requested speed runs fewer steps per frame and says so', async () => {
  const { page, errors, close } = await openPage();
  try {
    assert.deepEqual(await readout(page), { limited: 'false', text: '', visible: false }, 'small scene: nothing to say');
    await loadPaused(page, BIG);
    const canvasBox = () => page.evaluate(() => JSON.stringify(document.getElementById('scene-canvas').getBoundingClientRect()));
    const boxBefore = await canvasBox();
    await setSpeed(page, 20);
    assert.equal(await page.textContent('#spf-value'), '20×');
    const before = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.timeline().step));
    await page.evaluate(() => window.flockpath.play());
    await page.waitForFunction(() => document.getElementById('spf-actual').dataset.limited === 'true', null, {
      timeout: 60_000,
    });
    const shown = await readout(page);
    assert.ok(shown.visible, 'the readout is visible');
    const match = /^→ (\d+(?:\.\d)?)× \(frame budget\)$/.exec(shown.text);
    assert.ok(match, `readout text: ${shown.text}`);
    assert.ok(Number(match[1]) < 20, `fewer than the 20 requested steps per frame: ${shown.text}`);
    assert.match(await page.getAttribute('#spf-actual', 'title'), /Speed asks for 20 steps per frame/);
    assert.equal(await canvasBox(), boxBefore, 'showing the readout does not move the canvas');

    // Steps per painted frame, counted over a few frames: fewer than asked, but the run goes on.
    const counted = await page.evaluate(
      () =>
        new Promise((resolve) => {
          const start = window.flockpath.timeline().step;
          let left = 4;
          const tick = () => {
            left -= 1;
            if (left > 0) requestAnimationFrame(tick);
            else resolve({ steps: window.flockpath.timeline().step - start });
          };
          requestAnimationFrame(tick);
        }),
    );
    assert.ok(counted.steps > 0, 'the run advances');
    assert.ok(counted.steps < 4 * 20, `ran ${counted.steps} steps in 4 frames`);

    // The frames ran the same fixed steps: pausing and replaying from the start gives the same run.
    await page.evaluate(() => window.flockpath.pause());
    const played = await page.evaluate(async () => (await window.flockpath.settled(), ({ step: window.flockpath.timeline().step, digest: window.flockpath.digest() })));
    assert.ok(played.step > before);
    const replayed = await page.evaluate(async (n) => {
      await window.flockpath.reset();
      await window.flockpath.step(n);
      return window.flockpath.digest();
    }, played.step);
    assert.equal(replayed, played.digest, 'budgeted frames step the same run as step(n)');

    // At 1× nothing can be cut (a frame always runs its first step): the readout goes away.
    await setSpeed(page, 1);
    await page.evaluate(() => window.flockpath.play());
    await page.waitForFunction(() => document.getElementById('spf-actual').dataset.limited === 'false', null, {
      timeout: 60_000,
    });
    await frames(page, 2);
    assert.equal((await readout(page)).visible, false);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
