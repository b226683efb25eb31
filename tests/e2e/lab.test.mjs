// The optimizer lab page: it loads (and links with the playground), a 2-D run animates on the
// heat map with the right number of particles, and the 30-run table fills from a Web Worker
// while the page keeps answering clicks; a run can be cancelled.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPath, screenshot } from './helpers.mjs';

const ready = () => window.flockpathLab !== undefined;

/** A digest of the lab canvas's pixels, computed in the page. */
const canvasDigest = (page) =>
  page.evaluate(() => {
    const c = document.getElementById('lab-canvas');
    const data = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let h = 2166136261;
    for (let i = 0; i < data.length; i += 7) h = Math.imul(h ^ data[i], 16777619) >>> 0;
    return h;
  });

test('the lab loads, links to the playground, and a 2-D run animates', async () => {
  const { page, errors, close } = await openPath('lab.html', { ready });
  try {
    assert.equal(await page.getAttribute('#to-playground', 'href'), 'index.html');
    const index = await page.evaluate(() => fetch('index.html').then((r) => r.text()));
    assert.match(index, /href="lab\.html"/, 'the playground links to the lab');

    assert.equal(await page.inputValue('#lab-dim'), '2');
    const population = Number(await page.inputValue('#lab-pop'));
    assert.equal(await page.evaluate(() => window.flockpathLab.particles()), population);
    assert.equal((await page.evaluate(() => window.flockpathLab.positions())).length, 2 * population);
    const before = await canvasDigest(page);
    // Before the first iteration the particles are spread out: each shows as a white disc.
    const white = await page.evaluate(() => {
      const c = document.getElementById('lab-canvas');
      const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      let n = 0;
      for (let i = 0; i < d.length; i += 4) if (d[i] === 255 && d[i + 1] === 255 && d[i + 2] === 255) n += 1;
      return n;
    });
    assert.ok(white >= 10 * population, `${white} particle pixels for ${population} particles`);

    await page.click('#lab-play');
    await page.waitForFunction(() => window.flockpathLab.iteration() >= 20);
    const after = await canvasDigest(page);
    assert.notEqual(after, before, 'the canvas changes as the swarm moves');
    assert.match(await page.textContent('#lab-status'), /iteration \d+\/300/);

    // Step and pause.
    await page.click('#lab-play');
    const paused = await page.evaluate(() => window.flockpathLab.iteration());
    await page.click('#lab-step');
    assert.equal(await page.evaluate(() => window.flockpathLab.iteration()), paused + 1);

    // Frame cost of the 2-D view (render in wasm + putImageData), reported, not asserted.
    await page.click('#lab-reset');
    await page.click('#lab-play');
    await page.waitForFunction(() => window.flockpathLab.renderMs().length >= 100);
    const ms = await page.evaluate(() => window.flockpathLab.renderMs());
    const sorted = [...ms].sort((a, b) => a - b);
    console.log(`lab 2-D frame (render + putImageData, 560×560, ${population} particles): ` +
      `mean ${(ms.reduce((a, b) => a + b, 0) / ms.length).toFixed(3)} ms, median ${sorted[sorted.length >> 1].toFixed(3)} ms, ` +
      `max ${sorted[sorted.length - 1].toFixed(3)} ms over ${ms.length} frames`);

    // More than two dimensions: no picture, the plot still draws.
    await page.fill('#lab-dim', '10');
    await page.dispatchEvent('#lab-dim', 'change');
    assert.equal(await page.isHidden('#lab-canvas'), true);
    assert.equal(await page.isVisible('#lab-no-view'), true);
    await screenshot(page, 'lab-2d');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('30 runs fill the table in a worker while the page answers clicks, and can be cancelled', async () => {
  const { page, errors, close } = await openPath('lab.html', { ready });
  try {
    await page.fill('#lab-dim', '10');
    await page.dispatchEvent('#lab-dim', 'change');
    await page.fill('#lab-iters', '150');
    await page.dispatchEvent('#lab-iters', 'change');
    await page.click('#lab-30');
    // While the worker runs, clicks are handled at once.
    let clicksDuringRun = 0;
    for (let i = 0; i < 5; i += 1) {
      const running = await page.evaluate(() => document.getElementById('lab-progress').value < 1);
      await page.click('#lab-ping', { timeout: 2000 });
      if (running) clicksDuringRun += 1;
    }
    assert.equal(await page.textContent('#lab-ping-count'), '5');
    assert.ok(clicksDuringRun >= 1, 'some clicks landed while the worker was running');
    await page.waitForFunction(() => document.querySelectorAll('#lab-table tbody tr').length === 5, null, { timeout: 120_000 });
    const rows = await page.$$eval('#lab-table tbody tr', (trs) => trs.map((tr) => [...tr.cells].map((c) => c.textContent)));
    assert.deepEqual(rows.map((r) => r[0]), ['gsa', 'igsa', 'pso', 'firefly', 'ga']);
    for (const [name, best, worst, mean, median, runs] of rows) {
      assert.equal(runs, '30', name);
      for (const v of [best, worst, mean, median]) assert.ok(Number.isFinite(Number(v)), `${name}: ${v}`);
      assert.ok(Number(best) <= Number(median) && Number(median) <= Number(worst), `${name}: ${best} ${median} ${worst}`);
    }
    assert.equal(await page.evaluate(() => document.getElementById('lab-progress').value), 1);
    assert.match(await page.textContent('#lab-table-time'), /5 × 30 runs in [\d.]+ s/);

    // Cancel: the worker stops, the buttons come back, the progress stays where it was.
    await page.fill('#lab-iters', '3000');
    await page.dispatchEvent('#lab-iters', 'change');
    await page.click('#lab-30');
    await page.waitForFunction(() => document.getElementById('lab-progress').value > 0, null, { timeout: 60_000 });
    await page.click('#lab-cancel');
    assert.equal(await page.isEnabled('#lab-30'), true);
    assert.equal(await page.textContent('#lab-table-time'), 'cancelled');
    const stopped = await page.evaluate(() => document.getElementById('lab-progress').value);
    await page.waitForTimeout(500);
    assert.equal(await page.evaluate(() => document.getElementById('lab-progress').value), stopped);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
