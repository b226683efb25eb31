// Issue #27 §5: the Share dialog's iframe snippet had a fixed 720×480 frame; squeezed to a narrow
// column by max-width it kept its height and showed grey bands above and below the world. The
// snippet now keeps the world's aspect ratio (plus the embed's control bar) at any width: pasted
// into a host page at column widths 720 and 420 px, the frame's stage has the world's aspect
// within 3 %, for a wide (800×500) and a tall (400×700) world.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPage, simpleScene } from './helpers.mjs';

test('the iframe snippet keeps the world aspect ratio in narrow and wide columns', async () => {
  const { page, context, errors, close } = await openPage();
  try {
    for (const [width, height] of [[800, 500], [400, 700]]) {
      const scene = simpleScene({ width, height, goals: [{ position: [width / 2, height / 2], radius: 40 }] });
      scene.groups[0].spawn = { min: [20, 20], max: [120, 120] };
      await page.evaluate(async (s) => {
        await window.flockpath.pause();
        await window.flockpath.load(s);
      }, scene);
      await page.click('#share');
      const snippet = await page.inputValue('#share-iframe');
      await page.keyboard.press('Escape');
      for (const column of [720, 420]) {
        const host = await context.newPage();
        await host.setViewportSize({ width: column + 40, height: 1200 });
        await host.setContent(`<!doctype html><body style="margin:20px;background:#fff">${snippet}</body>`);
        const frameHandle = await host.waitForSelector('iframe');
        const frame = await frameHandle.contentFrame();
        await frame.waitForFunction(() => document.querySelector('flock-path') !== null, null, { timeout: 30_000 });
        await frame.evaluate(async () => {
          await customElements.whenDefined('flock-path');
          await document.querySelector('flock-path').ready;
        });
        const box = await frameHandle.boundingBox();
        const stage = await frame.evaluate(() => {
          const r = document.querySelector('flock-path').shadowRoot.querySelector('.stage').getBoundingClientRect();
          return { width: r.width, height: r.height };
        });
        const want = height / width;
        const got = stage.height / stage.width;
        assert.ok(Math.abs(box.width - Math.min(column, 720)) <= 1, `${width}×${height} in ${column} px: frame ${box.width} px wide`);
        assert.ok(Math.abs(got / want - 1) <= 0.03,
          `${width}×${height} in a ${column} px column: stage ${stage.width}×${stage.height} (aspect ${got.toFixed(3)}, world ${want.toFixed(3)})`);
        if (column === 420) await host.screenshot({ path: `test-artifacts/iframe-snippet-${width}x${height}-420.png` });
        await host.close();
      }
    }
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
