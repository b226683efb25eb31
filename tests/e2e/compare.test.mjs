// The compare page: a comparison URL opens with its panes, both panes animate in lockstep, the
// metrics table has a column per pane, the link reopens the same comparison, bad links give a
// message, the summary downloads as CSV, and the playground links to the page.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import { assertNoUnexpectedErrors, frames, openPage, openPath, simpleScene } from './helpers.mjs';

const ready = () => window.flockpathCompare !== undefined;

/** A cheap fingerprint of each pane canvas's pixels. */
const paneHashes = (page) =>
  page.$$eval('.pane canvas', (canvases) =>
    canvases.map((c) => {
      const data = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      let h = 0;
      for (let i = 0; i < data.length; i += 7) h = (h * 31 + data[i]) >>> 0;
      return h;
    }));

test('a comparison URL opens both panes, which animate in lockstep with one table', async () => {
  const scene = encodeURIComponent(JSON.stringify(simpleScene()));
  const { page, errors, close } = await openPath(`compare.html#s=${scene}&c=1.scene~pso`, { ready });
  try {
    assert.equal(await page.$$eval('.pane', (p) => p.length), 2);
    // Each pane's canvas points to its live description: the scene's paragraph and its pane's.
    await page.waitForFunction(() => document.querySelectorAll('#compare-description p[data-pane]').length === 2);
    const described = await page.$$eval('.pane canvas', (canvases) => canvases.map((c) =>
      (c.getAttribute('aria-describedby') ?? '').split(/\s+/).map((id) => document.getElementById(id)?.textContent ?? `missing #${id}`)));
    assert.equal(described.length, 2);
    for (const [i, [sceneWords, paneWords]] of described.entries()) {
      assert.match(sceneWords, /pane/i, `pane ${i}: the scene's paragraph (${sceneWords})`);
      assert.match(paneWords, new RegExp(`^Pane ${'AB'[i]}\\b`), `pane ${i}: its own paragraph (${paneWords})`);
    }
    const panes = await page.evaluate(async () => (await window.flockpathCompare.settled(), window.flockpathCompare.panes()));
    assert.deepEqual(panes.map((p) => p.planner), ['scene', 'pso']);
    await page.waitForFunction(() => window.flockpathCompare.steps()[0] > 20);
    const first = await paneHashes(page);
    await page.waitForFunction((n) => window.flockpathCompare.steps()[0] > n + 30,
      (await page.evaluate(async () => (await window.flockpathCompare.settled(), window.flockpathCompare.steps()[0]))));
    await frames(page, 2);
    const second = await paneHashes(page);
    assert.notEqual(first[0], second[0], 'pane A animates');
    assert.notEqual(first[1], second[1], 'pane B animates');

    await page.click('#play');
    const steps = await page.evaluate(async () => (await window.flockpathCompare.settled(), window.flockpathCompare.steps()));
    assert.equal(steps[0], steps[1], 'the panes step in lockstep');
    await page.click('#step');
    assert.deepEqual(await page.evaluate(async () => (await window.flockpathCompare.settled(), window.flockpathCompare.steps())), [steps[0] + 1, steps[1] + 1]);

    await frames(page, 2);
    const header = await page.$$eval('#metrics-table thead th', (ths) => ths.map((t) => t.textContent));
    assert.deepEqual(header, ['', 'A', 'B'], 'one column per pane');
    const row = await page.$$eval('#metrics-table tr[data-key="steps"] td', (tds) => tds.map((t) => t.textContent));
    // The row's name is its heading (th scope=row); the cells are the panes' values.
    assert.deepEqual(row, [String(steps[0] + 1), String(steps[0] + 1)]);
    assert.equal(await page.$$eval('.plot canvas', (c) => c.length), 5, 'five overlaid plots');
    const series = await page.evaluate(async () => (await window.flockpathCompare.settled(), window.flockpathCompare.series()));
    assert.equal(series.panes.length, 2);
    assert.notEqual(series.panes[0].color, series.panes[1].color);

    // Pane A runs the scene's planners: the playground's run, digest for digest.
    const digests = await page.evaluate(async () => (await window.flockpathCompare.settled(), window.flockpathCompare.digests()));

    // The summary CSV: one row per pane.
    const [download] = await Promise.all([page.waitForEvent('download'), page.click('#export-csv')]);
    const csv = await readFile(await download.path(), 'utf8');
    const lines = csv.trim().split('\n');
    assert.equal(lines.length, 3, csv);
    assert.match(lines[0], /^pane,planners,steps,agents,arrived_share/);
    assert.match(lines[1], /^A,/);
    assert.match(lines[2], /^B,PSO/);

    // The link reopens the same comparison.
    const link = await page.evaluate(async () => (await window.flockpathCompare.settled(), window.flockpathCompare.link()));
    const spec = await page.evaluate(async () => (await window.flockpathCompare.settled(), window.flockpathCompare.specString()));
    assert.ok(link.includes(`c=${spec}`), link);
    await page.goto('about:blank');
    await page.goto(link);
    await page.waitForFunction(ready);
    await page.evaluate(async () => {
      await window.flockpathCompare.pause();
      await window.flockpathCompare.reset();
    });
    assert.equal(await page.evaluate(async () => (await window.flockpathCompare.settled(), window.flockpathCompare.specString())), spec);
    await page.evaluate((n) => window.flockpathCompare.step(n), steps[0] + 1);
    assert.deepEqual(await page.evaluate(async () => (await window.flockpathCompare.settled(), window.flockpathCompare.digests())), digests, 'same runs from the link');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('pane A equals the playground run; panes can be added, changed and removed', async () => {
  const play = await openPage();
  let playgroundDigest;
  let compareHref;
  try {
    playgroundDigest = await play.page.evaluate(async (scene) => {
      await window.flockpath.pause();
      await window.flockpath.load(scene);
      await window.flockpath.step(90);
      return window.flockpath.digest();
    }, simpleScene({ seed: 5 }));
    await frames(play.page, 1);
    await play.page.waitForFunction(() => document.getElementById('compare-link').href.includes('compare.html#s='));
    compareHref = await play.page.$eval('#compare-link', (a) => a.getAttribute('href'));
    assertNoUnexpectedErrors(play.errors);
  } finally {
    await play.close();
  }
  const { page, errors, close } = await openPath(compareHref, { ready });
  try {
    await page.evaluate(async () => {
      await window.flockpathCompare.pause();
      await window.flockpathCompare.reset();
      await window.flockpathCompare.step(90);
    });
    const digests = await page.evaluate(async () => (await window.flockpathCompare.settled(), window.flockpathCompare.digests()));
    assert.equal(digests[0], playgroundDigest, 'pane A (the scene as linked) is the playground run');

    await page.click('#add-pane');
    await page.waitForFunction(() => document.querySelectorAll('.pane').length === 3);
    await page.selectOption('.pane[data-pane="C"] select', 'firefly');
    await frames(page, 2);
    const panes = await page.evaluate(async () => (await window.flockpathCompare.settled(), window.flockpathCompare.panes()));
    assert.deepEqual(panes.map((p) => p.planner), ['scene', 'pso', 'firefly']);
    assert.match(await page.evaluate(async () => (await window.flockpathCompare.settled(), window.flockpathCompare.specString())), /^1\.scene~pso\(.*\)~firefly\(/);
    await page.click('.pane[data-pane="B"] .pane-head button');
    await page.waitForFunction(() => document.querySelectorAll('.pane').length === 2);
    // The table follows on the next metrics refresh, not with the panes.
    await page.waitForFunction(() => document.querySelectorAll('#metrics-table thead th').length <= 3, null, { timeout: 10_000 });
    assert.equal(await page.$$eval('#metrics-table thead th', (t) => t.length), 3);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('a link that changes the scene and the spec together applies both (one group → two)', async () => {
  const { page, errors, close } = await openPath(`compare.html#s=${encodeURIComponent(JSON.stringify(simpleScene()))}&c=1.scene~firefly`, { ready });
  try {
    assert.deepEqual(await page.evaluate(async () => (await window.flockpathCompare.settled(), window.flockpathCompare.panes().map((p) => [p.planner, p.groups.length]))), [['scene', 1], ['firefly', 1]]);
    // The new spec sets group 2: checked against the old one-group scene alone it is refused,
    // and the new scene alone would keep the old spec. Only both together are the link.
    const two = simpleScene({ seed: 9 });
    two.groups.push({ ...two.groups[0], name: 'right', spawn: { min: [500, 100], max: [560, 160] } });
    await page.evaluate((scene) => {
      location.hash = `s=${encodeURIComponent(JSON.stringify(scene))}&c=1.scene~1=pso;2=boids`;
    }, two);
    await page.waitForFunction(() => window.flockpathCompare.panes()[0]?.groups.length === 2);
    const panes = await page.evaluate(async () => (await window.flockpathCompare.settled(), window.flockpathCompare.panes()));
    assert.deepEqual(panes.map((p) => p.per_group), [false, true]);
    assert.deepEqual(panes[1].groups.map((g) => g.planner), ['pso', 'boids']);
    assert.equal(await page.evaluate(() => document.getElementById('banner').hidden), true, 'no refusal shown');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('a bad comparison in the link gives a message and the default comparison', async () => {
  const { page, errors, close } = await openPath('compare.html#c=1.boids~teleport', { ready });
  try {
    const banner = await page.textContent('#banner-text');
    assert.match(banner, /unknown planner "teleport"/);
    assert.equal(await page.$$eval('.pane', (p) => p.length), 2, 'the default comparison runs');
    await assert.rejects(page.evaluate(() => window.flockpathCompare.setSpec('7.boids')), /version/);
    assert.equal(await page.$$eval('.pane', (p) => p.length), 2, 'a refused spec changes nothing');
    assertNoUnexpectedErrors(errors, [/the comparison in the link/i, /version/]);
  } finally {
    await close();
  }
});
