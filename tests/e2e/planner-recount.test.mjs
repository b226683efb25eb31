// Every planner on the first three scenes (`pillars`, `open-field`, `corridor`), run in
// Chromium to step 1,200 with its default parameters: an independent recount from the page's
// `positions()`, `goals()` and `scene()` (tests/e2e/recount-helpers.mjs) equals `metrics()`
// and no two bodies at rest overlap (issue 23 §3; the native twin is
// tests/arrival_recount.rs). The planners are the page's Planner menu.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPage } from './helpers.mjs';
import { disagreements, loadRunAndCount, presetScene } from './recount-helpers.mjs';

test('every planner on pillars, open-field and corridor: the recount equals metrics() at step 1,200', { timeout: 300_000 }, async () => {
  const { page, errors, close } = await openPage({ hash: '' });
  try {
    const kinds = await page.$$eval('#planner option', (options) => options.map((o) => o.value).filter(Boolean));
    assert.ok(kinds.length >= 7, `the Planner menu lists ${kinds.length} planners`);
    const problems = [];
    const rows = [];
    for (const name of ['pillars', 'open-field', 'corridor']) {
      const base = await presetScene(page, name);
      for (const kind of kinds) {
        const scene = { ...base, groups: base.groups.map((g) => ({ ...g, planner: { kind, params: {} } })) };
        const [counted, read] = await loadRunAndCount(page, scene, 1200);
        assert.ok(read.scene.groups.every((g) => g.planner.kind === kind), `${name} runs ${kind}`);
        problems.push(...disagreements(`${name} with ${kind}`, counted, read.metrics));
        rows.push(
          `${`${name} / ${kind}`.padEnd(26)} ${counted.inside}/${counted.agents} inside (metrics ${Math.round(read.metrics.arrived_share * read.metrics.agents)}), ` +
            `waiting ${read.metrics.waiting_agents}, ${counted.atRest} at rest, ${counted.overlappingAtRest} overlapping pairs at rest`,
        );
      }
    }
    console.log(rows.join('\n'));
    assert.deepEqual(problems, []);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
