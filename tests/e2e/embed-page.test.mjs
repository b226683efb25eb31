// embed.html#s=…: the canvas-only view loads the linked scene, autoplays when asked, plays,
// pauses and resets from its controls, links to the full page with the same scene, fills its
// iframe, and shows a readable message (keeping a running scene) for a garbled link.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPath, screenshot, simpleScene } from './helpers.mjs';

const ready = () => window.flockpathEmbed !== undefined;
// Read once the element's simulation worker has answered the clicks before (settled()).
const steps = (page) => page.evaluate(async () => (await window.flockpathEmbed.settled(), window.flockpathEmbed.steps));
const shadow = (page, selector) =>
  page.evaluate((sel) => {
    const el = window.flockpathEmbed.shadowRoot.querySelector(sel);
    return el && !el.hidden ? el.textContent : null;
  }, selector);

/** The fragment value of a scene, made by the page under test's own codec. */
async function fragmentOf(page, scene) {
  return page.evaluate(async (s) => {
    const el = window.flockpathEmbed;
    const before = el.sceneString();
    await el.load(s);
    const value = el.sceneString();
    await el.load(before);
    return value;
  }, scene);
}

test('the embed plays the linked scene and links to the full page', async () => {
  const first = await openPath('embed.html', { ready, viewport: { width: 640, height: 400 } });
  const fragment = await fragmentOf(first.page, simpleScene({ name: 'embedded', seed: 11 }));
  assert.equal(await steps(first.page), 0, 'without autoplay the embed waits');
  await first.close();

  const { page, errors, close } = await openPath(`embed.html#s=${fragment}&autoplay=1`, {
    ready,
    viewport: { width: 640, height: 400 },
  });
  try {
    assert.equal((await page.evaluate(() => window.flockpathEmbed.scene())).name, 'embedded');
    await page.waitForFunction(() => window.flockpathEmbed.steps > 20);
    assert.equal(await shadow(page, '.planner'), 'Boids steering');

    // The element fills the iframe-sized viewport (responsive to its container).
    const box = await page.evaluate(() => {
      const r = window.flockpathEmbed.getBoundingClientRect();
      return { width: r.width, height: r.height };
    });
    assert.equal(Math.round(box.width), 640);
    assert.equal(Math.round(box.height), 400);

    // Pause stops stepping; reset goes back to 0; play resumes.
    const button = page.locator('flock-path button.play');
    await button.click();
    assert.equal(await button.textContent(), 'Play');
    const paused = await steps(page);
    await page.waitForTimeout(300);
    assert.equal(await steps(page), paused, 'paused: no more steps');
    await page.locator('flock-path button.reset').click();
    assert.equal(await steps(page), 0);
    await button.click();
    await page.waitForFunction(() => window.flockpathEmbed.steps > 5);

    // "Open in flockpath" carries the same scene to index.html.
    const link = page.locator('#open-full');
    await link.hover();
    const href = await link.getAttribute('href');
    assert.match(href, /\/course\/demo\/flockpath\/index\.html#s=2\./);
    assert.equal(new URL(href).hash, `#s=${fragment}`);
    await screenshot(page, 'embed-page');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('a garbled embed link shows a message and a default scene still runs', async () => {
  const { page, errors, close } = await openPath('embed.html#s=2.garbled*link&autoplay=1', { ready });
  try {
    const message = await shadow(page, '.message');
    assert.ok(message, 'a message is shown');
    assert.match(message, /could not be loaded: .*(base64|damaged|cut short)/);
    assert.match(message, /showing “pillars” instead/i);
    await page.waitForFunction(() => window.flockpathEmbed.steps > 10);
    await screenshot(page, 'embed-garbled');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
