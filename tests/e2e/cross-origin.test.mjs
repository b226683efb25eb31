// The `<flock-path>` snippet from the Share dialog, pasted into a course page on another origin.
// Works: served by scripts/static-server.mjs (what serve.sh runs), with and without the README's CSP.
// Fails readably: no CORS at all, a wrong URL (the module never runs: the snippet's own fallback
// text turns into the reason), CORS on the module only, the wasm blocked or missing, a CSP
// without 'wasm-unsafe-eval' (the element says why in its box and fires `flockpath-error`), and a
// bad scene (message in the box, `flockpath-error`, the first preset runs instead). The iframe
// snippet needs no CORS at all.

import { after, before, describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { createHash } from 'node:crypto';
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import { chromium } from 'playwright-core';
import { CHROMIUM_ARGS, ROOT, assertNoUnexpectedErrors, screenshot, simpleScene, startServer } from './helpers.mjs';
import { startHost, startDocumentedServer } from './cross-origin-helpers.mjs';
import { coveringCircles, timedPause } from './pause-helpers.mjs';

/** Host-page script (external, so a strict CSP allows it): records the element's events. */
const RECORDER = `window.flockpathEvents = [];
for (const type of ['flockpath-ready', 'flockpath-error']) {
  document.addEventListener(type, (e) => window.flockpathEvents.push({ type, detail: e.detail ?? null }));
}`;

const hostPage = (snippet, headers = {}) => ({
  headers,
  html: `<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>Week 3: crowds</title><link rel="icon" href="data:,">
<script src="/record.js"></script></head>
<body>
<h1>Week 3: crowds</h1><p>The simulation below is served by another site.</p>
${snippet}
<p>Text after the figure.</p></body></html>`,
});

/** The README's Content-Security-Policy for host pages, for a flockpath folder at `origin`. */
async function readmePolicy(origin) {
  const readme = await readFile(path.join(ROOT, 'README.md'), 'utf8');
  const line = readme.split('\n').find((l) => l.startsWith("script-src 'self' https://flockpath.example"));
  assert.ok(line, 'README.md gives the CSP for host pages');
  // The host page's own policy for everything else.
  return `default-src 'self'; img-src data:; ${line.replaceAll('https://flockpath.example', origin)}`;
}

/** 1,000 Boids among 5,000 circles that all cover the world: each step takes ~0.4 s (worker-pause). */
const HEAVY = simpleScene({
  name: 'heavy-covering-circles',
  width: 1000,
  height: 1000,
  obstacles: coveringCircles(5_000, 1000),
  goals: [{ position: [900, 900], radius: 60 }],
  groups: [{ ...simpleScene().groups[0], count: 1_000, spawn: { min: [600, 600], max: [980, 980] } }],
});

/** The snippet's own message when the module never runs. */
const MODULE_REFUSED = /^The flockpath simulation could not be loaded: the browser refused or could not find http:\S+\.js\.$/;

/** What the reader sees of the element: its shadow message, or its fallback text before upgrade. */
function visibleMessage() {
  const el = document.querySelector('flock-path');
  const box = el.getBoundingClientRect();
  const shown = (node) => node && node.checkVisibility() && node.textContent.trim() !== '';
  const shadow = el.shadowRoot?.querySelector('.message');
  const fallback = el.querySelector('[data-flockpath-status]');
  let where = null;
  let text = null;
  if (shown(shadow)) [where, text] = ['shadow', shadow.textContent];
  else if (!el.shadowRoot && shown(fallback)) [where, text] = ['fallback', fallback.textContent];
  if (!text) return null;
  const rect = (where === 'shadow' ? shadow : fallback).getBoundingClientRect();
  const inside =
    rect.top >= box.top - 1 && rect.bottom <= box.bottom + 1 && rect.left >= box.left - 1 && rect.right <= box.right + 1;
  return { where, text, inside, defined: customElements.get('flock-path') !== undefined };
}

/** Pixel statistics of the element's canvas: distinct colours and pixels near the group colour. */
function canvasStats() {
  const canvas = document.querySelector('flock-path').shadowRoot.querySelector('canvas');
  const data = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
  const colours = new Set();
  let group = 0;
  for (let i = 0; i < data.length; i += 4) {
    colours.add((data[i] << 16) | (data[i + 1] << 8) | data[i + 2]);
    if (Math.abs(data[i] - 0x2f) < 40 && Math.abs(data[i + 1] - 0x6f) < 40 && Math.abs(data[i + 2] - 0xdf) < 40) group++;
  }
  return { width: canvas.width, height: canvas.height, colours: colours.size, group };
}

describe('the <flock-path> snippet on a page of another origin', () => {
  let documented;
  let flock;
  let host;
  let browser;
  let context;
  let snippet;
  let iframeSnippet;
  let playgroundDigest;
  /** Which paths the flockpath test server sends CORS headers for (changed per case). */
  let corsFor = () => true;
  let pageCount = 0;

  before(async () => {
    documented = await startDocumentedServer();
    flock = await startServer({ cors: (pathname) => corsFor(pathname) });
    host = await startHost(new Map([['/record.js', RECORDER]]));
    browser = await chromium.launch({ executablePath: '/usr/bin/chromium', headless: true, args: CHROMIUM_ARGS });
    context = await browser.newContext({ viewport: { width: 1000, height: 800 } });

    // The snippet exactly as the Share dialog hands it out, from the playground served by static-server.mjs.
    const page = await context.newPage();
    await page.goto(`${documented.url}index.html`);
    await page.waitForFunction(() => window.flockpath !== undefined, null, { timeout: 30_000 });
    playgroundDigest = await page.evaluate(async (scene) => {
      await window.flockpath.pause();
      await window.flockpath.load(scene);
      await window.flockpath.step(40);
      return window.flockpath.digest();
    }, simpleScene());
    await page.locator('#share').click();
    snippet = await page.locator('#share-component').inputValue();
    iframeSnippet = await page.locator('#share-iframe').inputValue();
    await page.close();
    assert.ok(snippet.includes(`src="${documented.url}js/flock-path.js"`), snippet);
  });

  after(async () => {
    await browser?.close();
    await host?.close();
    await flock?.close();
    await documented?.close();
  });

  /** Opens `page` ({ html, headers }) on the host origin; returns { page, errors, warnings }. */
  async function openHostPage(page) {
    const name = `/notes-${++pageCount}.html`;
    host.pages.set(name, page);
    const tab = await context.newPage();
    const errors = [];
    const warnings = [];
    tab.on('console', (msg) => {
      if (msg.type() === 'error') errors.push(`console: ${msg.text()}`);
      if (msg.type() === 'warning') warnings.push(msg.text());
    });
    tab.on('pageerror', (error) => errors.push(`page error: ${error.message}`));
    await tab.goto(host.origin + name);
    return { page: tab, errors, warnings };
  }

  /** The snippet pointed at the flockpath test server (sub-path, CORS switchable) instead of static-server.mjs. */
  const onTestServer = (text) => text.replaceAll(documented.url, flock.url);

  /** Waits for the message in the element's box; checks it is there for the reader and returns it. */
  async function waitForMessage(page, pattern) {
    const handle = await page.waitForFunction(visibleMessage, null, { timeout: 30_000 });
    const message = await handle.jsonValue();
    assert.match(message.text, pattern);
    assert.ok(message.inside, `the message lies inside the element's box: ${JSON.stringify(message)}`);
    return message;
  }

  test('served by static-server.mjs, the element renders, fires flockpath-ready and its methods work', async () => {
    // Wrapped in <p> as a Markdown tool that does not know the tag does: its fallback stays inside.
    const { page, errors } = await openHostPage(hostPage(`<p>${snippet}</p>`));
    try {
      await page.waitForFunction(() => window.flockpathEvents.some((e) => e.type === 'flockpath-ready'), null, { timeout: 30_000 });
      await page.waitForFunction(() => document.querySelector('flock-path').steps > 5);
      const stats = await page.evaluate(canvasStats);
      assert.ok(stats.width > 100 && stats.height > 100, JSON.stringify(stats));
      assert.ok(stats.colours > 3, `the canvas is not blank: ${JSON.stringify(stats)}`);
      assert.ok(stats.group > 50, `the group's agents are drawn: ${JSON.stringify(stats)}`);
      const result = await page.evaluate(async () => {
        const el = document.querySelector('flock-path');
        await el.pause();
        const before = el.steps;
        await el.step(5);
        const stepped = el.steps - before;
        await el.reset();
        await el.step(40);
        return { stepped, name: el.scene().name, digest: el.digest(), arrived: el.metrics().arrived_share, string: el.sceneString() };
      });
      assert.equal(result.stepped, 5);
      assert.equal(result.name, 'e2e', 'the scene came with the snippet');
      assert.equal(result.digest, playgroundDigest, 'the same run as in the playground');
      assert.equal(typeof result.arrived, 'number');
      assert.ok(snippet.includes(result.string), 'the snippet carries the scene string');
      // Upgraded: the fallback text is no longer shown (nor left outside the element), and no message is.
      assert.equal(await page.locator('flock-path > [data-flockpath-status]').count(), 1);
      assert.equal(await page.getByText('Loading the flockpath simulation').isVisible(), false);
      assert.equal(await page.getByText('Open this scene in flockpath').isVisible(), false);
      assert.equal(await page.evaluate(visibleMessage), null);
      assert.ok(!(await page.evaluate(() => window.flockpathEvents.some((e) => e.type === 'flockpath-error'))));
      await screenshot(page, 'cross-origin-works');
      assertNoUnexpectedErrors(errors);
    } finally {
      await page.close();
    }
  });

  test('on another origin the element steps in a worker (from a blob): Pause within 100 ms in a heavy scene, the native digest', { timeout: 120_000 }, async () => {
    const { page, errors } = await openHostPage(hostPage(snippet));
    try {
      await page.waitForFunction(() => window.flockpathEvents.some((e) => e.type === 'flockpath-ready'), null, { timeout: 30_000 });
      // The worker was started from a same-origin blob (a worker script must be same-origin).
      const worker = await page.evaluate(() => {
        const remote = document.querySelector('flock-path').host.remote;
        return { isWorker: remote.worker instanceof Worker, origin: location.origin };
      });
      assert.equal(worker.isWorker, true, 'the element runs its simulation in a Worker');
      assert.notEqual(worker.origin, new URL(documented.url).origin, 'the host page is on another origin');
      // The golden link (tests/golden_url.rs pins its native digest at step 300).
      const goldenUrl = (await readFile(path.join(ROOT, 'tests', 'data', 'golden-url.txt'), 'utf8')).trim();
      const goldenDigest = (await readFile(path.join(ROOT, 'tests', 'data', 'golden-digest.txt'), 'utf8')).trim();
      const digest = await page.evaluate(async (url) => {
        const el = document.querySelector('flock-path');
        await el.pause();
        await el.load(url);
        await el.step(300);
        return el.digest();
      }, goldenUrl);
      assert.equal(digest, goldenDigest, 'the same digest as the native run');
      // A scene of ~0.4 s steps: the host page's Pause is answered at once while the worker steps.
      await page.evaluate(async (scene) => {
        const el = document.querySelector('flock-path');
        await el.load(scene);
      }, HEAVY);
      const times = [];
      for (let round = 0; round < 3; round += 1) {
        await page.evaluate(() => document.querySelector('flock-path').play());
        await page.waitForFunction(() => !document.querySelector('flock-path').shadowRoot.querySelector('.slow-scene').hidden, null, { timeout: 30_000 });
        times.push(await timedPause(page, null, { element: 'flock-path' }));
        await page.evaluate(() => document.querySelector('flock-path').settled());
      }
      const median = [...times].sort((a, b) => a - b)[1];
      console.log(`cross-origin <flock-path>, heavy scene: Pause answered in ${times.map((t) => t.toFixed(0)).join(', ')} ms`);
      assert.ok(median <= 100, `Pause took ${median.toFixed(0)} ms (median of ${times.map((t) => t.toFixed(0)).join(', ')})`);
      assertNoUnexpectedErrors(errors);
    } finally {
      await page.close();
    }
  });

  test('with a CSP without worker-src blob:, the box says the worker could not start and why', async () => {
    const readme = await readmePolicy(new URL(documented.url).origin);
    const csp = readme.replace(/; worker-src [^;]*/, '');
    assert.notEqual(csp, readme, 'the README gives worker-src');
    const { page } = await openHostPage(hostPage(snippet, { 'content-security-policy': csp }));
    try {
      const message = await waitForMessage(page, /^The simulation could not start in its worker: .+ must allow worker-src blob: and the flockpath origin/);
      assert.equal(message.where, 'shadow');
      const events = await page.evaluate(() => window.flockpathEvents);
      assert.deepEqual(events.map((e) => e.type), ['flockpath-error']);
      await screenshot(page, 'cross-origin-worker-refused');
    } finally {
      await page.close();
    }
  });

  test('with the CSP the README gives, the element runs and is styled', async () => {
    const csp = await readmePolicy(new URL(documented.url).origin);
    const { page, errors } = await openHostPage(hostPage(snippet, { 'content-security-policy': csp }));
    try {
      await page.waitForFunction(() => window.flockpathEvents.some((e) => e.type === 'flockpath-ready'), null, { timeout: 30_000 });
      await page.waitForFunction(() => document.querySelector('flock-path').steps > 5);
      assert.ok((await page.evaluate(canvasStats)).group > 50);
      // The element's own style applies under style-src 'self' (a constructed sheet, not <style>).
      const play = await page.evaluate(
        () => getComputedStyle(document.querySelector('flock-path').shadowRoot.querySelector('.play')).backgroundColor,
      );
      assert.equal(play, 'rgb(47, 111, 223)');
      assertNoUnexpectedErrors(errors);
    } finally {
      await page.close();
    }
  });

  test('with the wasm served as application/octet-stream, the element still runs (compiled after download)', async () => {
    corsFor = () => true;
    await context.route('**/pkg/flockpath_bg.wasm', async (route) => {
      const response = await route.fetch();
      await route.fulfill({ response, headers: { ...response.headers(), 'content-type': 'application/octet-stream' } });
    });
    const { page, errors, warnings } = await openHostPage(hostPage(onTestServer(snippet)));
    try {
      await page.waitForFunction(() => window.flockpathEvents.some((e) => e.type === 'flockpath-ready'), null, { timeout: 30_000 });
      await page.waitForFunction(() => document.querySelector('flock-path').steps > 5);
      assert.ok((await page.evaluate(canvasStats)).group > 50);
      assert.ok(warnings.some((w) => w.includes('application/wasm')), `the glue's fallback was taken: ${warnings}`);
      assertNoUnexpectedErrors(errors);
    } finally {
      await page.close();
      await context.unroute('**/pkg/flockpath_bg.wasm');
    }
  });

  test('with a CSP without wasm-unsafe-eval, the box says the WebAssembly could not start', async () => {
    const readme = await readmePolicy(new URL(documented.url).origin);
    const csp = readme.replace(" 'wasm-unsafe-eval'", '');
    assert.notEqual(csp, readme);
    const { page } = await openHostPage(hostPage(snippet, { 'content-security-policy': csp }));
    try {
      const message = await waitForMessage(
        page,
        /could not be loaded: .*flockpath_bg\.wasm could not be started as WebAssembly .*must allow 'wasm-unsafe-eval'/,
      );
      assert.equal(message.where, 'shadow');
      const events = await page.evaluate(() => window.flockpathEvents);
      assert.deepEqual(events.map((e) => e.type), ['flockpath-error']);
      assert.equal(events[0].detail, message.text);
    } finally {
      await page.close();
    }
  });

  // The module itself never runs: only the snippet's fallback text and its error handler speak.
  for (const [label, cors, edit] of [
    ['without any CORS header', () => false, (text) => text],
    ['from a wrong URL (404)', () => true, (text) => text.replace('/js/flock-path.js', '/js/no-such-module.js')],
  ]) {
    test(`served ${label}, the fallback text turns into the reason`, async () => {
      corsFor = cors;
      const { page } = await openHostPage(hostPage(onTestServer(edit(snippet))));
      try {
        const message = await waitForMessage(page, MODULE_REFUSED);
        assert.deepEqual([message.where, message.defined], ['fallback', false]);
        // The link to the playground stays offered.
        const link = await page.locator('flock-path a').getAttribute('href');
        assert.ok(link.startsWith(flock.url) && link.includes('#s='), link);
        assert.deepEqual(await page.evaluate(() => window.flockpathEvents), []);
        await screenshot(page, `cross-origin-blocked-${cors() ? '404' : 'cors'}`);
      } finally {
        await page.close();
      }
    });
  }

  test('when scripts do not run at all, the fallback text and link are shown', async () => {
    const noScript = await browser.newContext({ javaScriptEnabled: false });
    try {
      const name = `/notes-${++pageCount}.html`;
      host.pages.set(name, hostPage(snippet));
      const page = await noScript.newPage();
      await page.goto(host.origin + name);
      assert.equal(await page.locator('[data-flockpath-status]').textContent(), 'Loading the flockpath simulation…');
      assert.ok(await page.locator('[data-flockpath-status]').isVisible());
      assert.ok(await page.locator('flock-path a', { hasText: 'Open this scene in flockpath' }).isVisible());
    } finally {
      await noScript.close();
    }
  });

  // The module runs but what it loads is refused: the element says so in its box and fires the event.
  const corsHint = /\. This page is on another site than flockpath: the flockpath server must send Access-Control-Allow-Origin/;
  for (const [label, cors, pattern, hint] of [
    ['CORS on the modules of js/ only (not on pkg/)', (p) => p.includes('/js/'), /refused or could not find http:\S+\/pkg\/flockpath\.js \(/, true],
    ['the wasm without CORS', (p) => !p.endsWith('.wasm'), /refused or could not fetch http:\S+\/pkg\/flockpath_bg\.wasm \(/, true],
    ['the wasm missing (404)', () => true, /http:\S+\/pkg\/flockpath_bg\.wasm could not be loaded \([^)]*404 Not Found\)\.$/, false],
  ]) {
    test(`with ${label}, the box says what failed and flockpath-error fires`, async () => {
      corsFor = cors;
      const missingWasm = label.includes('404');
      const notFound = { status: 404, headers: { 'access-control-allow-origin': '*' }, body: 'not found' };
      if (missingWasm) await context.route('**/pkg/flockpath_bg.wasm', (route) => route.fulfill(notFound));
      const { page } = await openHostPage(hostPage(onTestServer(snippet)));
      try {
        const message = await waitForMessage(page, pattern);
        assert.match(message.text, /^The flockpath simulation could not be loaded: /);
        assert.equal(corsHint.test(message.text), hint, 'the CORS hint for the page author, where it applies');
        assert.equal(message.where, 'shadow');
        const events = await page.evaluate(() => window.flockpathEvents);
        assert.deepEqual(events.map((e) => e.type), ['flockpath-error']);
        assert.equal(events[0].detail, message.text);
        // The message stays (a click does not leave a blank box); no dead controls beside it.
        await page.locator('flock-path .message').click();
        assert.ok(await page.locator('flock-path .message').isVisible());
        assert.equal(await page.locator('flock-path .play').isVisible(), false);
        await screenshot(page, `cross-origin-${label.replace(/[^a-z0-9]+/gi, '-')}`);
      } finally {
        await page.close();
        if (missingWasm) await context.unroute('**/pkg/flockpath_bg.wasm');
      }
    });
  }

  test('the iframe snippet needs no CORS; when its wasm is missing it says so and keeps its link', async () => {
    corsFor = () => false;
    const iframe = onTestServer(iframeSnippet).replace('loading="lazy"', '');
    for (const missingWasm of [false, true]) {
      const notFound = { status: 404, body: 'not found' };
      if (missingWasm) await context.route('**/pkg/flockpath_bg.wasm', (route) => route.fulfill(notFound));
      const { page } = await openHostPage(hostPage(iframe));
      try {
        const frame = await (await page.waitForSelector('iframe')).contentFrame();
        if (!missingWasm) {
          await frame.waitForFunction(() => window.flockpathEmbed?.steps > 5, null, { timeout: 30_000 });
          assert.equal(await frame.evaluate(() => window.flockpathEmbed.scene().name), 'e2e');
        } else {
          const message = frame.locator('flock-path .message');
          await message.waitFor({ timeout: 30_000 });
          assert.match(await message.textContent(), /flockpath_bg\.wasm could not be loaded \([^)]*404/);
          assert.ok(await frame.locator('#open-full').isVisible(), 'the link to the full page stays');
          assert.equal(await frame.locator('flock-path .play').isVisible(), false);
        }
      } finally {
        await page.close();
        if (missingWasm) await context.unroute('**/pkg/flockpath_bg.wasm');
      }
    }
  });

  test('with a bad scene, the box shows the core message, flockpath-error fires and the first preset runs', async () => {
    const bad = snippet.replace(/ scene="[^"]*"/, ' scene="no-such-preset"');
    assert.notEqual(bad, snippet);
    const { page } = await openHostPage(hostPage(bad));
    try {
      const message = await waitForMessage(page, /^The scene could not be loaded: [\s\S]+\. Showing “\S+” instead\.$/);
      assert.equal(message.where, 'shadow');
      const events = await page.evaluate(() => window.flockpathEvents);
      assert.deepEqual(events.map((e) => e.type), ['flockpath-error', 'flockpath-ready']);
      assert.ok(message.text.includes(events[0].detail.replace(/[.?!]$/, '')), 'the core message is shown');
      await page.waitForFunction(() => document.querySelector('flock-path').steps > 5);
    } finally {
      await page.close();
    }
  });

  test('a CSP that refuses the module but allows the handler by the README’s hash gets the message', async () => {
    const handler = /onerror="([^"]*)"/.exec(snippet)?.[1];
    assert.ok(handler, snippet);
    const hash = `sha256-${createHash('sha256').update(handler).digest('base64')}`;
    const readme = await readFile(path.join(ROOT, 'README.md'), 'utf8');
    assert.ok(readme.includes(`'unsafe-hashes' '${hash}'`), `README.md should name ${hash}`);
    // The README's policy for a flockpath folder elsewhere: the CSP refuses this one's module.
    const csp = await readmePolicy('https://flockpath.example');
    const { page } = await openHostPage(hostPage(snippet, { 'content-security-policy': csp }));
    try {
      const message = await waitForMessage(page, MODULE_REFUSED);
      assert.match(message.text, /\/js\/flock-path\.js\.$/);
      assert.equal(message.where, 'fallback');
    } finally {
      await page.close();
    }
  });
});
