// Projector theme and colour: the playground's text passes axe-core's color-contrast rule (no
// serious or critical violation) in the standard and the projector theme; the top bar's toggle
// and the URL option (`?theme=projector`, `#…&theme=projector`) switch the theme, which the Rust
// renderer draws (white field, darker obstacles) without changing the scene; new groups take the
// Okabe–Ito palette.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import {
  ROOT,
  assertNoUnexpectedErrors,
  frames,
  openPage,
  openPath,
  pixelsAt,
  sceneToCanvasPixel,
  screenshot,
  simpleScene,
  snapshotCanvas,
  waitReady,
} from './helpers.mjs';

const AXE = path.join(ROOT, 'node_modules', 'axe-core', 'axe.min.js');

/** axe-core's color-contrast violations of impact serious or critical, as readable lines. */
async function contrastProblems(page) {
  if (!(await page.evaluate(() => typeof window.axe === 'object'))) await page.addScriptTag({ path: AXE });
  const violations = await page.evaluate(async () => {
    const result = await window.axe.run(document, { runOnly: { type: 'rule', values: ['color-contrast'] } });
    return result.violations.map((v) => ({
      impact: v.impact,
      nodes: v.nodes.map((n) => `${n.target.join(' ')}: ${n.any.map((c) => c.message).join('; ')}`),
    }));
  });
  return violations.filter((v) => v.impact === 'serious' || v.impact === 'critical').flatMap((v) => v.nodes);
}

/** Relative luminance (WCAG) of an sRGB triple. */
function luminance([r, g, b]) {
  const lin = (c) => {
    const s = c / 255;
    return s <= 0.03928 ? s / 12.92 : ((s + 0.055) / 1.055) ** 2.4;
  };
  return 0.2126 * lin(r) + 0.7152 * lin(g) + 0.0722 * lin(b);
}

/** The canvas colour at a few scene points: the field's corner, and the first obstacle's centre. */
async function sample(page, name) {
  await frames(page, 3);
  await snapshotCanvas(page, name);
  const scene = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene()));
  const obstacle = scene.obstacles.find((o) => o.shape === 'circle');
  const points = [await sceneToCanvasPixel(page, 3, 3), await sceneToCanvasPixel(page, ...obstacle.center)];
  const [field, pillar] = await pixelsAt(page, name, points);
  return { field, pillar };
}

test('the projector theme: readable text in both themes, a toggle and a URL option, drawn by the renderer', async () => {
  const { page, errors, close } = await openPage({ hash: '' });
  try {
    await page.evaluate(() => window.flockpath.pause());
    assert.equal(await page.evaluate(() => window.flockpath.theme()), 'standard');
    assert.deepEqual(await contrastProblems(page), [], 'standard theme: no serious/critical contrast violation');
    const standard = await sample(page, 'standard');
    const sceneBefore = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.sceneString()));
    const textBefore = await page.evaluate(() => parseFloat(getComputedStyle(document.body).fontSize));

    const toggle = page.locator('#theme-toggle');
    assert.equal(await toggle.getAttribute('aria-pressed'), 'false');
    await toggle.click();
    assert.equal(await toggle.getAttribute('aria-pressed'), 'true');
    assert.equal(await page.evaluate(() => document.documentElement.dataset.theme), 'projector');
    assert.equal(await page.evaluate(() => window.flockpath.theme()), 'projector');
    assert.equal(new URL(page.url()).searchParams.get('theme'), 'projector', 'the link keeps the theme');
    const projector = await sample(page, 'projector');
    await screenshot(page, 'projector-theme');

    // The renderer draws it: a brighter field, darker obstacles.
    assert.ok(luminance(projector.field) > luminance(standard.field), `field ${standard.field} → ${projector.field}`);
    assert.deepEqual(projector.field, [255, 255, 255]);
    assert.ok(luminance(projector.pillar) < luminance(standard.pillar), `obstacle ${standard.pillar} → ${projector.pillar}`);
    // Larger text; the scene itself is untouched.
    const textAfter = await page.evaluate(() => parseFloat(getComputedStyle(document.body).fontSize));
    assert.ok(textAfter >= textBefore * 1.15, `text ${textBefore}px → ${textAfter}px`);
    assert.equal(await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.sceneString())), sceneBefore);
    assert.deepEqual(await contrastProblems(page), [], 'projector theme: no serious/critical contrast violation');

    // And back.
    await toggle.click();
    assert.equal(new URL(page.url()).searchParams.get('theme'), null);
    const again = await sample(page, 'standard-again');
    assert.deepEqual(again, standard, 'the standard look comes back exactly');

    // Okabe–Ito: the preset's group is its blue, and so is a group that names no colour.
    const colours = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene().groups.map((g) => g.color)));
    assert.deepEqual(colours, ['#0072b2'], 'the preset’s group is Okabe–Ito blue');
    const scene = simpleScene();
    delete scene.groups[0].color;
    const loaded = await page.evaluate(async (s) => (await window.flockpath.load(s)).groups[0].color, scene);
    assert.equal(loaded, '#0072b2', 'a group without a colour gets the palette’s first');
    const refused = await page.evaluate(async () => {
      try {
        await window.flockpath.theme('neon');
        return null;
      } catch (error) {
        return error.message;
      }
    });
    assert.match(refused ?? '', /unknown theme "neon"; known: standard, projector/);
    assertNoUnexpectedErrors(errors, [/unknown theme/]);
  } finally {
    await close();
  }
});

test('?theme=projector and #…&theme=projector open the page in the projector theme', async () => {
  for (const where of ['index.html?theme=projector', 'index.html#theme=projector']) {
    const { page, errors, close } = await openPath(where, { ready: () => window.flockpath !== undefined });
    try {
      await waitReady(page);
      assert.equal(await page.evaluate(() => window.flockpath.theme()), 'projector', where);
      assert.equal(await page.locator('#theme-toggle').getAttribute('aria-pressed'), 'true', where);
      const { field } = await sample(page, 'from-url');
      assert.deepEqual(field, [255, 255, 255], `${where}: the field is white`);
      assertNoUnexpectedErrors(errors);
    } finally {
      await close();
    }
  }
});

test('embed.html#…&theme=projector draws its <flock-path> in the projector theme', async () => {
  const field = async (hash) => {
    const { page, errors, close } = await openPath(`embed.html#s=pillars${hash}`, {
      ready: () => window.flockpathEmbed?.sim !== undefined && window.flockpathEmbed.steps >= 0,
    });
    try {
      await page.evaluate(() => window.flockpathEmbed.pause());
      await frames(page, 3);
      const rgb = await page.evaluate(() => {
        const el = window.flockpathEmbed;
        const [scale, ox, oy] = el.sim.view();
        const canvas = el.shadowRoot.querySelector('canvas');
        const d = canvas.getContext('2d').getImageData(Math.round(3 * scale + ox), Math.round(3 * scale + oy), 1, 1).data;
        return [d[0], d[1], d[2]];
      });
      assertNoUnexpectedErrors(errors);
      return rgb;
    } finally {
      await close();
    }
  };
  assert.deepEqual(await field(''), [0xf6, 0xf5, 0xf0], 'standard field');
  assert.deepEqual(await field('&theme=projector'), [255, 255, 255], 'projector field');
});
