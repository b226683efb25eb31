// The canvas keeps its size while the page around it changes: a WebM recording (the REC badge
// overlays the canvas corner, so the video has one frame size throughout), a preset with a longer
// or shorter description, a message in the banner, the timeline's note. Checked on a laptop
// screen and on a phone.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, frames, openPage, screenshot, simpleScene } from './helpers.mjs';

/** The canvas's CSS box and backing-store size. */
const canvasSize = (page) =>
  page.evaluate(() => {
    const canvas = document.getElementById('scene-canvas');
    const r = canvas.getBoundingClientRect();
    return { left: r.left, top: r.top, width: r.width, height: r.height, store: [canvas.width, canvas.height] };
  });

const boxOf = (page, selector) =>
  page.evaluate((sel) => {
    const r = document.querySelector(sel).getBoundingClientRect();
    return { left: r.left, top: r.top, right: r.right, bottom: r.bottom };
  }, selector);

/** Taps or clicks a header button, through the phone's menu when the header is collapsed. */
async function pressHeaderButton(page, selector) {
  if (await page.isVisible('#menu-toggle')) await page.click('#menu-toggle');
  await page.click(selector);
}

for (const viewport of [{ width: 1280, height: 800 }, { width: 390, height: 844 }]) {
  test(`at ${viewport.width}×${viewport.height} recording, presets and messages leave the canvas size alone`, async () => {
    const { page, errors, close } = await openPage({ viewport });
    try {
      await frames(page, 3);
      const before = await canvasSize(page);

      // Presets with descriptions of different lengths.
      const presets = await page.$$eval('#preset option:not([disabled])', (options) => options.map((o) => o.value));
      const lengths = await page.$$eval('#preset option:not([disabled])', (options) => options.map((o) => o.title.length));
      const longest = presets[lengths.indexOf(Math.max(...lengths))];
      const shortest = presets[lengths.indexOf(Math.min(...lengths))];
      for (const name of [longest, shortest, longest]) {
        await page.selectOption('#preset', name);
        await frames(page, 2);
        assert.deepEqual(await canvasSize(page), before, `the canvas keeps its place and size with preset ${name}`);
      }

      // A message in the banner overlays the page.
      await page.evaluate(async () => {
        try {
          await window.flockpath.load('{"width": "wide"}');
        } catch {
          // The refusal is shown in the banner; that is what this checks.
        }
      });
      await page.waitForSelector('#banner:not([hidden])');
      await frames(page, 2);
      assert.deepEqual(await canvasSize(page), before, 'the canvas keeps its size while the banner shows');
      await screenshot(page, `layout-banner-${viewport.width}`);
      await page.click('#banner-close');

      // Recording: the backing store (the video's frame size) is the same before and during it.
      await page.evaluate((scene) => window.flockpath.load(scene), simpleScene({ name: 'record me' }));
      await pressHeaderButton(page, '#export');
      await page.click('#record-webm');
      await page.waitForSelector('#recording-indicator:not([hidden])');
      await page.waitForFunction(() => document.getElementById('recording-time').textContent === '0:01', null, { timeout: 10_000 });
      await frames(page, 2);
      const during = await canvasSize(page);
      assert.deepEqual(during, before, 'the canvas keeps its size while recording');
      const badge = await boxOf(page, '#recording-indicator');
      const stage = await boxOf(page, '#stage');
      assert.ok(
        badge.left >= stage.left && badge.right <= stage.right && badge.top >= stage.top && badge.bottom <= stage.bottom,
        `the REC badge overlays the canvas area: ${JSON.stringify({ badge, stage })}`,
      );
      await screenshot(page, `layout-recording-${viewport.width}`);
      const [download] = await Promise.all([page.waitForEvent('download'), page.click('#recording-indicator')]);
      assert.equal(download.suggestedFilename(), 'record-me.webm');
      assert.ok(await page.isHidden('#recording-indicator'), 'the badge goes away');
      await frames(page, 2);
      assert.deepEqual(await canvasSize(page), before, 'and the canvas still has its size after');

      if (viewport.width === 1280) {
        // The timeline's note (its checkpoints thinned: 20,000 agents for 420 steps fill the
        // budget) overlays the canvas area instead of adding a row above it.
        const crowd = simpleScene({
          name: 'crowd',
          width: 4000,
          height: 4000,
          goals: [],
          groups: [{ ...simpleScene().groups[0], count: 20000, goal: null, spawn: { min: [0, 0], max: [4000, 4000] } }],
        });
        await page.evaluate(async (scene) => {
          await window.flockpath.pause();
          await window.flockpath.load(scene);
          await window.flockpath.step(420);
        }, crowd);
        await page.waitForSelector('#timeline-note:not([hidden])');
        await frames(page, 2);
        assert.deepEqual(await canvasSize(page), before, 'the canvas keeps its size while the timeline note shows');
      }
      assertNoUnexpectedErrors(errors);
    } finally {
      await close();
    }
  });
}
