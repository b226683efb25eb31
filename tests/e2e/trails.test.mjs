// Trails that tell the truth: after `reset(); step(2000)` in one call (no frame between) the
// trails go round the pillars (every step leaves its segment, no chord from the old to the new
// positions), and a timeline jump redraws the trails of the recorded steps before it instead of
// erasing them. Both read the canvas pixels; pillar interiors and agent positions come from the
// page API and its scene → canvas transform.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, frames, openPage, screenshot, snapshotCanvas } from './helpers.mjs';

/**
 * Loads the `pillars` preset paused at step 0, lets a frame start its trails, and installs the
 * pixel test both checks use: `__e2eTint(image, x, y, ground)` is whether canvas pixel (x, y)
 * moved from the `ground` colour at least 6 levels in a direction within 60° of the first
 * group's colour (a trail is that colour blended over whatever lies below).
 */
async function loadPillars(page) {
  await page.evaluate(() => {
    window.__e2eTint = (image, x, y, ground) => {
      if (x < 0 || y < 0 || x >= image.width || y >= image.height) return false;
      const hex = window.flockpath.scene().groups[0].color;
      const group = [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16));
      const i = (y * image.width + x) * 4;
      const d = [0, 1, 2].map((k) => image.data[i + k] - ground[k]);
      const g = group.map((c, k) => c - ground[k]);
      const dn = Math.hypot(...d);
      return dn > 6 && d.reduce((s, c, k) => s + c * g[k], 0) > 0.5 * dn * Math.hypot(...g);
    };
    window.__e2ePixel = (image, x, y) => {
      const i = (y * image.width + x) * 4;
      return [image.data[i], image.data[i + 1], image.data[i + 2]];
    };
  });
  await page.selectOption('#preset', 'pillars');
  await page.evaluate(async () => {
    await window.flockpath.pause();
    await window.flockpath.reset();
  });
  await frames(page, 2);
}

/**
 * In the page: counts the group-tinted pixels of snapshot `name` inside each circular obstacle,
 * at least `inset` canvas px from its border, and over the background in the whole canvas.
 */
async function tintedPixels(page, name, inset) {
  return page.evaluate(([key, insetPx]) => {
    const image = window.__e2eSnapshots[key];
    const api = window.flockpath;
    const { scale, offsetX, offsetY } = api.view();
    let inside = 0;
    let interior = 0;
    for (const o of api.scene().obstacles) {
      if (o.shape !== 'circle') continue;
      const cx = o.center[0] * scale + offsetX;
      const cy = o.center[1] * scale + offsetY;
      const reach = o.radius * scale - insetPx;
      const fill = window.__e2ePixel(image, Math.floor(cx), Math.floor(cy));
      for (let y = Math.floor(cy - reach); y <= Math.ceil(cy + reach); y += 1) {
        for (let x = Math.floor(cx - reach); x <= Math.ceil(cx + reach); x += 1) {
          if (Math.hypot(x + 0.5 - cx, y + 0.5 - cy) > reach) continue;
          interior += 1;
          if (window.__e2eTint(image, x, y, fill)) inside += 1;
        }
      }
    }
    const background = window.__e2ePixel(image, Math.floor(offsetX + 2), Math.floor(offsetY + 2));
    let outside = 0;
    for (let y = 0; y < image.height; y += 1) {
      for (let x = 0; x < image.width; x += 1) if (window.__e2eTint(image, x, y, background)) outside += 1;
    }
    return { inside, interior, outside };
  }, [name, inset]);
}

/** In the page: how many of `points` (scene px) have a group-tinted pixel of snapshot `name` within 3 px. */
async function pointsOnTrails(page, name, points) {
  return page.evaluate(([key, pts]) => {
    const image = window.__e2eSnapshots[key];
    const { scale, offsetX, offsetY } = window.flockpath.view();
    const background = window.__e2ePixel(image, Math.floor(offsetX + 2), Math.floor(offsetY + 2));
    const near = ([sx, sy]) => {
      const cx = Math.round(sx * scale + offsetX);
      const cy = Math.round(sy * scale + offsetY);
      for (let y = cy - 3; y <= cy + 3; y += 1) {
        for (let x = cx - 3; x <= cx + 3; x += 1) if (window.__e2eTint(image, x, y, background)) return true;
      }
      return false;
    };
    return pts.filter(near).length;
  }, [name, points]);
}

test('after step(2000) in one call no trail lies inside a pillar', async () => {
  const { page, errors, close } = await openPage();
  try {
    await loadPillars(page);
    const shape = await page.evaluate(() => {
      const s = window.flockpath.scene();
      return { circles: s.obstacles.filter((o) => o.shape === 'circle').length, trails: s.view?.trails ?? true };
    });
    assert.equal(shape.circles, 16, 'pillars has 16 circular pillars');
    assert.equal(shape.trails, true, 'trails are on');
    // Reset and step in one go, no frame between: a course note scripting a scene.
    const steps = await page.evaluate(async () => {
      await window.flockpath.reset();
      return window.flockpath.step(2000);
    });
    assert.equal(steps, 2000);
    await frames(page, 2);
    await snapshotCanvas(page, 'after-2000');
    await screenshot(page, 'trails-step-2000');
    // 3 px in from the border: the outline's anti-aliasing and agent bodies pressed against
    // the pillar are left out.
    const { inside, interior, outside } = await tintedPixels(page, 'after-2000', 3);
    assert.ok(interior > 5000, `${interior} pillar pixels were checked`);
    assert.ok(outside > 3000, `the trails are on screen: ${outside} group-tinted pixels`);
    assert.equal(inside, 0, `${inside} trail pixels inside the pillars`);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('a timeline jump redraws the trails of the recorded steps before it', async () => {
  const { page, errors, close } = await openPage();
  try {
    await loadPillars(page);
    const before = await page.evaluate(async () => {
      const api = window.flockpath;
      await api.step(200);
      const positions = await api.positions();
      await api.step(400);
      return positions;
    });
    await frames(page, 2);
    const count = () => pointsOnTrails(page, 'now', before);
    await snapshotCanvas(page, 'now');
    const live = await count();
    assert.ok(live >= 0.8 * before.length, `before the jump ${live}/${before.length} step-200 positions have a trail`);

    assert.equal(await page.evaluate(() => window.flockpath.seek(300)), 300);
    await frames(page, 2);
    await snapshotCanvas(page, 'now');
    await screenshot(page, 'trails-after-seek');
    const rebuilt = await count();
    assert.ok(rebuilt >= 0.8 * before.length, `after the jump ${rebuilt}/${before.length} step-200 positions have a trail`);
    const { inside } = await tintedPixels(page, 'now', 3);
    assert.equal(inside, 0, 'the rebuilt trails stay out of the pillars');

    // The slider jumps the same way.
    await page.$eval('#timeline', (el) => {
      el.value = '250';
      el.dispatchEvent(new Event('input', { bubbles: true }));
      el.dispatchEvent(new Event('change', { bubbles: true }));
    });
    await frames(page, 2);
    assert.equal(await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.metrics().steps)), 250);
    await snapshotCanvas(page, 'now');
    const scrubbed = await count();
    assert.ok(scrubbed >= 0.8 * before.length, `after scrubbing ${scrubbed}/${before.length} step-200 positions have a trail`);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
