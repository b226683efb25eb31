// Offline: after one visit, the playground, the embed page and the course-notes example open and
// run with the network cut (Playwright's offline mode, and the server refusing every request), all
// served under a sub-path; a new build (a changed file, precache list rewritten by
// scripts/precache.mjs) replaces the cache of the old version.
//
// The folder is served from a copy (the new-build case edits it) by scripts/static-server.mjs,
// made to drop every connection while "down".

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { appendFile, cp, mkdtemp, readFile, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { chromium } from 'playwright-core';
import { CHROMIUM_ARGS, ROOT, SUB_PATH, WWW, assertNoUnexpectedErrors, waitReady } from './helpers.mjs';
import { serveStatic } from '../../scripts/static-server.mjs';

/** Serves `dir` at SUB_PATH (scripts/static-server.mjs); `down = true` makes it drop every request unanswered. */
async function serve(dir) {
  const state = { down: false, servedWhileDown: 0, requests: [] };
  const server = await serveStatic(
    { [SUB_PATH]: dir },
    {
      onRequest: (req) => {
        if (state.down) {
          state.servedWhileDown += 1;
          req.socket.destroy();
          return false;
        }
        state.requests.push(decodeURIComponent(new URL(req.url, 'http://x').pathname));
        return true;
      },
    },
  );
  return { state, url: `${server.origin}${SUB_PATH}`, close: server.close };
}

/** The flockpath caches of the origin: `{ name: [listed paths relative to the scope] }`. */
async function cacheContents(page) {
  return page.evaluate(async () => {
    const out = {};
    for (const name of await caches.keys()) {
      if (!name.startsWith('flockpath ')) continue;
      const cache = await caches.open(name);
      const scope = name.split(' ')[1];
      out[name] = (await cache.keys()).map((r) => r.url.slice(scope.length)).sort();
    }
    return out;
  });
}

/** The version scripts/precache.mjs wrote into `dir`. */
async function versionIn(dir) {
  const text = await readFile(path.join(dir, 'pkg', 'precache.js'), 'utf8');
  return /"version":\s*"([0-9a-f]+)"/.exec(text)[1];
}

const playgroundRuns = async (page) => {
  await waitReady(page);
  const before = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.metrics().steps));
  await page.evaluate(() => window.flockpath.play());
  await page.waitForFunction((n) => window.flockpath.metrics().steps > n + 10, before, { timeout: 20_000 });
};

test('after one visit the pages open offline, under a sub-path, and a new build replaces the cache', async () => {
  const tmp = await mkdtemp(path.join(tmpdir(), 'flockpath-offline-'));
  const www = path.join(tmp, 'www');
  // Without the precompressed copies: a copy gets new times, so a stale one could look fresh.
  await cp(WWW, www, { recursive: true, filter: (src) => !/\.(br|gz)$/.test(src) });
  const server = await serve(www);
  const context = await chromium.launchPersistentContext(path.join(tmp, 'profile'), {
    executablePath: '/usr/bin/chromium',
    headless: true,
    args: CHROMIUM_ARGS,
    viewport: { width: 1100, height: 800 },
    serviceWorkers: 'allow',
  });
  const page = context.pages()[0] ?? (await context.newPage());
  const errors = [];
  let offline = false;
  page.on('console', (msg) => {
    if (msg.type() === 'error') errors.push(`${offline ? 'offline ' : ''}console: ${msg.text()}`);
  });
  page.on('pageerror', (error) => errors.push(`page error: ${error.message}`));
  try {
    // First visit, online: the worker installs with every listed file.
    await page.goto(`${server.url}index.html`);
    await waitReady(page);
    const scope = await page.evaluate(async () => {
      const registration = await window.flockpathOffline;
      await navigator.serviceWorker.ready;
      return registration?.scope ?? null;
    });
    assert.equal(scope, server.url, 'the worker’s scope is the served folder, under its sub-path');
    const version = await versionIn(www);
    const caches1 = await cacheContents(page);
    assert.deepEqual(Object.keys(caches1), [`flockpath ${scope} ${version}`], 'one cache, named for this build');
    const listed = caches1[`flockpath ${scope} ${version}`];
    for (const file of ['index.html', 'embed.html', 'examples/course-notes.html', 'style.css', 'manifest.webmanifest',
      'icon.svg', 'js/flock-path.js', 'js/core/offline.js', 'js/play/main.js', 'pkg/flockpath.js', 'pkg/flockpath_bg.wasm',
      'activities.html', 'activities.css', 'js/activities/main.js', 'js/activities/library.js', 'js/activities/measured.js']) {
      assert.ok(listed.includes(file), `${file} is cached (cached: ${listed.join(', ')})`);
    }
    assert.ok(!listed.includes('sw.js') && !listed.includes('pkg/precache.js'), 'the worker and its list are not');

    // The network goes away: Playwright's offline mode, and the server drops whatever still reaches it.
    offline = true;
    await context.setOffline(true);
    server.state.down = true;

    // The playground, with a query string (the cache answers for the page without it).
    await page.goto(`${server.url}index.html?from=offline`);
    await playgroundRuns(page);
    assert.equal(await page.evaluate(() => navigator.onLine), false, 'the browser is offline');
    // The folder URL stands for its index.html.
    await page.goto(server.url);
    await playgroundRuns(page);

    // The embed page, with a preset scene and autoplay.
    await page.goto(`${server.url}embed.html#s=pillars&autoplay=1`);
    await page.waitForFunction(() => window.flockpathEmbed && window.flockpathEmbed.steps > 10, null, { timeout: 30_000 });
    assert.equal(await page.evaluate(() => window.flockpathEmbed.scene().name), 'pillars');

    // The course notes: both elements and the iframe of embed.html run.
    await page.goto(`${server.url}examples/course-notes.html`);
    await page.waitForFunction(
      () => {
        const els = [...document.querySelectorAll('flock-path')];
        return els.length === 2 && els.every((el) => el.sim && el.steps > 10);
      },
      null,
      { timeout: 30_000 },
    );
    await page.locator('#corridor').scrollIntoViewIfNeeded();
    await page.waitForFunction(() => {
      const frame = document.getElementById('corridor').contentWindow;
      return frame.flockpathEmbed && frame.flockpathEmbed.steps > 10;
    }, null, { timeout: 30_000 });
    // The Activities page, and an activity opened from it.
    await page.goto(`${server.url}activities.html`);
    await page.waitForFunction(() => window.flockpathActivities !== undefined, null, { timeout: 30_000 });
    await page.locator('a.activity-open').first().click();
    await page.locator('#activity .fp-activity .fp-prompt').waitFor({ timeout: 30_000 });
    assert.equal(server.state.requests.length > 0, true);
    assertNoUnexpectedErrors(errors);

    // Back online with a new build: a changed style sheet, the precache list rewritten as
    // scripts/build-wasm.sh does. The next visit installs it and drops the old cache.
    offline = false;
    server.state.down = false;
    await context.setOffline(false);
    await appendFile(path.join(www, 'style.css'), '\n/* offline test: a new build */\n');
    execFileSync(process.execPath, [path.join(ROOT, 'scripts', 'precache.mjs'), '--www', www]);
    const version2 = await versionIn(www);
    assert.notEqual(version2, version, 'a changed file gives a new version');
    await page.goto(`${server.url}index.html`);
    await waitReady(page);
    // (Polled from here: waitForFunction does not await a promise, and opening a cache creates it.)
    const wanted = [`flockpath ${scope} ${version2}`];
    const deadline = Date.now() + 30_000;
    let names = [];
    while (Date.now() < deadline) {
      names = await page.evaluate(async () => (await caches.keys()).filter((k) => k.startsWith('flockpath ')));
      if (names.length === 1 && names[0] === wanted[0]) break;
      await new Promise((resolve) => setTimeout(resolve, 250));
    }
    assert.deepEqual(names, wanted, 'the new build’s cache replaced the old one');
    const css = await page.evaluate(async ([name, url]) => {
      const response = await (await caches.open(name)).match(url);
      return response.text();
    }, [`flockpath ${scope} ${version2}`, `${server.url}style.css`]);
    assert.ok(css.includes('offline test: a new build'), 'the new cache holds the new build’s files');

    // And offline again, the new build is what opens.
    await context.setOffline(true);
    server.state.down = true;
    await page.goto(`${server.url}index.html`);
    await playgroundRuns(page);
    const sheet = await page.evaluate(async () => (await fetch('style.css')).text());
    assert.ok(sheet.includes('offline test: a new build'));
    assertNoUnexpectedErrors(errors);
  } finally {
    await context.close().catch(() => {});
    await server.close();
    await rm(tmp, { recursive: true, force: true });
  }
});
