// A first visit to the playground (issue 29 §1): a fresh profile opens the page from the project's
// server (scripts/static-server.mjs, what serve.sh runs) and waits until the offline service worker
// has cached the folder. Everything the server sent for it (page, workers, the service worker's
// precache; bodies as sent, after compression) stays under 1 MB, the wasm is sent once (the page
// compiles it and hands the module to its worker; the precache revalidates it: 304), and every
// script, page and style sheet goes compressed. The figures are logged.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtemp, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { chromium } from 'playwright-core';
import { CHROMIUM_ARGS, WWW, assertNoUnexpectedErrors } from './helpers.mjs';
import { serveStatic } from '../../scripts/static-server.mjs';

/** The most a first visit may transfer (bytes): the issue's target. */
const FIRST_VISIT_BYTES = 1_000_000;

test('a first visit transfers under 1 MB, the wasm once, every text file compressed', async () => {
  const sent = [];
  const server = await serveStatic({ '/': WWW }, {
    log: (line) => {
      const m = /^GET (\S+) (\d{3})(?: (\d+) bytes(?: \((\w+)\))?)?$/.exec(line);
      if (m) sent.push({ path: m[1], status: Number(m[2]), bytes: Number(m[3] ?? 0), encoding: m[4] ?? null });
    },
  });
  const profile = await mkdtemp(path.join(tmpdir(), 'flockpath-cold-'));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: '/usr/bin/chromium', headless: true, args: CHROMIUM_ARGS, viewport: { width: 1280, height: 800 },
  });
  try {
    const page = context.pages()[0] ?? (await context.newPage());
    const errors = [];
    const warnings = [];
    page.on('console', (msg) => {
      if (msg.type() === 'error') errors.push(`console: ${msg.text()}`);
      if (msg.type() === 'warning') warnings.push(msg.text());
    });
    page.on('pageerror', (error) => errors.push(`page error: ${error.message}`));
    await page.goto(`${server.origin}/`);
    await page.waitForFunction(() => window.flockpath !== undefined, null, { timeout: 30_000 });
    await page.evaluate(() => window.flockpath.step(5));
    // The service worker is active once its install has cached every listed file.
    const active = await page.evaluate(async () => Boolean((await navigator.serviceWorker.ready).active));
    assert.ok(active, 'the offline service worker is active');
    const total = sent.reduce((sum, r) => sum + r.bytes, 0);
    const wasm = sent.filter((r) => r.path === '/pkg/flockpath_bg.wasm');
    const plainText = sent.filter((r) => r.status === 200 && !r.encoding && /\.(js|html|css|wasm|json)$|\/$/.test(r.path) && r.bytes >= 1024);
    console.log(`first visit: ${sent.length} requests, ${(total / 1024).toFixed(0)} KiB sent; wasm: ${wasm.map((r) => `${r.status} ${r.bytes} B ${r.encoding ?? ''}`).join(', ')}`);
    assert.ok(total <= FIRST_VISIT_BYTES, `a first visit sent ${total} bytes (at most ${FIRST_VISIT_BYTES})`);
    assert.equal(wasm.filter((r) => r.status === 200).length, 1, `the wasm is sent once: ${JSON.stringify(wasm)}`);
    assert.deepEqual(plainText, [], 'every text file of 1 KiB or more goes compressed');
    assert.deepEqual(warnings.filter((w) => /preload/i.test(w)), [], 'the wasm preload is used');
    assertNoUnexpectedErrors(errors);
  } finally {
    await context.close().catch(() => {});
    await server.close();
    await rm(profile, { recursive: true, force: true });
  }
});
