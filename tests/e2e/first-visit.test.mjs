// A first-time visitor (fresh profile, the page's own URL, no link) sees the default scene,
// `pillars`, play; after 20 s of simulated time (1,200 steps) what the page says agrees with
// what it shows (issue 23 §3). Regression: `pillars` said "Arrived 100.0 %" with 2 of its 80
// agents inside the goal ring, the rest frozen in a chain reaching 370 px out.
//
// Checked in Chromium, from the page's API and pixels only: the run is the same whether played
// or stepped (digest); an independent recount from `positions()`, `goals()` and `scene()`
// (tests/e2e/recount-helpers.mjs) equals `metrics()` (arrived, waiting, no bodies at rest
// overlapping); the canvas shows the goal ring round `goals()`'s position and an agent's colour
// at every agent's position; the metrics panel's Arrived and Waiting figures say the same.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, frames, openPage, pixelsAt, sceneToCanvasPixel, screenshot, snapshotCanvas } from './helpers.mjs';
import { disagreements, recount } from './recount-helpers.mjs';

/** 20 s of simulated time at 60 steps per second. */
const STEPS = 1200;

const hex = (c) => [1, 3, 5].map((i) => parseInt(c.slice(i, i + 2), 16));
const distance = (a, b) => Math.hypot(...a.map((v, i) => v - b[i]));

/** Whether one of `colours` (a pixel neighbourhood) is nearer to `ink` than a third of the way to `field`. */
const inked = (colours, ink, field) => colours.some((p) => p && distance(p, ink) < distance(ink, field) / 3);

/** Canvas pixels of a 3×3 neighbourhood round each scene point. */
async function neighbourhoods(page, points) {
  const out = [];
  for (const [x, y] of points) {
    const c = await sceneToCanvasPixel(page, x, y);
    for (let dy = -1; dy <= 1; dy += 1) for (let dx = -1; dx <= 1; dx += 1) out.push({ x: c.x + dx, y: c.y + dy });
  }
  return out;
}

test('a first visit: pillars runs 20 s and the page’s numbers, recount and pixels agree', async () => {
  const { page, errors, close } = await openPage({ hash: '' });
  try {
    // What the visitor gets without choosing anything: the first preset, playing.
    const opened = await page.evaluate(async () => (await window.flockpath.settled(), ({
      name: window.flockpath.scene().name,
      menu: document.getElementById('preset').value,
      playing: window.flockpath.isPlaying(),
    })));
    assert.deepEqual(opened, { name: 'pillars', menu: 'pillars', playing: true }, 'the default scene plays');
    await page.waitForFunction(() => window.flockpath.metrics().steps >= 30, null, { timeout: 30_000 });

    // Take over from the frame loop, then step exactly to 1,199 and 1,200.
    const played = await page.evaluate(async (n) => {
      const api = window.flockpath;
      await api.pause();
      const from = api.metrics().steps;
      await api.step(n - 1 - from);
      const before = await api.positions();
      const step = await api.step(1);
      return { from, step, before, after: await api.positions(), digest: api.digest() };
    }, STEPS);
    assert.equal(played.step, STEPS);
    assert.ok(played.from < STEPS - 1, `the page played ${played.from} steps before the test paused it`);

    // The same run from step 0 by the API alone: played or stepped, the state is the same.
    const stepped = await page.evaluate(async (n) => {
      const api = window.flockpath;
      await api.reset();
      await api.step(n);
      return {
        digest: api.digest(),
        positions: await api.positions(),
        goals: api.goals(),
        scene: api.scene(),
        metrics: api.metrics(),
      };
    }, STEPS);
    assert.equal(stepped.digest, played.digest, `played from step ${played.from} on, or stepped from 0: the same run`);
    assert.deepEqual(stepped.positions, played.after);

    const { scene, goals, metrics } = stepped;
    assert.equal(metrics.steps, STEPS);
    const counted = recount(scene, goals, played.before, played.after);
    const goal = goals[scene.groups[0].goal];
    console.log(
      `pillars at step ${STEPS}: ${counted.inside} of ${counted.agents} inside the goal (r ${goal.radius} px at ${goal.x}, ${goal.y}), ` +
        `metrics arrived ${(metrics.arrived_share * 100).toFixed(1)} %, waiting ${metrics.waiting_agents}, ` +
        `${counted.atRest} at rest, ${counted.overlappingAtRest} pairs at rest overlapping, ` +
        `${counted.restingOutsideByGroup.reduce((s, v) => s + v, 0)} at rest outside`,
    );
    assert.deepEqual(disagreements('pillars', counted, metrics), []);
    // The default scene shows a flock that ends inside its goal: most of it by 20 s.
    assert.ok(counted.inside >= 0.9 * counted.withGoal, `${counted.inside} of ${counted.withGoal} inside their goal at 20 s`);

    // Pixels: the frame the canvas shows now is step 1,200.
    await frames(page, 3);
    await snapshotCanvas(page, 'end');
    const [field] = await pixelsAt(page, 'end', [await sceneToCanvasPixel(page, 3, 3)]);
    const inks = scene.groups.map((g) => hex(g.color));
    assert.ok(inks.every((ink) => distance(ink, field) > 60), `the field (${field}) differs from the groups' colours`);
    const radiusOf = scene.groups.map((g) => g.agent_radius ?? 4);
    const groupOf = scene.groups.flatMap((g, k) => Array.from({ length: g.count }, () => k));

    // Every agent: a pixel of its colour at its position.
    const agentPixels = await pixelsAt(page, 'end', await neighbourhoods(page, played.after));
    const unseen = played.after.filter((_, i) => !inked(agentPixels.slice(i * 9, i * 9 + 9), inks[groupOf[i]], field));
    assert.deepEqual(unseen, [], 'agents with no pixel of their colour at their position');

    // The goal ring: 48 points on its circle where no agent stands are drawn in the group's
    // colour; 48 points 12 px outside it where no agent stands, mostly not.
    const clear = (x, y) => played.after.every(([ax, ay], i) => Math.hypot(ax - x, ay - y) > radiusOf[groupOf[i]] + 2);
    const circle = (r) =>
      Array.from({ length: 48 }, (_, k) => [goal.x + r * Math.cos((k / 48) * 2 * Math.PI), goal.y + r * Math.sin((k / 48) * 2 * Math.PI)]).filter(
        ([x, y]) => clear(x, y),
      );
    const ink = inks[0];
    const share = async (points) => {
      const colours = await pixelsAt(page, 'end', await neighbourhoods(page, points));
      return points.filter((_, k) => inked(colours.slice(k * 9, k * 9 + 9), ink, field)).length / points.length;
    };
    const ring = circle(goal.radius);
    const outside = circle(goal.radius + 12);
    const [onRing, offRing] = [await share(ring), await share(outside)];
    console.log(`goal ring: ${ring.length} clear points on it, ${(onRing * 100).toFixed(0)} % inked; ${outside.length} 12 px outside, ${(offRing * 100).toFixed(0)} % inked`);
    assert.ok(ring.length >= 12, `only ${ring.length} points of the ring are clear of agents`);
    assert.ok(onRing >= 0.9, `only ${onRing} of the goal ring is drawn round goals()'s position`);
    assert.ok(offRing <= 0.25, `${offRing} of a circle 12 px outside the goal is inked: the ring is not where goals() says`);

    // The words on the page: the metrics panel shows the same step, arrived and waiting.
    await page.waitForFunction(
      (n) => document.querySelector('#metrics dd[data-key="steps"]')?.textContent === n.toLocaleString('en-US'),
      STEPS,
      { timeout: 10_000 },
    );
    const words = await page.evaluate(() => {
      const cell = (key) => document.querySelector(`#metrics dd[data-key="${key}"]`);
      return { arrived: cell('arrived_share').textContent, waiting: cell('waiting_agents').textContent, waitingShown: !cell('waiting_agents').hidden };
    });
    const percent = Number.parseFloat(words.arrived);
    console.log(`metrics panel: Arrived "${words.arrived}", Waiting "${words.waiting}"`);
    assert.match(words.arrived, /^\d+\.\d %$/);
    assert.equal(Math.round((percent / 100) * counted.agents), counted.inside, `the panel says ${words.arrived}, the recount ${counted.inside} of ${counted.agents}`);
    assert.ok(words.waitingShown, 'the Waiting row shows');
    assert.equal(Number.parseInt(words.waiting.replace(/,/g, ''), 10), metrics.waiting_agents);
    await screenshot(page, 'first-visit-1200');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
