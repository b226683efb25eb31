// The Validation page: a small subset of the suite runs in a Web Worker, the table fills with
// pass/fail cells, the fundamental-diagram and sweep plots are drawn, a test's link opens its scene in the
// playground, and a run can be cancelled. The playground's menu links to the page.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPath, screenshot, waitReady } from './helpers.mjs';

const ready = () => window.flockpathValidation !== undefined;

/** Leaves only `values` checked among the checkboxes of `box`. */
async function pick(page, box, values) {
  await page.evaluate(
    ({ box, values }) => {
      for (const input of document.querySelectorAll(`#${box} input`)) input.checked = values.includes(input.value);
    },
    { box, values },
  );
}

test('a subset runs in a worker, the table shows pass/fail, a link opens the scene', async () => {
  const { page, errors, close } = await openPath('validation.html', { ready });
  try {
    assert.equal(await page.getAttribute('#to-playground', 'href'), 'index.html');
    const index = await page.evaluate(() => fetch('index.html').then((r) => r.text()));
    assert.match(index, /href="validation\.html"/, 'the playground links to the page');
    const planners = await page.$$eval('#val-planners input', (inputs) => inputs.map((i) => i.value));
    for (const name of ['boids', 'pso', 'firefly', 'forces', 'igsa']) assert.ok(planners.includes(name), name);

    await pick(page, 'val-planners', ['boids', 'forces']);
    await pick(page, 'val-tests', ['t1-free-walking', 'juelich-head-on', 't8-speed-sweep']);
    await page.click('#val-run');
    assert.equal(await page.isDisabled('#val-cancel'), false, 'Cancel is offered while running');
    await page.waitForFunction(() => document.querySelector('#val-summary').textContent !== '', null, { timeout: 120_000 });

    const rows = await page.$$eval('#val-table tbody tr', (trs) =>
      trs.map((tr) => ({
        test: tr.dataset.test,
        planner: tr.dataset.planner,
        result: tr.lastElementChild.textContent,
        cls: tr.lastElementChild.className,
        href: tr.querySelector('a.scene-link')?.getAttribute('href') ?? '',
        measured: tr.children[2].textContent,
      })),
    );
    assert.equal(rows.length, 6, JSON.stringify(rows));
    for (const r of rows) {
      assert.ok(['pass', 'fail'].includes(r.result) && r.cls === r.result, JSON.stringify(r));
      assert.match(r.href, /^index\.html#s=/, 'each test links to its scene');
      assert.ok(r.measured.length > 0);
    }
    // One walker alone in a corridor with Boids keeps its desired speed (the T1 row says m/s).
    const t1 = rows.find((r) => r.test === 't1-free-walking' && r.planner === 'boids');
    assert.match(t1.measured, /m\/s/);
    assert.match(await page.textContent('#val-summary'), /of 6 passed/);
    // Issue 27 §5: after a run the page stays inside a 1366 px screen (it was 31 px wider).
    await page.setViewportSize({ width: 1366, height: 768 });
    const widths = await page.evaluate(() => [document.documentElement.scrollWidth, document.documentElement.clientWidth]);
    assert.ok(widths[0] <= widths[1], `the page is ${widths[0]} px wide in a ${widths[1]} px window`);
    // The T8 sweep is plotted per planner.
    const sweepLegend = await page.textContent('#val-sweep-legend');
    assert.match(sweepLegend, /boids/);
    assert.match(sweepLegend, /forces/);
    assert.equal(await page.isDisabled('#val-cancel'), true);
    await screenshot(page, 'validation-table');

    // The link opens the test's scene in the playground.
    await page.goto(new URL(t1.href, page.url()).href);
    await waitReady(page);
    const scene = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene()));
    assert.equal(scene.name, 'validate-t1-free-walking');
    assert.equal(scene.groups[0].count, 1);
    assert.equal(scene.groups[0].planner.kind, 'boids');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('the fundamental diagram is plotted and a run can be cancelled', async () => {
  const { page, errors, close } = await openPath('validation.html', { ready });
  try {
    // A T4 run is slow enough to cancel mid-way.
    await pick(page, 'val-planners', ['boids', 'pso', 'firefly']);
    await pick(page, 'val-tests', ['t4-fundamental-diagram']);
    await page.click('#val-run');
    await page.waitForFunction(() => document.querySelectorAll('#val-table tbody tr').length >= 1, null, { timeout: 120_000 });
    const legend = await page.textContent('#val-legend');
    assert.match(legend, /Weidmann/);
    assert.match(legend, /boids/, 'the finished planner is in the plot legend');
    const inked = await page.evaluate(() => {
      const c = document.getElementById('val-plot');
      const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      let n = 0;
      for (let i = 0; i < d.length; i += 4) if (d[i] < 200 || d[i + 1] < 200 || d[i + 2] < 200) n += 1;
      return n;
    });
    assert.ok(inked > 200, `the plot has lines (${inked} dark pixels)`);
    await page.click('#val-cancel');
    assert.equal(await page.textContent('#val-progress-text'), 'cancelled');
    assert.equal(await page.evaluate(() => window.flockpathValidation.running()), false);
    const rows = await page.$$eval('#val-table tbody tr', (trs) => trs.length);
    assert.ok(rows < 3, `cancelled before the last planner (${rows} rows)`);
    assert.equal(await page.isDisabled('#val-run'), false);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
