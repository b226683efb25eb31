// The SCORM package against a real SCORM 1.2 runtime: the example of docs/course-notes.md is
// built with the CLI (`flockpath scorm`), unzipped into a temporary folder and served with a host
// page that plays the LMS: it loads scorm-again's SCORM 1.2 runtime (npm devDependency) as
// `window.API` and iframes the package's launch page. In headless Chromium a student plays the
// activity (Play, the prediction, the run to its check); the test reads what the runtime recorded
// (`cmi.core.lesson_status`, `cmi.core.score.raw`, `cmi.suspend_data`, LMSFinish), reopens the
// SCO with that state and checks the prediction is restored, and opens the package with no
// runtime around it to see it work as the embed view. The playground's Export → LMS package,
// which builds the zip in the browser from the files the page fetches, gives the CLI's bytes.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { createServer } from 'node:http';
import { copyFile, mkdtemp, readFile, rm, stat, writeFile } from 'node:fs/promises';
import { homedir, tmpdir } from 'node:os';
import path from 'node:path';
import { chromium } from 'playwright-core';
import { ARTIFACTS, assertNoUnexpectedErrors, CHROMIUM_ARGS, openPage, ROOT, screenshot, WWW } from './helpers.mjs';

/** The link of the `flockpath scorm --link '…'` example in docs/course-notes.md. */
async function documentedLink() {
  const doc = await readFile(path.join(ROOT, 'docs', 'course-notes.md'), 'utf8');
  const match = doc.match(/^flockpath scorm --link '([^']+)'/m);
  assert.ok(match, 'docs/course-notes.md has the `flockpath scorm --link` example');
  return match[1];
}

/** Runs the flockpath CLI (built by cargo if needed) with `args`; returns its stdout. */
function flockpath(args) {
  const env = { ...process.env, PATH: `${path.join(homedir(), '.cargo', 'bin')}:${process.env.PATH}` };
  return execFileSync('cargo', ['run', '--quiet', '--bin', 'flockpath', '--', ...args], { cwd: ROOT, env, encoding: 'utf8' });
}

const MIME = { '.html': 'text/html; charset=utf-8', '.js': 'text/javascript; charset=utf-8', '.json': 'application/json', '.wasm': 'application/wasm', '.xml': 'application/xml' };

/** Serves `dir` on 127.0.0.1 (a free port) as an LMS would serve an unpacked package. */
async function serve(dir) {
  const server = createServer(async (req, res) => {
    const file = path.join(dir, decodeURIComponent(new URL(req.url, 'http://x').pathname));
    if (!file.startsWith(dir)) return res.writeHead(403).end();
    try {
      if (!(await stat(file)).isFile()) throw new Error('not a file');
      res.writeHead(200, { 'content-type': MIME[path.extname(file)] ?? 'application/octet-stream', 'cache-control': 'no-store' });
      res.end(await readFile(file));
    } catch {
      res.writeHead(404).end('not found');
    }
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  return { url: `http://127.0.0.1:${server.address().port}/`, close: () => new Promise((resolve) => server.close(resolve)) };
}

/**
 * The host page: `startLms(state)` makes scorm-again's SCORM 1.2 runtime `window.API` (with
 * `state`, a previous attempt's cmi, loaded first as an LMS does on resume), records every call
 * the SCO makes in `window.lmsCalls`, and iframes the launch page.
 */
const HOST_PAGE = `<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>LMS stand-in</title><link rel="icon" href="data:,">
<script src="scorm12.js"></script>
<script>
window.lmsCalls = [];
window.startLms = (state) => {
  const api = new Scorm12API({ autocommit: false, logLevel: 5 });
  if (state) api.loadFromJSON(state, '');
  for (const name of ['LMSInitialize', 'LMSGetValue', 'LMSSetValue', 'LMSCommit', 'LMSFinish']) {
    const real = api[name].bind(api);
    api[name] = (...args) => { const result = real(...args); window.lmsCalls.push([name, ...args, result]); return result; };
  }
  window.API = api;
  const frame = document.createElement('iframe');
  frame.src = 'sco/activity.html';
  frame.title = 'the activity';
  frame.style.cssText = 'width: 900px; height: 700px; border: 0';
  document.body.append(frame);
};
window.cmi = () => ({ lesson_status: API.cmi.core.lesson_status, score_raw: API.cmi.core.score.raw, score_max: API.cmi.core.score.max, suspend_data: API.cmi.suspend_data });
// cmi.core.exit is write-only in SCORM 1.2: what the SCO set is read from the calls.
window.lastSet = (element) => window.lmsCalls.filter(([name, el]) => name === 'LMSSetValue' && el === element).map(([, , value]) => value).pop() ?? null;
</script></head><body></body></html>`;

/** The SCO's frame once its simulation is ready. */
async function scoFrame(page) {
  await page.waitForFunction(() => document.querySelector('iframe')?.contentWindow?.flockpathEmbed, null, { timeout: 60_000 });
  const frame = page.frames().find((f) => f.url().includes('/sco/embed.html'));
  assert.ok(frame, 'the launch page forwarded to the embed view');
  return frame;
}

const card = 'flock-path .fp-activity';

/**
 * The documented package built by the CLI, unzipped beside the host page and scorm-again, served,
 * and Chromium with a fresh profile. Returns { page, server, errors, close }.
 */
async function hostedPackage() {
  const link = await documentedLink();
  const dir = await mkdtemp(path.join(tmpdir(), 'flockpath-scorm-'));
  const zip = path.join(dir, 'crossing-scorm.zip');
  const printed = flockpath(['scorm', '--link', link, '--www', WWW, '--out', zip]);
  assert.match(printed, /SCORM 1\.2, \d+ files/);
  execFileSync('python3', ['-m', 'zipfile', '-e', zip, path.join(dir, 'sco')]);
  await writeFile(path.join(dir, 'lms.html'), HOST_PAGE);
  await copyFile(path.join(ROOT, 'node_modules', 'scorm-again', 'dist', 'scorm12.js'), path.join(dir, 'scorm12.js'));
  const server = await serve(dir);
  const profile = await mkdtemp(path.join(tmpdir(), 'flockpath-scorm-profile-'));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: '/usr/bin/chromium',
    headless: true,
    args: CHROMIUM_ARGS,
    viewport: { width: 1000, height: 800 },
    serviceWorkers: 'block',
  });
  const page = context.pages()[0] ?? (await context.newPage());
  const errors = [];
  page.on('console', (msg) => {
    if (msg.type() === 'error') errors.push(`console: ${msg.text()}`);
  });
  page.on('pageerror', (error) => errors.push(`page error: ${error.message}`));
  const close = async () => {
    await context.close().catch(() => {});
    await server.close();
    await rm(profile, { recursive: true, force: true });
    await rm(dir, { recursive: true, force: true });
  };
  return { page, server, errors, dir, zip, close };
}

test('a SCORM package reports completion, score and the prediction to scorm-again, and restores the prediction', { timeout: 300_000 }, async () => {
  const { page, server, errors, dir, zip, close } = await hostedPackage();
  try {
    // The zip's central directory lists what the manifest lists.
    const listing = execFileSync('python3', ['-m', 'zipfile', '-l', zip], { encoding: 'utf8' });
    const names = listing.split('\n').slice(1).map((l) => l.trim().split(/\s+/)[0]).filter(Boolean).sort();
    const manifest = await readFile(path.join(dir, 'sco', 'imsmanifest.xml'), 'utf8');
    const listed = [...manifest.matchAll(/<file href="([^"]+)"\/>/g)].map((m) => m[1]).concat('imsmanifest.xml').sort();
    assert.deepEqual(listed, names);
    assert.ok(names.includes('pkg/flockpath_bg.wasm') && names.includes('js/core/scorm.js'), names.join(' '));

    // First visit: a student opens the activity in the LMS.
    await page.goto(`${server.url}lms.html`);
    await page.evaluate(() => window.startLms(null));
    let sco = await scoFrame(page);
    await page.waitForFunction(() => window.lmsCalls.some(([name]) => name === 'LMSCommit'));
    assert.equal((await page.evaluate(() => window.cmi())).lesson_status, 'incomplete', 'opened: incomplete');
    assert.equal(await sco.locator('#open-full').count(), 0, 'no link to a playground the package does not hold');

    // Play asks the prediction first; the student picks "At least half" (the expected answer).
    await sco.click('flock-path .play');
    await sco.locator(`${card} label.fp-choice`, { hasText: 'At least half' }).click();
    await sco.click(`${card} .fp-lock`);
    await page.waitForFunction(() => window.API.cmi.suspend_data !== '', null, { timeout: 10_000 });
    assert.deepEqual(JSON.parse((await page.evaluate(() => window.cmi())).suspend_data), { answer: 1 });

    // The run plays to its check (met at step 316 of 600 for this scene and seed).
    await page.waitForFunction(() => window.API.cmi.core.lesson_status === 'passed', null, { timeout: 120_000 });
    const graded = await page.evaluate(() => window.cmi());
    assert.equal(String(graded.score_raw), '100', 'check met (50) + the expected prediction (50)');
    assert.equal(String(graded.score_max), '100');
    assert.match(await sco.locator(`${card} .fp-status`).innerText(), /316/);
    await page.screenshot({ path: path.join(ARTIFACTS, 'scorm-lms-graded.png') }).catch(() => {});

    // Leaving the page: suspend, commit, finish.
    await page.evaluate(() => document.querySelector('iframe').remove());
    await page.waitForFunction(() => window.lmsCalls.some(([name]) => name === 'LMSFinish'), null, { timeout: 10_000 });
    const finished = await page.evaluate(() => window.cmi());
    assert.equal(await page.evaluate(() => window.lastSet('cmi.core.exit')), 'suspend');
    const calls = await page.evaluate(() => window.lmsCalls.map((call) => [call[0], call[call.length - 1]]));
    assert.deepEqual(calls.filter(([name]) => name === 'LMSInitialize').length, 1);
    assert.ok(calls.every(([name, result]) => name === 'LMSGetValue' || String(result) === 'true'), JSON.stringify(calls));
    const failedSets = await page.evaluate(() => window.lmsCalls.filter(([name, , , result]) => name === 'LMSSetValue' && String(result) !== 'true'));
    assert.deepEqual(failedSets, [], 'every value set is one scorm-again accepts');

    // Reopening: the LMS resumes the attempt with what it stored.
    const stored = { cmi: { core: { lesson_status: finished.lesson_status, score: { raw: finished.score_raw } }, suspend_data: finished.suspend_data } };
    await page.goto(`${server.url}lms.html`);
    await page.evaluate((state) => window.startLms(state), stored);
    sco = await scoFrame(page);
    await page.waitForFunction(() => window.lmsCalls.some(([name]) => name === 'LMSCommit'));
    await sco.locator(`${card} .fp-predicted`).waitFor({ state: 'visible' });
    assert.match(await sco.locator(`${card} .fp-predicted`).innerText(), /At least half/, 'the prediction is restored');
    assert.equal(await sco.locator(`${card} .fp-prediction input`).count(), 0, 'not asked again');
    assert.equal((await page.evaluate(() => window.cmi())).lesson_status, 'passed', 'a reopened passed attempt stays passed');
    // Play now plays at once: the question is answered.
    await sco.click('flock-path .play');
    await sco.waitForFunction(() => window.flockpathEmbed.metrics().steps > 0, null, { timeout: 10_000 });
    await page.screenshot({ path: path.join(ARTIFACTS, 'scorm-lms-reopened.png') }).catch(() => {});

    // Outside an LMS: the package's launch page alone works as the embed view.
    await page.goto(`${server.url}sco/activity.html`);
    await page.waitForFunction(() => window.flockpathEmbed, null, { timeout: 60_000 });
    assert.equal(await page.evaluate(() => window.flockpathScorm), null, 'no runtime found, nothing connected');
    await page.click('flock-path .play');
    assert.equal(await page.locator(`${card} .fp-prediction input`).count(), 2, 'the question is asked as always');
    const unexpected = errors.filter((e) => !/sw\.js|service ?worker/i.test(e));
    assert.deepEqual(unexpected, []);
  } finally {
    await close();
  }
});

test('a wrong prediction with the check met passes with 50', { timeout: 300_000 }, async () => {
  const { page, server, errors, close } = await hostedPackage();
  try {
    await page.goto(`${server.url}lms.html`);
    await page.evaluate(() => window.startLms(null));
    const sco = await scoFrame(page);
    await sco.click('flock-path .play');
    await sco.locator(`${card} label.fp-choice`, { hasText: 'Under half' }).click();
    await sco.click(`${card} .fp-lock`);
    await page.waitForFunction(() => window.API.cmi.core.score.raw !== '', null, { timeout: 120_000 });
    const graded = await page.evaluate(() => window.cmi());
    assert.equal(graded.lesson_status, 'passed', 'the check decides the status');
    assert.equal(String(graded.score_raw), '50', 'check met (50), prediction wrong (0)');
    assert.deepEqual(JSON.parse(graded.suspend_data), { answer: 0 });
    assert.deepEqual(errors.filter((e) => !/sw\.js|service ?worker/i.test(e)), []);
  } finally {
    await close();
  }
});

test('Export → LMS package builds in the browser, with the Share dialog\'s options, the same zip as the CLI', { timeout: 300_000 }, async () => {
  const link = await documentedLink();
  const dir = await mkdtemp(path.join(tmpdir(), 'flockpath-scorm-page-'));
  const zip = path.join(dir, 'cli.zip');
  flockpath(['scorm', '--link', link, '--www', WWW, '--out', zip]);
  // The teacher opens the scene unlocked and ticks the link's options under Share… → Lock….
  const fragment = link.slice(link.indexOf('#') + 1);
  const options = Object.fromEntries(fragment.split('&').map((part) => part.split('=')));
  const { page, errors, close } = await openPage({ hash: `#s=${options.s}` });
  try {
    await page.evaluate((wanted) => {
      for (const box of document.querySelectorAll('#share-lock input[data-classroom]')) {
        const [field, name] = box.dataset.classroom.split(':');
        box.checked = (wanted[field] ?? '').split(',').includes(name);
        box.dispatchEvent(new Event('change'));
      }
    }, { controls: options.controls, lock: options.lock, hide: options.hide });
    await page.click('#export');
    await page.locator('#export-scorm').waitFor({ state: 'visible' });
    await screenshot(page, 'scorm-export-dialog');
    const [download] = await Promise.all([page.waitForEvent('download', { timeout: 60_000 }), page.click('#export-scorm')]);
    assert.match(download.suggestedFilename(), /-scorm\.zip$/);
    const fromPage = await readFile(await download.path());
    const fromCli = await readFile(zip);
    assert.ok(fromPage.length > 1_000_000, `a package with the wasm (${fromPage.length} bytes)`);
    assert.ok(fromPage.equals(fromCli), `the page's zip (${fromPage.length} bytes) is the CLI's (${fromCli.length} bytes)`);
    assert.match(await page.textContent('#export-status'), /-scorm\.zip/);

    // A scene without an activity is refused in words, and nothing downloads.
    await page.evaluate(async () => {
      await window.flockpath.load('pillars');
    });
    const fetched = [];
    page.on('request', (request) => fetched.push(request.url()));
    await page.click('#export-scorm');
    await page.waitForFunction(() => /Not exported/.test(document.querySelector('#export-status').textContent));
    assert.match(await page.textContent('#export-status'), /Not exported: .*no activity/);
    assert.deepEqual(fetched.filter((url) => url.endsWith('.wasm')), [], 'refused before fetching the files');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
    await rm(dir, { recursive: true, force: true });
  }
});
