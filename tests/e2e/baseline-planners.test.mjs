// The baseline planners (ORCA and the social force model) in the playground: chosen in the page's
// planner picker, their parameter sliders appear (generated from the Rust table, in SI units),
// a slider change reaches the scene, and a run brings every agent to the goal without an error.
// The compare page offers them too.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPage, openPath, simpleScene } from './helpers.mjs';

const BASELINES = [
  { name: 'orca', slider: 'pref_speed', unit: 'm/s', value: '1.5' },
  { name: 'social_force', slider: 'relaxation_time', unit: 's', value: '0.4' },
];

test('ORCA and social force are chosen in the panel, run, and every agent arrives', async () => {
  const { page, errors, close } = await openPage();
  try {
    // 30 agents cross 28 m of open field (20 px per metre) to a goal 4 m in radius, which holds
    // them all (arrived means inside it now; social force's body forces keep a crowd loose).
    await page.evaluate(async (scene) => {
      await window.flockpath.pause();
      await window.flockpath.load(scene);
    }, simpleScene({ goals: [{ position: [700, 250], radius: 80 }] }));
    const offered = await page.$$eval('#planner option', (options) => options.map((o) => o.value));
    for (const { name, slider, unit, value } of BASELINES) {
      assert.ok(offered.includes(name), `${name} is in the planner picker: ${offered}`);
      await page.selectOption('#planner', name);
      assert.equal(await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene().groups[0].planner.kind)), name);
      // The sliders come from the planner's table, with their SI units in the help and label.
      const keys = await page.$$eval('#params .param', (rows) => rows.map((r) => r.dataset.key));
      assert.ok(keys.includes(slider) && keys.includes('guidance'), `${name} sliders: ${keys}`);
      const help = await page.getAttribute(`#param-${slider}`, 'title');
      assert.ok(help && help.length > 10, `${slider} has help: ${help}`);
      await page.fill(`#param-${slider}`, value);
      await page.dispatchEvent(`#param-${slider}`, 'change');
      // The slider's change goes to the simulation worker: read once it has answered.
      const set = await page.evaluate(async (key) => (await window.flockpath.settled(), window.flockpath.scene().groups[0].planner.params[key]), slider);
      assert.equal(set, Number(value), `${slider} (${unit}) reached the scene`);

      const result = await page.evaluate(async () => {
        await window.flockpath.reset();
        const shares = [];
        // Social force's last walkers are pressed into the ring by those behind them.
        for (let k = 0; k < 16; k += 1) {
          await window.flockpath.step(250);
          shares.push(window.flockpath.metrics().arrived_share);
        }
        return { shares, metrics: window.flockpath.metrics() };
      });
      assert.equal(result.metrics.arrived_share, 1, `${name}: every agent arrived (${result.shares})`);
      assert.equal(result.metrics.penetrations_agent_obstacle, 0);
      assert.equal(result.metrics.groups[0].planner, name);
      if (name === 'orca') assert.equal(result.metrics.collisions_agent_agent, 0, 'ORCA kept every pair apart');
    }
    // The link carries the planner: reloading it replays the same run.
    const replay = await page.evaluate(async () => {
      const link = window.flockpath.sceneString();
      await window.flockpath.reset();
      await window.flockpath.step(200);
      const first = window.flockpath.digest();
      await window.flockpath.pause();
      await window.flockpath.load(link);
      await window.flockpath.step(200);
      return { first, again: window.flockpath.digest(), kind: window.flockpath.scene().groups[0].planner.kind };
    });
    assert.equal(replay.kind, 'social_force');
    assert.equal(replay.again, replay.first, 'the link replays the same run');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('the compare page runs a baseline beside the scene and offers both', async () => {
  const scene = encodeURIComponent(JSON.stringify(simpleScene({
    groups: [{ ...simpleScene().groups[0], planner: { kind: 'orca', params: {} } }],
  })));
  const { page, errors, close } = await openPath(`compare.html#s=${scene}&c=1.scene~social_force`, {
    ready: () => window.flockpathCompare !== undefined,
  });
  try {
    const panes = await page.evaluate(async () => (await window.flockpathCompare.settled(), window.flockpathCompare.panes()));
    assert.deepEqual(panes.map((p) => p.planner), ['scene', 'social_force']);
    const options = await page.$$eval('.pane[data-pane="B"] select option', (o) => o.map((x) => x.value));
    assert.ok(options.includes('orca') && options.includes('social_force'), `compare offers: ${options}`);
    await page.waitForFunction(() => window.flockpathCompare.steps()[0] > 20);
    const digests = await page.evaluate(async () => (await window.flockpathCompare.settled(), window.flockpathCompare.digests()));
    assert.notEqual(digests[0], digests[1], 'ORCA (the scene) and social force move differently');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
