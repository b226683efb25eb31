// The metrics panel: a row per group with its planner, and time-series plots drawn from the
// core's metrics history (canvas pixels beyond the white background).

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, frames, openPage, screenshot, simpleScene } from './helpers.mjs';

/** Non-white pixels of a plot canvas below its label line. */
async function inkedPixels(page, key) {
  return page.evaluate((k) => {
    const canvas = document.querySelector(`#plots canvas[data-key="${k}"]`);
    const ctx = canvas.getContext('2d');
    const top = Math.round(16 * (window.devicePixelRatio || 1));
    const { data } = ctx.getImageData(0, top, canvas.width, canvas.height - top);
    let inked = 0;
    for (let i = 0; i < data.length; i += 4) {
      if (data[i] < 200 || data[i + 1] < 200 || data[i + 2] < 200) inked += 1;
    }
    return inked;
  }, key);
}

test('the metrics panel shows per-group rows and plots over time', async () => {
  const { page, errors, close } = await openPage({ viewport: { width: 1280, height: 1400 } });
  try {
    await page.selectOption('#preset', 'two-groups-swap');
    await page.evaluate(async () => {
      await window.flockpath.pause();
      await window.flockpath.reset();
      await window.flockpath.step(400);
    });
    await frames(page, 3);
    const rows = await page.$$eval('#metrics-groups tbody tr', (trs) => trs.map((tr) => tr.cells[0].textContent));
    assert.deepEqual(rows, ['left (boids)', 'right (boids)']);
    const history = await page.evaluate(() => window.flockpath.metricsHistory());
    assert.equal(history.steps.at(-1), 400);
    assert.equal(history.series.arrived_share.groups.length, 2);
    assert.equal(history.series.mean_path_length.overall.length, history.steps.length);
    assert.ok(history.series.mean_path_length.overall.at(-1) > 100, 'agents walked');
    for (const key of ['arrived_share', 'mean_path_length', 'mean_turn_deg']) {
      const inked = await inkedPixels(page, key);
      assert.ok(inked > 40, `plot ${key} has ${inked} inked pixels`);
    }
    const empty = await page.$$eval('#plots canvas', (list) => list.length);
    assert.equal(empty, Object.keys(history.series).length, 'one plot per series');
    const card = await page.$('#metrics-title');
    await card.scrollIntoViewIfNeeded();
    await screenshot(page, 'metrics-panel');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

// Issue #27 §4 (stale state): paused, the plots follow what the page API and the Scene menu did —
// after step(300) they show the run's samples, and a scene picked from the menu starts them
// empty (they kept the previous run's history, to step 615 at step 0, until Play).
test('paused, the plots follow steps and a newly picked scene', async () => {
  const { page, errors, close } = await openPage();
  try {
    const shown = () =>
      page.evaluate(() => [...document.querySelectorAll('#plots canvas')].map((c) => `${c.dataset.samples}@${c.dataset.lastStep}`));
    const drawn = async (expected) => {
      await page.waitForFunction(
        (want) => [...document.querySelectorAll('#plots canvas')].every((c) => c.dataset.samples !== undefined && c.dataset.lastStep === want),
        expected,
        { timeout: 10_000 },
      ).catch(() => {});
      return shown();
    };
    await page.selectOption('#preset', 'pillars');
    await page.evaluate(async () => {
      await window.flockpath.settled();
      await window.flockpath.pause();
      await window.flockpath.reset();
      await window.flockpath.step(300);
    });
    assert.equal(await page.evaluate(() => document.getElementById('plots-details').open), true, 'the plots are open');
    const after300 = await drawn('300');
    assert.ok(after300.length > 5, `${after300.length} plots`);
    for (const p of after300) assert.match(p, /^\d+@300$/, 'each plot shows the run to step 300');
    assert.ok(after300.every((p) => Number(p.split('@')[0]) > 1), after300.join());

    await page.selectOption('#preset', 'open-field');
    await page.evaluate(async () => {
      await window.flockpath.settled();
      await window.flockpath.pause();
    });
    assert.equal(await page.evaluate(() => window.flockpath.metrics().steps), 0);
    const picked = await drawn('');
    for (const p of picked) assert.equal(p, '0@', 'a new scene at step 0 plots nothing of the old run');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

/** Pixels of a plot canvas below its label line whose colour is within 40 of `rgb` in each channel. */
async function pixelsOf(page, key, rgb) {
  return page.evaluate(({ k, c }) => {
    const canvas = document.querySelector(`#plots canvas[data-key="${k}"]`);
    const top = Math.round(16 * (window.devicePixelRatio || 1));
    const { data } = canvas.getContext('2d').getImageData(0, top, canvas.width, canvas.height - top);
    let n = 0;
    for (let i = 0; i < data.length; i += 4) {
      if (Math.abs(data[i] - c[0]) < 40 && Math.abs(data[i + 1] - c[1]) < 40 && Math.abs(data[i + 2] - c[2]) < 40) n += 1;
    }
    return n;
  }, { k: key, c: rgb });
}

// Issue #24: 5,000 one-agent groups held the page's main thread for 45 s (a plot line per group
// and series, each asked of the worker in its own message) and 250 ms per refresh after (a
// table row per group). Past 12 groups the plots draw the whole run only; the table pages 50 rows.
test('a scene of many groups pages its table and plots the whole run only', async () => {
  const { page, errors, close } = await openPage({ viewport: { width: 1280, height: 1400 } });
  try {
    const base = simpleScene().groups[0];
    const groups = Array.from({ length: 120 }, (_, k) => ({
      ...base,
      name: `g${k + 1}`,
      color: '#d94f2a',
      count: 1,
      spawn: { min: [10 + (k % 12) * 50, 10 + Math.floor(k / 12) * 40], max: [40 + (k % 12) * 50, 40 + Math.floor(k / 12) * 40] },
    }));
    await page.evaluate(async (s) => {
      await window.flockpath.pause();
      await window.flockpath.load(s);
      await window.flockpath.step(120);
    }, simpleScene({ name: 'many-groups', width: 900, height: 500, groups }));
    const table = () => page.evaluate(() => ({
      groups: [...document.querySelectorAll('#metrics-groups tbody tr')].map((tr) => Number(tr.dataset.group)),
      first: document.querySelector('#metrics-groups tbody tr').cells[0].textContent,
      range: document.querySelector('.group-pager span').textContent,
      previous: document.querySelector('.group-pager button:first-child').disabled,
      next: document.querySelector('.group-pager button:last-child').disabled,
    }));
    await page.waitForFunction(() => document.querySelector('.group-pager span')?.textContent !== '');
    let shown = await table();
    assert.deepEqual(shown.groups, Array.from({ length: 50 }, (_, k) => k));
    assert.equal(shown.range, 'Groups 1–50 of 120');
    assert.deepEqual([shown.previous, shown.next], [true, false]);
    for (const expected of [[50, 100, 'g51 (boids)', 'Groups 51–100 of 120'], [100, 120, 'g101 (boids)', 'Groups 101–120 of 120']]) {
      await page.click('.group-pager button:last-child');
      await page.waitForFunction((range) => document.querySelector('.group-pager span').textContent === range, expected[3]);
      shown = await table();
      assert.deepEqual(shown.groups, Array.from({ length: expected[1] - expected[0] }, (_, k) => expected[0] + k));
      assert.equal(shown.first, expected[2]);
    }
    assert.deepEqual([shown.previous, shown.next], [false, true]);
    assert.match(await page.textContent('#plots-note'), /^120 groups: the plots draw the whole run only/);
    await page.waitForFunction(() => document.querySelector('#plots canvas[data-key="mean_path_length"]').dataset.lastStep === '120');
    // The whole run's dark line is drawn; no group's red line is.
    const dark = await pixelsOf(page, 'mean_path_length', [0x17, 0x20, 0x2c]);
    const red = await pixelsOf(page, 'mean_path_length', [0xd9, 0x4f, 0x2a]);
    assert.ok(dark > 40, `the whole run's line: ${dark} pixels`);
    assert.equal(red, 0, 'no group line');
    await page.locator('.group-pager').scrollIntoViewIfNeeded();
    await screenshot(page, 'metrics-many-groups');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
