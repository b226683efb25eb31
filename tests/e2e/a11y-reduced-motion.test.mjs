// prefers-reduced-motion (issue #15 item 1): a reader who asked the system for less motion gets
// a playground, a compare page, the tune page's preview and embeds (embed.html with autoplay,
// <flock-path autoplay> in the course notes) that start paused; Play still plays. Without the preference they play as before.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, frames, openPath } from './helpers.mjs';

/** Opens `file`, then reloads it with `prefers-reduced-motion: reduce` emulated. */
async function openReduced(file, ready) {
  const opened = await openPath(file, { ready });
  // Let the first load's fetches finish: a reload would abort them (a "request failed" error).
  await opened.page.waitForLoadState('networkidle');
  await opened.page.emulateMedia({ reducedMotion: 'reduce' });
  await opened.page.reload();
  await opened.page.waitForFunction(ready, null, { timeout: 30_000 });
  assert.equal(await opened.page.evaluate(() => matchMedia('(prefers-reduced-motion: reduce)').matches), true);
  return opened;
}

test('reduced motion: the playground and compare start paused; Play plays', async () => {
  let opened = await openReduced('index.html', () => window.flockpath !== undefined);
  try {
    const { page } = opened;
    await frames(page, 10);
    assert.equal(await page.evaluate(() => window.flockpath.isPlaying()), false, 'the playground starts paused');
    assert.equal(await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.metrics().steps)), 0, 'no step ran');
    assert.equal(await page.textContent('#play'), 'Play');
    assert.equal(await page.getAttribute('#play', 'aria-pressed'), 'false');
    await page.click('#play');
    await page.waitForFunction(() => window.flockpath.metrics().steps > 0);
    assertNoUnexpectedErrors(opened.errors);
  } finally {
    await opened.close();
  }

  opened = await openReduced('compare.html', () => window.flockpathCompare !== undefined);
  try {
    const { page } = opened;
    await frames(page, 10);
    assert.equal(await page.evaluate(() => window.flockpathCompare.isPlaying()), false, 'compare starts paused');
    assert.deepEqual(await page.evaluate(async () => (await window.flockpathCompare.settled(), [...new Set(window.flockpathCompare.steps())])), [0]);
    await page.click('#play');
    await page.waitForFunction(() => window.flockpathCompare.steps()[0] > 0);
    assertNoUnexpectedErrors(opened.errors);
  } finally {
    await opened.close();
  }
});

test('reduced motion: the tune preview shows its first frame and waits; its Play plays', async () => {
  const opened = await openReduced('tune.html', () => window.flocktune !== undefined);
  try {
    const { page } = opened;
    await page.waitForFunction(() => window.flocktune.state().previewFrames > 0);
    const before = await page.evaluate(() => window.flocktune.state());
    await frames(page, 20);
    const after = await page.evaluate(() => window.flocktune.state());
    assert.equal(after.previewPlaying, false, 'the preview starts paused');
    assert.equal(after.previewSteps, 0, 'no preview step ran');
    assert.equal(after.previewFrames, before.previewFrames, 'a paused preview is not repainted every frame');
    assert.equal(await page.textContent('#preview-play'), 'Play');
    assert.equal(await page.getAttribute('#preview-play', 'aria-pressed'), 'false');
    await page.click('#preview-play');
    await page.waitForFunction(() => window.flocktune.state().previewSteps > 0);
    assert.equal(await page.textContent('#preview-play'), 'Pause');
    assert.equal(await page.getAttribute('#preview-play', 'aria-pressed'), 'true');
    await page.click('#preview-play');
    const paused = await page.evaluate(() => window.flocktune.state().previewSteps);
    await frames(page, 10);
    assert.equal(await page.evaluate(() => window.flocktune.state().previewSteps), paused, 'Pause stops it again');
    assertNoUnexpectedErrors(opened.errors);
  } finally {
    await opened.close();
  }
});

test('reduced motion: embeds with autoplay start paused; without the preference they play', async () => {
  const embedReady = () => window.flockpathEmbed !== undefined;
  let opened = await openPath('embed.html#autoplay=1', { ready: embedReady });
  try {
    await opened.page.waitForFunction(() => window.flockpathEmbed.steps > 0);
    assert.equal(await opened.page.evaluate(() => window.flockpathEmbed.playing), true, 'autoplay plays by default');
  } finally {
    await opened.close();
  }

  opened = await openReduced('embed.html#autoplay=1', embedReady);
  try {
    const { page } = opened;
    await frames(page, 10);
    assert.equal(await page.evaluate(() => window.flockpathEmbed.playing), false, 'the embed waits for Play');
    assert.equal(await page.evaluate(() => window.flockpathEmbed.steps), 0);
    await page.evaluate(() => window.flockpathEmbed.shadowRoot.querySelector('.play').click());
    await page.waitForFunction(() => window.flockpathEmbed.steps > 0);
    assertNoUnexpectedErrors(opened.errors);
  } finally {
    await opened.close();
  }

  const booted = () => {
    const els = [...document.querySelectorAll('flock-path')];
    return els.length > 0 && els.every((el) => el.sim);
  };
  opened = await openReduced('examples/course-notes.html', booted);
  try {
    const { page } = opened;
    await frames(page, 10);
    const states = await page.evaluate(() =>
      [...document.querySelectorAll('flock-path')].map((el) => ({ autoplay: el.hasAttribute('autoplay'), playing: el.playing, steps: el.steps })),
    );
    assert.ok(states.some((s) => s.autoplay), `the notes have autoplay elements: ${JSON.stringify(states)}`);
    assert.ok(states.every((s) => !s.playing && s.steps === 0), `every element waits for Play: ${JSON.stringify(states)}`);
    assertNoUnexpectedErrors(opened.errors);
  } finally {
    await opened.close();
  }
});
