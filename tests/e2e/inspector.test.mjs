// Diagnose: clicking an agent with the Select tool opens the inspector with its speed and state,
// and the canvas highlights it.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, frames, openPage, sceneToClient, screenshot, settled, simpleScene } from './helpers.mjs';

test('clicking an agent opens the inspector with its speed', async () => {
  const { page, errors, close } = await openPage();
  try {
    await page.evaluate(async (scene) => {
      await window.flockpath.pause();
      await window.flockpath.load(scene);
      await window.flockpath.step(120);
    }, simpleScene({ obstacles: [{ shape: 'circle', center: [400, 250], radius: 40 }] }));
    assert.equal(await page.isHidden('#inspector'), true, 'no inspector before a click');
    // Pick an agent away from the spawn region, so the click selects nothing else.
    const target = await page.evaluate(async () => {
      const ps = await window.flockpath.positions();
      let best = 0;
      ps.forEach((p, i) => {
        if (p[0] > ps[best][0]) best = i;
      });
      return { id: best, at: ps[best] };
    });
    await page.click('[data-tool="select"]');
    const client = await sceneToClient(page, target.at[0], target.at[1]);
    await page.mouse.click(client.x, client.y);
    await settled(page);
    await frames(page, 2);
    assert.equal(await page.isVisible('#inspector'), true, 'the inspector opens');
    const explained = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.explanation()));
    assert.ok(explained !== null, 'an agent is inspected');
    const picked = await page.evaluate(([x, y]) => window.flockpath.agentAt(x, y, 3), target.at);
    assert.equal(explained.agent, picked, 'the clicked agent is the nearest one');
    assert.match(await page.textContent('#inspector-title'), new RegExp(`Agent ${explained.agent} `));
    const facts = await page.$$eval('#inspector-facts dt, #inspector-facts dd', (els) => els.map((e) => e.textContent));
    const speedAt = facts.indexOf('Speed');
    assert.ok(speedAt >= 0, `facts: ${facts.join(' | ')}`);
    assert.equal(facts[speedAt + 1], `${explained.speed.toFixed(2)} px/step`);
    assert.ok(explained.speed > 0, 'the agent moves');
    const arrows = await page.$$eval('#inspector-vectors li', (lis) => lis.map((li) => li.textContent));
    for (const name of ['separation', 'alignment', 'cohesion', 'seek', 'obstacle avoidance']) {
      assert.ok(arrows.some((a) => a.startsWith(`${name}:`)), `${name} listed in ${arrows.join(' | ')}`);
    }
    await screenshot(page, 'inspector');

    // Clicking empty ground closes it.
    const empty = await sceneToClient(page, 780, 20);
    await page.mouse.click(empty.x, empty.y);
    await settled(page);
    assert.equal(await page.isHidden('#inspector'), true, 'the inspector closes');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
