// Trails that tell the truth: after `step(2000)` in one call the trails go round the pillars
// (every step leaves its segment, no chord from the old to the new positions), and a timeline
// jump redraws the trails of the recorded steps before it instead of erasing them. Both read the
// canvas pixels; pillar interiors and agent positions come from the page API and its
// scene → canvas transform.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, frames, openPage, screenshot, snapshotCanvas } from './helpers.mjs';

/** Loads the `pillars` preset paused at step 0 and lets a frame start its trails. */
async function loadPillars(page) {
  await page.selectOption('#preset', 'pillars');
  await page.evaluate(() => {
    window.flockpath.pause();
    window.flockpath.reset();
  });
  await frames(page, 2);
}

/**
 * In the page: counts the pixels of snapshot `name` inside each circular obstacle, at least
 * `inset` canvas px from its border, that are tinted towards the first group's colour (the
 * trail is that colour blended over the obstacle), and the group-tinted pixels over the
 * background in the whole canvas.
 */
async function tintedPixels(page, name, inset) {
  return page.evaluate(([key, insetPx]) => {
    const image = window.__e2eSnapshots[key];
    const api = window.flockpath;
    const scene = api.scene();
    const { scale, offsetX, offsetY } = api.view();
    const hex = scene.groups[0].color;
    const group = [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16));
    const at = (x, y) => {
      const i = (y * image.width + x) * 4;
      return [image.data[i], image.data[i + 1], image.data[i + 2]];
    };
    // Moved from `ground` at least 6 levels, in a direction within 60° of the group's colour.
    const tinted = (p, ground) => {
      const d = p.map((c, k) => c - ground[k]);
      const g = group.map((c, k) => c - ground[k]);
      const dn = Math.hypot(...d);
      const gn = Math.hypot(...g);
      return dn > 6 && d.reduce((s, c, k) => s + c * g[k], 0) > 0.5 * dn * gn;
    };
    let inside = 0;
    let interior = 0;
    for (const o of scene.obstacles) {
      if (o.shape !== 'circle') continue;
      const cx = o.center[0] * scale + offsetX;
      const cy = o.center[1] * scale + offsetY;
      const reach = o.radius * scale - insetPx;
      const fill = at(Math.floor(cx), Math.floor(cy));
      for (let y = Math.floor(cy - reach); y <= Math.ceil(cy + reach); y += 1) {
        for (let x = Math.floor(cx - reach); x <= Math.ceil(cx + reach); x += 1) {
          if (Math.hypot(x + 0.5 - cx, y + 0.5 - cy) > reach) continue;
          interior += 1;
          if (tinted(at(x, y), fill)) inside += 1;
        }
      }
    }
    const background = at(Math.floor(offsetX + 2), Math.floor(offsetY + 2));
    let outside = 0;
    for (let y = 0; y < image.height; y += 1) {
      for (let x = 0; x < image.width; x += 1) if (tinted(at(x, y), background)) outside += 1;
    }
    return { inside, interior, outside };
  }, [name, inset]);
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
    assert.equal(await page.evaluate(() => window.flockpath.step(2000)), 2000);
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
    const before = await page.evaluate(() => {
      const api = window.flockpath;
      api.step(200);
      const positions = api.positions();
      api.step(400);
      return positions;
    });
    await frames(page, 2);
    const count = () =>
      page.evaluate((points) => {
        const image = window.__e2eSnapshots.now;
        const { scale, offsetX, offsetY } = window.flockpath.view();
        const background = (() => {
          const i = (Math.floor(offsetY + 2) * image.width + Math.floor(offsetX + 2)) * 4;
          return [image.data[i], image.data[i + 1], image.data[i + 2]];
        })();
        const hex = window.flockpath.scene().groups[0].color;
        const group = [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16));
        // A pixel within 3 px of where the agent was that is tinted towards the group's colour.
        const near = ([sx, sy]) => {
          const cx = Math.round(sx * scale + offsetX);
          const cy = Math.round(sy * scale + offsetY);
          for (let y = cy - 3; y <= cy + 3; y += 1) {
            for (let x = cx - 3; x <= cx + 3; x += 1) {
              const i = (y * image.width + x) * 4;
              const d = [0, 1, 2].map((k) => image.data[i + k] - background[k]);
              const g = group.map((c, k) => c - background[k]);
              const dot = d.reduce((s, c, k) => s + c * g[k], 0);
              if (Math.hypot(...d) > 6 && dot > 0.5 * Math.hypot(...d) * Math.hypot(...g)) return true;
            }
          }
          return false;
        };
        return points.filter(near).length;
      }, before);
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
    assert.equal(await page.evaluate(() => window.flockpath.metrics().steps), 250);
    await snapshotCanvas(page, 'now');
    const scrubbed = await count();
    assert.ok(scrubbed >= 0.8 * before.length, `after scrubbing ${scrubbed}/${before.length} step-200 positions have a trail`);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
