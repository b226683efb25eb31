// The MyST example (examples/myst-course-notes/, issue 28): mystmd from npm builds the page of course
// notes, whose two `{anywidget}` directives name the book's one-line module that imports
// flockpath's widget from another site; the
// built page's widgets render and run in Chromium with no kernel, the locked one with its activity,
// and a widget stepped 300 times gives the CLI's digest.
//
// The MyST book theme is downloaded from the MyST site at build time, which these machines cannot
// reach: the example builds with `myst build --site` and a stand-in theme whose page
// (stand-in-theme/page.js) renders the built content's widgets by the anywidget contract, as the
// book theme does. What is real: mystmd's directive and build, the built content, the widget
// module and its element, served cross-origin with CORS as a course site would use them.

import assert from 'node:assert/strict';
import { execFile } from 'node:child_process';
import { promisify } from 'node:util';
import { cp, mkdir, mkdtemp, readFile, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { after, before, test } from 'node:test';
import { chromium } from 'playwright-core';
import { serveStatic } from '../../scripts/static-server.mjs';
import { ARTIFACTS, CHROMIUM_ARGS, ROOT, WWW } from '../e2e/helpers.mjs';
import { cliDigest } from '../notebook/jupyter-helpers.mjs';

const EXAMPLE = path.join(ROOT, 'examples', 'myst-course-notes');
const PLACEHOLDER = 'https://example.org/flockpath/';

let dir;
let flockpath;
let book;
let context;

before(async () => {
  dir = await mkdtemp(path.join(tmpdir(), 'flockpath-myst-'));
  // flockpath on one site (CORS), the book on another, as a course would host them.
  flockpath = await serveStatic({ '/flockpath/': WWW }, { cors: true, cacheControl: 'no-store' });
  await cp(EXAMPLE, dir, { recursive: true, filter: (source) => !source.includes('node_modules') && !source.includes('_build') });
  // The book's one-line module names where flockpath is hosted: here, the server above.
  const loader = path.join(dir, 'flockpath-widget.mjs');
  const source = await readFile(loader, 'utf8');
  assert.ok(source.includes(`'${PLACEHOLDER}js/widget.js'`), 'the example imports the widget from its placeholder site');
  await writeFile(loader, source.replaceAll(PLACEHOLDER, `${flockpath.origin}/flockpath/`));
  // Not execFileSync: mystmd requests the module's URL, which this process serves.
  await promisify(execFile)(path.join(EXAMPLE, 'node_modules', '.bin', 'myst'), ['build', '--site', '--ci'], { cwd: dir, timeout: 120_000 });
  const site = path.join(dir, '_build', 'site');
  for (const file of ['page.html', 'page.js']) await cp(path.join(dir, 'stand-in-theme', file), path.join(site, file));
  // The theme serves the site's public/ (the copied modules) at the root, the pages beside it.
  book = await serveStatic({ '/': path.join(site, 'public'), '/notes/': site }, { cacheControl: 'no-store' });
  context = await chromium.launchPersistentContext(await mkdtemp(path.join(tmpdir(), 'flockpath-myst-chromium-')), {
    executablePath: '/usr/bin/chromium',
    headless: true,
    args: CHROMIUM_ARGS,
    viewport: { width: 900, height: 1400 },
  });
});

after(async () => {
  await context?.close();
  await book?.close();
  await flockpath?.close();
  if (dir) await rm(dir, { recursive: true, force: true });
});

test('mystmd builds the anywidget directives into the page content', async () => {
  const content = JSON.parse(await readFile(path.join(dir, '_build', 'site', 'content', 'index.json'), 'utf8'));
  const widgets = [];
  const walk = (node) => {
    if (node?.type === 'anywidget') widgets.push(node);
    for (const child of node?.children ?? []) walk(child);
  };
  walk(content.mdast);
  assert.equal(widgets.length, 2);
  // mystmd copies the directive's module into the site; the copy imports flockpath's by URL.
  assert.equal(widgets[0].esm, widgets[1].esm);
  const built = await readFile(path.join(dir, '_build', 'site', 'public', path.basename(widgets[0].esm)), 'utf8');
  assert.ok(built.includes(`'${flockpath.origin}/flockpath/js/widget.js'`), built);
  assert.equal(widgets[0].model.scene, 'pillars');
  assert.match(widgets[1].model.scene, /^2\./, 'the second: an activity link');
  assert.equal(widgets[1].model.lock, 'obstacles,goals,groups,paths');
});

test('the built page: two widgets render and run with no kernel, the CLI digest', { timeout: 120_000 }, async () => {
  const page = context.pages()[0] ?? (await context.newPage());
  const errors = [];
  page.on('pageerror', (error) => errors.push(error.message));
  page.on('console', (msg) => msg.type() === 'error' && errors.push(msg.text()));
  await page.goto(`${book.origin}/notes/page.html`);
  await page
    .waitForFunction(() => document.querySelectorAll('flock-path').length === 2 && window.mystWidgets?.length === 2, null, { timeout: 60_000 })
    .catch((error) => assert.fail(`${error.message}; page errors: ${errors.join(' | ')}`));
  await page.evaluate(() => Promise.all([...document.querySelectorAll('flock-path')].map((el) => el.ready)));

  const first = await page.evaluate(async () => {
    const el = document.querySelectorAll('flock-path')[0];
    const buttons = [...el.shadowRoot.querySelectorAll('.bar button')].filter((b) => !b.hidden).map((b) => b.className);
    await el.step(300);
    return { name: el.scene().name, steps: el.steps, digest: el.digest(), buttons };
  });
  assert.equal(first.name, 'pillars');
  assert.deepEqual(first.buttons, ['play', 'step', 'reset']);
  assert.equal(first.steps, 300);
  assert.equal(first.digest, cliDigest('pillars', 300), 'the CLI digest');

  // The reader presses Play on the locked activity: it runs, on its own, and tells its model.
  const second = page.locator('flock-path').nth(1);
  assert.equal(await second.locator('.activity').count(), 1, 'the activity card is shown');
  // As a student: an answer, locked in (the run waits for it), then Play.
  await second.getByText('None: the whisker turns every agent in time').click();
  await second.getByRole('button', { name: 'Lock in my prediction' }).click();
  if (!(await page.evaluate(() => document.querySelectorAll('flock-path')[1].playing))) await second.locator('button.play').click();
  await page.waitForFunction(() => document.querySelectorAll('flock-path')[1].steps > 30, null, { timeout: 30_000 }).catch(async (error) => {
    await page.screenshot({ path: path.join(ARTIFACTS, 'myst-book-failed.png'), fullPage: true });
    const seen = await page.evaluate(() => {
      const el = document.querySelectorAll('flock-path')[1];
      return { steps: el.steps, playing: el.playing, card: el.shadowRoot.querySelector('.activity')?.innerText };
    });
    assert.fail(`${error.message}: ${JSON.stringify(seen)}; errors: ${errors.join(' | ')}`);
  });
  await page.waitForFunction(() => window.mystWidgets[1].get('steps') > 0, null, { timeout: 10_000 });
  await page.waitForFunction((digest) => window.mystWidgets[0].get('digest') === digest, first.digest, { timeout: 10_000 }).catch(() => {});
  const state = await page.evaluate(() => {
    const [a, b] = [...document.querySelectorAll('flock-path')];
    return { classroom: b.classroom(), firstSteps: a.steps, model: window.mystWidgets[1].snapshot(), firstModel: window.mystWidgets[0].snapshot() };
  });
  assert.equal(state.firstSteps, 300, 'the first widget did not move with the second');
  assert.equal(state.model.playing, true, 'Play written back to the model');
  assert.match(state.model.digest, /^[0-9a-f]{16}$/);
  assert.equal(state.firstModel.digest, first.digest, 'the first model holds the digest the widget reported');
  assert.deepEqual(state.classroom.lock, ['obstacles', 'goals', 'groups', 'paths']);
  assert.ok(state.model.activity_report, 'the activity report reaches the model');
  await mkdir(ARTIFACTS, { recursive: true });
  await page.screenshot({ path: path.join(ARTIFACTS, 'myst-book.png'), fullPage: true });
  assert.deepEqual(errors, []);
});
