// Print: before printing, each <flock-path> of the course notes (and the playground's canvas) gets a
// still image of the scene at its current step, shown under @media print instead of the canvas;
// after printing the stills are gone and the canvases show again.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, frames, openPage, openPath, screenshot } from './helpers.mjs';

/**
 * For each canvas (found by `find`, evaluated in the page): the still next to it, whether it and
 * the canvas are displayed, how many of its pixels are not background, and whether its pixels
 * equal the canvas's (compared before print media resized anything).
 */
function inspectStills(find, compare) {
  return Promise.all(
    find().map(async (canvas) => {
      const img = canvas.parentNode.querySelector('img.flockpath-print-still');
      if (!img) return { present: false };
      await img.decode();
      const probe = document.createElement('canvas');
      probe.width = img.naturalWidth;
      probe.height = img.naturalHeight;
      const ctx = probe.getContext('2d');
      ctx.drawImage(img, 0, 0);
      const data = ctx.getImageData(0, 0, probe.width, probe.height).data;
      // Background (#f6f5f0) and letterbox (#d8d8d3) of the renderer.
      const plain = [[0xf6, 0xf5, 0xf0], [0xd8, 0xd8, 0xd3]];
      let drawn = 0;
      for (let i = 0; i < data.length; i += 4) {
        const near = plain.some(([r, g, b]) => Math.abs(data[i] - r) + Math.abs(data[i + 1] - g) + Math.abs(data[i + 2] - b) < 12);
        if (!near) drawn++;
      }
      let same = null;
      if (compare) {
        const live = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
        same = probe.width === canvas.width && probe.height === canvas.height && live.every((v, i) => v === data[i]);
      }
      return {
        present: true,
        drawn,
        pixels: probe.width * probe.height,
        same,
        stillShown: getComputedStyle(img).display !== 'none' && img.getBoundingClientRect().height > 20,
        canvasShown: getComputedStyle(canvas).display !== 'none',
      };
    }),
  );
}

const courseCanvases = () => [...document.querySelectorAll('flock-path')].map((el) => el.shadowRoot.querySelector('canvas'));

test('printing the course notes shows a still of each scene at its current step', async () => {
  const { page, errors, close } = await openPath('examples/course-notes.html', {
    ready: () => {
      const els = [...document.querySelectorAll('flock-path')];
      return els.length === 2 && els.every((el) => el.sim && el.steps > 30);
    },
    viewport: { width: 1000, height: 900 },
  });
  try {
    // Paused, so the canvas and the still can be compared pixel for pixel.
    await page.evaluate(() => Promise.all([...document.querySelectorAll('flock-path')].map((el) => el.pause())));
    await frames(page, 2);
    await page.evaluate(() => window.dispatchEvent(new Event('beforeprint')));
    const onScreen = await page.evaluate(`(${inspectStills})(${courseCanvases}, true)`);
    assert.equal(onScreen.length, 2);
    for (const s of onScreen) {
      assert.ok(s.present, 'a still was added');
      assert.equal(s.same, true, 'the still is the scene as the canvas shows it now');
      assert.ok(s.drawn > 200, `the still is not blank (${s.drawn} of ${s.pixels} pixels drawn)`);
      assert.equal(s.stillShown, false, 'on screen the still stays hidden');
      assert.equal(s.canvasShown, true);
    }

    await page.emulateMedia({ media: 'print' });
    const printed = await page.evaluate(`(${inspectStills})(${courseCanvases}, false)`);
    for (const s of printed) {
      assert.ok(s.present && s.drawn > 200, 'the still survives the print layout');
      assert.equal(s.stillShown, true, 'printed: the still is shown');
      assert.equal(s.canvasShown, false, 'printed: the canvas is not');
    }

    await page.evaluate(() => window.dispatchEvent(new Event('afterprint')));
    await page.emulateMedia({ media: 'screen' });
    const after = await page.evaluate(`(${inspectStills})(${courseCanvases}, false)`);
    assert.deepEqual(after, [{ present: false }, { present: false }], 'the stills are removed after printing');
    // The elements run on after printing.
    const before = await page.evaluate(() => document.getElementById('swap').steps);
    await page.evaluate(() => document.getElementById('swap').play());
    await page.waitForFunction((n) => document.getElementById('swap').steps > n + 5, before);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('print media alone (no beforeprint) also swaps the playground canvas for a still', async () => {
  const { page, errors, close } = await openPage();
  try {
    await page.evaluate(async () => {
      await window.flockpath.pause();
      await window.flockpath.step(40);
    });
    await page.waitForTimeout(100);
    await page.emulateMedia({ media: 'print' });
    await page.waitForFunction(() => document.querySelector('img.flockpath-print-still') !== null);
    const [s] = await page.evaluate(`(${inspectStills})(() => [document.getElementById('scene-canvas')], false)`);
    assert.ok(s.present && s.drawn > 200, `a drawn still (${s.drawn} px)`);
    assert.equal(s.stillShown, true);
    assert.equal(s.canvasShown, false);
    assert.equal(await page.locator('#stage img.flockpath-print-still').count(), 1, 'one still in the stage: the overlay canvas is not copied');
    assert.equal(await page.locator('#overlay-canvas').evaluate((c) => c.hasAttribute('data-flockpath-print')), false);
    // The plots are canvases too: they print as stills as well.
    assert.ok((await page.locator('#plots img.flockpath-print-still').count()) > 0, 'the plots get stills');
    await screenshot(page, 'print-playground');
    await page.emulateMedia({ media: 'screen' });
    await page.waitForFunction(() => document.querySelector('img.flockpath-print-still') === null);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
