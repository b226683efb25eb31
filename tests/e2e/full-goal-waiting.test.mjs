// A goal too small for its group fills, and the rest wait outside it (issue 23 §1, §3): in
// Chromium, 60 Boids of `open-field` heading for a goal shrunk to 20 px (about 13 places)
// run to step 2,400; the recount from the page's `positions()` and `goals()`
// (tests/e2e/recount-helpers.mjs) equals `metrics()`, the agents counted waiting are no more
// than those at rest outside the goal, and no two bodies at rest overlap.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPage } from './helpers.mjs';
import { disagreements, loadRunAndCount, presetScene } from './recount-helpers.mjs';

test('a goal too small for its group: it fills, and the agents counted waiting stand at rest outside it', { timeout: 120_000 }, async () => {
  const { page, errors, close } = await openPage({ hash: '' });
  try {
    // 60 Boids for a goal of radius 20 px, which holds about 13 bodies of radius 4 px.
    const base = await presetScene(page, 'open-field');
    const scene = { ...base, goals: base.goals.map((g, k) => (k === base.groups[0].goal ? { ...g, radius: 20 } : g)) };
    const [counted, read] = await loadRunAndCount(page, scene, 2400);
    const { metrics } = read;
    const restingOutside = counted.restingOutsideByGroup.reduce((s, v) => s + v, 0);
    console.log(
      `open-field, goal r 20 px, step 2400: ${counted.inside}/${counted.agents} inside, ${metrics.waiting_agents} waiting ` +
        `(${restingOutside} at rest outside), ${counted.overlappingAtRest} overlapping pairs at rest`,
    );
    assert.deepEqual(disagreements('open-field, small goal', counted, metrics), []);
    assert.ok(metrics.waiting_agents > 0, 'a full goal leaves agents waiting');
    assert.ok(counted.inside + metrics.waiting_agents <= counted.agents, 'no agent is both inside and waiting');
    assert.ok(counted.inside < counted.agents, 'the goal cannot hold the whole group');
    assert.equal(Math.round(metrics.waiting_share * metrics.agents), metrics.waiting_agents);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
