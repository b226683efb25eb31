// docs/course-notes.md's web-page example, pasted as a course author would: its html block is
// served as a page of a course site on another origin (the flockpath folder's address put in for
// https://example.org/flockpath/), and what it promises happens: the element runs and its script
// steps it through the page API, the iframe says it is ready and answers postMessage.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import { ROOT, assertNoUnexpectedErrors, launchBrowser, startServer } from './helpers.mjs';
import { startHost } from './cross-origin-helpers.mjs';

/** The first ```html block of docs/course-notes.md. */
async function docsBlock() {
  const text = await readFile(path.join(ROOT, 'docs', 'course-notes.md'), 'utf8');
  const block = text.match(/```html\n([\s\S]*?)```/);
  assert.ok(block, 'docs/course-notes.md has an html example');
  return block[1];
}

test('the course-notes doc’s html example runs on a course page of another origin', async () => {
  const flockpath = await startServer({ cors: true });
  const block = (await docsBlock()).replaceAll('https://example.org/flockpath/', flockpath.url);
  assert.ok(block.includes(flockpath.url), 'the example points at the flockpath folder');
  const host = await startHost(new Map([['/week3.html', {
    headers: {},
    html: `<!doctype html><html lang="en"><head><meta charset="utf-8"><title>Week 3</title><link rel="icon" href="data:,"></head><body><h1>Week 3: crowds</h1>\n${block}\n</body></html>`,
  }]]));
  const launched = await launchBrowser({ viewport: { width: 1280, height: 900 } });
  const { page, errors, close } = launched;
  const logs = [];
  page.on('console', (msg) => logs.push(msg.text()));
  try {
    await page.goto(`${host.origin}/week3.html`);
    assert.notEqual(new URL(host.origin).origin, new URL(flockpath.url).origin, 'another origin');
    // The element's script stepped it to 60 and read its digest.
    await page.waitForFunction(() => { try { return document.getElementById('pillars').steps >= 60; } catch { return false; } }, null, { timeout: 60_000 });
    const deadline = Date.now() + 30_000;
    while (!logs.some((l) => /^element at step 60 digest [0-9a-f]{16}$/.test(l)) && Date.now() < deadline) await page.waitForTimeout(100);
    assert.ok(logs.some((l) => /^element at step 60 digest [0-9a-f]{16}$/.test(l)), `the element's script ran: ${logs.join(' | ')}`);
    // Only the controls named, and the locked parts said.
    const bar = await page.evaluate(() => {
      const root = document.getElementById('pillars').shadowRoot;
      const shown = (s) => Boolean(root.querySelector(s) && !root.querySelector(s).hidden);
      return { play: shown('.play'), step: shown('.step'), reset: shown('.reset'), planner: shown('.planner'), lock: document.getElementById('pillars').classroom().lock };
    });
    assert.deepEqual(bar, { play: true, step: true, reset: true, planner: false, lock: ['obstacles', 'goals'] });
    // The iframe said it was ready and answered the step request.
    await page.waitForFunction(() => document.title === 'iframe at step 60', null, { timeout: 60_000 });
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
    await host.close();
    await flockpath.close();
  }
});
