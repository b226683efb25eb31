// The standard theme's trails are legible on a projector (issue 27 §2): measured in a screenshot
// of the page, not eyeballed. Three groups in the palette's palest colours (yellow, orange, sky
// blue) walk left to right in their own bands; trail pixels are those that change when trails
// are switched off at the same step; across each trail (a run of trail pixels down a column) the
// darkest pixel is its core, and the median core must reach 3:1 against the field (WCAG's
// non-text contrast). The old 1 px, 35 %-opacity trails reached 1.1–1.3:1 in these colours.
// The hint pill fades once read, so it does not always cover the canvas's bottom-left corner.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, frames, loadPaused, openPage, simpleScene } from './helpers.mjs';

const BANDS = [
  { color: '#f0e442', y: 100 },
  { color: '#e69f00', y: 250 },
  { color: '#56b4e9', y: 400 },
];

const scene = simpleScene({
  view: { trails: true, trail_fade: 0 },
  goals: BANDS.map(({ y }) => ({ position: [760, y], radius: 25 })),
  groups: BANDS.map(({ color, y }, i) => ({
    ...simpleScene().groups[0],
    name: `band ${i + 1}`,
    color,
    count: 12,
    spawn: { min: [30, y - 40], max: [90, y + 40] },
    goal: i,
  })),
});

/** A screenshot of the scene canvas, kept in the page as `window.__shots[name]` (decoded RGBA). */
async function screenshotInPage(page, name) {
  const box = await page.locator('#scene-canvas').boundingBox();
  const png = await page.screenshot({ clip: box });
  await page.evaluate(async ([key, base64]) => {
    const image = new Image();
    image.src = `data:image/png;base64,${base64}`;
    await image.decode();
    const canvas = Object.assign(document.createElement('canvas'), { width: image.width, height: image.height });
    const ctx = canvas.getContext('2d');
    ctx.drawImage(image, 0, 0);
    window.__shots ??= {};
    window.__shots[key] = ctx.getImageData(0, 0, image.width, image.height);
  }, [name, png.toString('base64')]);
}

/**
 * Per band: the trail cross-sections (runs of trail pixels down every third column between the
 * spawn and the goal) and the contrast of each one's darkest pixel against the field (WCAG).
 */
function measureBands([bands, background]) {
  const channel = (c) => {
    const s = c / 255;
    return s <= 0.04045 ? s / 12.92 : ((s + 0.055) / 1.055) ** 2.4;
  };
  const luminance = (r, g, b) => 0.2126 * channel(r) + 0.7152 * channel(g) + 0.0722 * channel(b);
  const field = luminance(...background);
  const contrast = (l) => (Math.max(l, field) + 0.05) / (Math.min(l, field) + 0.05);
  const on = window.__shots.on;
  const off = window.__shots.off;
  const { width, height } = on;
  const v = window.flockpath.view();
  const cssPerDevice = width / v.canvasWidth;
  const toScreenX = (x) => Math.round((x * v.scale + v.offsetX) * cssPerDevice);
  const toScreenY = (y) => Math.round((y * v.scale + v.offsetY) * cssPerDevice);
  return bands.map(({ color, y }) => {
    const top = Math.max(0, toScreenY(y - 45));
    const bottom = Math.min(height - 1, toScreenY(y + 45));
    const cores = [];
    for (let x = toScreenX(100); x < toScreenX(700); x += 3) {
      let best = 0;
      for (let yy = top; yy <= bottom; yy += 1) {
        const i = (yy * width + x) * 4;
        const d = Math.abs(on.data[i] - off.data[i]) + Math.abs(on.data[i + 1] - off.data[i + 1]) + Math.abs(on.data[i + 2] - off.data[i + 2]);
        if (d > 6) {
          best = Math.max(best, contrast(luminance(on.data[i], on.data[i + 1], on.data[i + 2])));
        } else if (best > 0) {
          cores.push(best);
          best = 0;
        }
      }
      if (best > 0) cores.push(best);
    }
    cores.sort((a, b) => a - b);
    const pick = (q) => Number((cores[Math.floor(cores.length * q)] ?? 0).toFixed(2));
    return { color, trails: cores.length, p25: pick(0.25), median: pick(0.5) };
  });
}

test('standard-theme trails reach 3:1 against the field in a screenshot, even in yellow', async () => {
  const { page, errors, close } = await openPage({ viewport: { width: 1366, height: 768 } });
  try {
    await loadPaused(page, scene);
    await page.evaluate(() => window.flockpath.step(150));
    await frames(page, 4);
    await screenshotInPage(page, 'on');
    await page.click('#trails');
    await frames(page, 4);
    await screenshotInPage(page, 'off');
    const results = await page.evaluate(measureBands, [BANDS, [0xf6, 0xf5, 0xf0]]);
    console.log(JSON.stringify(results));
    for (const r of results) {
      assert.ok(r.trails > 100, `${r.color}: ${r.trails} trail cross-sections: the trails were not drawn, so this proves nothing`);
      assert.ok(r.median >= 3, `${r.color}: median trail core contrast ${r.median}:1 (aim ≥ 3:1)`);
    }
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('the hint pill fades once read and comes back when its words change', async () => {
  const { page, errors, close } = await openPage();
  try {
    const opacity = () => page.evaluate(() => Number(getComputedStyle(document.getElementById('hint')).opacity));
    assert.ok((await page.textContent('#hint')).length > 0, 'the hint says something');
    await page.waitForFunction(() => Number(getComputedStyle(document.getElementById('hint')).opacity) === 0, null, { timeout: 9000 });
    // Faded, it does not hide the canvas's bottom-left corner (and takes no pointer).
    assert.equal(await opacity(), 0);
    await page.click('button[data-tool="circle"]');
    await page.waitForFunction(() => Number(getComputedStyle(document.getElementById('hint')).opacity) === 1, null, { timeout: 2000 });
    assert.match(await page.textContent('#hint'), /centre|center/i);
    await page.waitForFunction(() => Number(getComputedStyle(document.getElementById('hint')).opacity) === 0, null, { timeout: 9000 });
    // The pointer arriving over the canvas shows it again.
    const box = await page.locator('#overlay-canvas').boundingBox();
    await page.mouse.move(5, 5);
    await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
    await page.waitForFunction(() => Number(getComputedStyle(document.getElementById('hint')).opacity) === 1, null, { timeout: 2000 });
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
