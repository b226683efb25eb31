// Shared setup for the end-to-end tests: a static server for www/ (under a sub-path, to prove the
// page uses only relative URLs), Debian's Chromium driven by playwright-core, console-error
// collection, and small helpers that talk to the page only through its public surface.

import { mkdtemp, mkdir, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { serveStatic } from '../../scripts/static-server.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
export const ROOT = path.resolve(here, '..', '..');
/** The folder served; FLOCKPATH_WWW points the tests at another copy of the page (a deploy dir). */
export const WWW = path.resolve(process.env.FLOCKPATH_WWW ?? path.join(ROOT, 'www'));
export const ARTIFACTS = path.join(ROOT, 'test-artifacts');
/** The page is served below this prefix, as a course site might host it. */
export const SUB_PATH = '/course/demo/flockpath/';

/** Chromium flags for a root user without network (see TOOLCHAIN.md). */
export const CHROMIUM_ARGS = [
  '--no-sandbox',
  '--disable-dev-shm-usage',
  '--disable-gpu',
  '--disable-quic',
  '--no-first-run',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
];

/**
 * Serves www/ at SUB_PATH on 127.0.0.1 and a free port (scripts/static-server.mjs, the server
 * serve.sh runs: compressed answers as users get them); resolves to { url, close }. Option `cors`:
 * send `Access-Control-Allow-Origin: *` (true, or a function of the path that says for which files).
 */
export async function startServer({ cors = false } = {}) {
  const server = await serveStatic({ [SUB_PATH]: WWW }, { cors, cacheControl: 'no-store' });
  return { url: `${server.origin}${SUB_PATH}`, close: server.close };
}

/**
 * Starts the server (`startServer`) and Chromium with a fresh profile, and collects the page's
 * console errors, page errors and (unless `requestFailures` is false) failed requests in
 * `errors`. `contextOptions` go to `launchPersistentContext` over the common ones (Debian's
 * Chromium, headless, CHROMIUM_ARGS). Returns { page, context, server, errors, close } where
 * `close()` tears everything down; nothing is opened yet.
 */
export async function launchBrowser(contextOptions = {}, { requestFailures = true, profilePrefix = 'flockpath-e2e-' } = {}) {
  const server = await startServer();
  const profile = await mkdtemp(path.join(tmpdir(), profilePrefix));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: '/usr/bin/chromium',
    headless: true,
    args: CHROMIUM_ARGS,
    ...contextOptions,
  });
  const page = context.pages()[0] ?? (await context.newPage());
  const errors = [];
  page.on('console', (msg) => {
    if (msg.type() === 'error') errors.push(`console: ${msg.text()}`);
  });
  page.on('pageerror', (error) => errors.push(`page error: ${error.message}`));
  if (requestFailures) page.on('requestfailed', (request) => errors.push(`request failed: ${request.url()}`));
  const close = async () => {
    await context.close().catch(() => {});
    await server.close();
    await rm(profile, { recursive: true, force: true });
  };
  return { page, context, server, errors, close };
}

/**
 * Opens `server.url + pathAndHash` in a browser from `launchBrowser` and, given `ready` (a
 * function evaluated in the page), waits until it returns true; on failure closes the browser and throws
 * `failure: …` with the page's errors.
 */
async function openIn(launched, pathAndHash, ready, failure) {
  const { page, server, errors, close } = launched;
  try {
    await page.goto(server.url + pathAndHash);
    if (ready) await page.waitForFunction(ready, null, { timeout: 30_000 });
  } catch (error) {
    await close();
    throw new Error(`${failure}: ${error.message}\n${errors.join('\n')}`);
  }
  return launched;
}

/**
 * Launches Chromium with a fresh profile, opens the page and waits for `flockpath-ready`.
 * Options: viewport, deviceScaleFactor, hasTouch, hash (appended to the URL), expectBootError,
 * serviceWorkers ('block' by default: only tests of the offline worker allow it).
 * Returns { page, context, server, errors, close } where `errors` collects console errors and
 * page errors; `close()` tears everything down.
 */
export async function openPage(options = {}) {
  const launched = await launchBrowser({
    viewport: options.viewport ?? { width: 1280, height: 800 },
    deviceScaleFactor: options.deviceScaleFactor ?? 1,
    hasTouch: options.hasTouch ?? false,
    isMobile: false,
    serviceWorkers: options.serviceWorkers ?? 'block',
  });
  return openIn(launched, options.hash ?? '', () => window.flockpath !== undefined, 'the page did not boot');
}

/** Resolves when `window.flockpath` exists (the page sets it after boot). */
export async function waitReady(page) {
  await page.waitForFunction(() => window.flockpath !== undefined, null, { timeout: 30_000 });
}

/** Pauses the playground and loads `scene` through its API (no step runs between: the pause is sent first). */
export async function loadPaused(page, scene) {
  await page.evaluate(async (s) => {
    await window.flockpath.pause();
    await window.flockpath.load(s);
  }, scene);
}

/**
 * Waits until the playground's simulation worker has answered everything sent so far (a click, a
 * key, a slider's edit): the page API's reads then show its effect.
 */
export async function settled(page) {
  await page.evaluate(() => window.flockpath.settled());
}

/** Waits until the page has painted `n` more animation frames. */
export async function frames(page, n = 2) {
  await page.evaluate(
    (count) =>
      new Promise((resolve) => {
        const tick = (left) => (left === 0 ? resolve() : requestAnimationFrame(() => tick(left - 1)));
        tick(count);
      }),
    n,
  );
}

/** Client (CSS) coordinates of a scene point, from the page's published view transform. */
export async function sceneToClient(page, x, y) {
  return page.evaluate(
    ([sx, sy]) => {
      const canvas = document.getElementById('scene-canvas');
      const rect = canvas.getBoundingClientRect();
      const { scale, offsetX, offsetY } = window.flockpath.view();
      return {
        x: rect.left + ((sx * scale + offsetX) * rect.width) / canvas.width,
        y: rect.top + ((sy * scale + offsetY) * rect.height) / canvas.height,
      };
    },
    [x, y],
  );
}

/**
 * Keeps a copy of the scene canvas's pixels in the page under `name` (shipping megabytes of
 * pixels to the test process is slow; only the sampled pixels travel, see `pixelsAt`).
 */
export async function snapshotCanvas(page, name) {
  await page.evaluate((key) => {
    const canvas = document.getElementById('scene-canvas');
    window.__e2eSnapshots ??= {};
    window.__e2eSnapshots[key] = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height);
  }, name);
}

/** `[r, g, b]` of snapshot `name` at each canvas pixel `{x, y}` (null outside the canvas). */
export async function pixelsAt(page, name, points) {
  return page.evaluate(([key, pts]) => {
    const image = window.__e2eSnapshots[key];
    return pts.map(({ x, y }) => {
      if (x < 0 || y < 0 || x >= image.width || y >= image.height) return null;
      const i = (y * image.width + x) * 4;
      return [image.data[i], image.data[i + 1], image.data[i + 2]];
    });
  }, [name, points]);
}

/** Canvas pixel coordinates (backing store) of a scene point. */
export async function sceneToCanvasPixel(page, x, y) {
  return page.evaluate(
    ([sx, sy]) => {
      const { scale, offsetX, offsetY } = window.flockpath.view();
      return { x: Math.round(sx * scale + offsetX), y: Math.round(sy * scale + offsetY) };
    },
    [x, y],
  );
}

/** Saves a screenshot under test-artifacts/ (git-ignored) and returns its path. */
export async function screenshot(page, name) {
  await mkdir(ARTIFACTS, { recursive: true });
  const file = path.join(ARTIFACTS, `${name}.png`);
  await page.screenshot({ path: file });
  return file;
}

/** The text of the message banner, or null when it is hidden. */
export async function bannerText(page) {
  return page.evaluate(() => {
    const banner = document.getElementById('banner');
    return banner && !banner.hidden ? document.getElementById('banner-text').textContent : null;
  });
}

/** A small scene: one group heading for one goal, no obstacles. */
export function simpleScene(overrides = {}) {
  return {
    name: 'e2e',
    width: 800,
    height: 500,
    seed: 7,
    obstacles: [],
    goals: [{ position: [700, 250], radius: 30 }],
    groups: [
      {
        name: 'flock',
        color: '#2f6fdf',
        count: 30,
        spawn: { min: [40, 200], max: [140, 300] },
        goal: 0,
        agent_radius: 4,
        planner: { kind: 'boids', params: {} },
      },
    ],
    ...overrides,
  };
}

/** Fails with every collected console/page error, except those matching `allowed` patterns. */
export function assertNoUnexpectedErrors(errors, allowed = []) {
  const unexpected = errors.filter((e) => !allowed.some((pattern) => pattern.test(e)));
  if (unexpected.length) {
    throw new Error(`unexpected errors in the page:\n${unexpected.join('\n')}`);
  }
}

/**
 * Like `openPage`, for any page of the folder: opens `SUB_PATH + pathAndHash` and waits until
 * `ready` (a function evaluated in the page) returns true; `hasTouch` and `serviceWorkers` as in
 * `openPage`. Returns the same handles.
 */
export async function openPath(pathAndHash, { ready, viewport, hasTouch = false, serviceWorkers = 'block' } = {}) {
  const launched = await launchBrowser({
    viewport: viewport ?? { width: 1280, height: 800 },
    hasTouch,
    acceptDownloads: true,
    serviceWorkers,
  });
  return openIn(launched, pathAndHash, ready, `${pathAndHash} did not load`);
}

/** axe-core (npm) for the accessibility audits. */
const AXE = path.join(ROOT, 'node_modules', 'axe-core', 'axe.min.js');

/** axe-core's violations of impact serious or critical on `page` as it is now, as readable lines. */
export async function seriousViolations(page) {
  if (!(await page.evaluate(() => typeof window.axe === 'object'))) await page.addScriptTag({ path: AXE });
  const violations = await page.evaluate(async () =>
    (await window.axe.run(document)).violations.map((v) => ({
      impact: v.impact,
      nodes: v.nodes.map((n) => `${v.id} (${v.impact}) at ${n.target.join(' ')}: ${n.failureSummary ?? ''}`),
    })));
  return violations.filter((v) => v.impact === 'serious' || v.impact === 'critical').flatMap((v) => v.nodes);
}
