// Cold load of the playground (issue 29 §1): a fresh browser profile per run opens index.html
// from the project's server and this prints, as medians over the runs, when the first frame was
// drawn (the first putImageData on the page's canvas, ms after navigation start), the main
// thread's CPU time until then, and the bytes the server sent until the page was ready and until
// the offline service worker had cached the folder.
//
//   node scripts/bench-cold-load.mjs [--runs 7] [--www DIR] [--before DIR [--before-plain]] [--json FILE]
//
// --before DIR: the same runs on that copy of the page too, alternated with www/ so both see the
// same machine load; --before-plain serves it as the project's server did before issue 29 (no
// compression, no validators). Chromium runs under `taskset -c 0` when taskset exists.

import { chmod, mkdtemp, rm, writeFile } from 'node:fs/promises';
import { execFileSync } from 'node:child_process';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { CHROMIUM_ARGS } from './chromium.mjs';
import { serveStatic } from './static-server.mjs';

const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const args = process.argv.slice(2);
const flag = (name, fallback) => {
  const i = args.indexOf(name);
  return i >= 0 && i + 1 < args.length ? args[i + 1] : fallback;
};
const RUNS = Number(flag('--runs', '7'));
const WWW = path.resolve(flag('--www', path.join(ROOT, 'www')));
const BEFORE = flag('--before', null) && path.resolve(flag('--before'));
const PLAIN = args.includes('--before-plain');

const tmp = await mkdtemp(path.join(tmpdir(), 'flockpath-cold-'));
let executablePath = '/usr/bin/chromium';
try {
  const taskset = execFileSync('sh', ['-c', 'command -v taskset'], { encoding: 'utf8' }).trim();
  executablePath = path.join(tmp, 'chromium-on-core-0.sh');
  await writeFile(executablePath, `#!/bin/sh\nexec ${taskset} -c 0 /usr/bin/chromium "$@"\n`);
  await chmod(executablePath, 0o755);
} catch {
  console.error('[bench-cold-load] taskset not found: Chromium runs unpinned');
}

/** A server per variant, each counting the body bytes it sends. */
async function variant(name, dir, options) {
  const counter = { bytes: 0, requests: 0 };
  const server = await serveStatic({ '/': dir }, {
    ...options,
    log: (line) => {
      const m = / (\d{3})(?: (\d+) bytes)?/.exec(line);
      if (m) {
        counter.requests += 1;
        counter.bytes += Number(m[2] ?? 0);
      }
    },
  });
  return { name, server, counter, runs: [] };
}

// Records, in the page, when the first frame reached the canvas (works on any version of the page).
const FIRST_FRAME_PROBE = () => {
  const put = CanvasRenderingContext2D.prototype.putImageData;
  CanvasRenderingContext2D.prototype.putImageData = function (...a) {
    if (window.__firstFrame === undefined && this.canvas.id === 'scene-canvas') window.__firstFrame = performance.now();
    return put.apply(this, a);
  };
};

async function coldRun(v) {
  const profile = await mkdtemp(path.join(tmp, 'profile-'));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath, headless: true, args: CHROMIUM_ARGS, viewport: { width: 1280, height: 800 },
  });
  try {
    const page = context.pages()[0] ?? (await context.newPage());
    await page.addInitScript(FIRST_FRAME_PROBE);
    const cdp = await context.newCDPSession(page);
    await cdp.send('Performance.enable', { timeDomain: 'threadTicks' });
    v.counter.bytes = 0;
    v.counter.requests = 0;
    await page.goto(`${v.server.origin}/index.html`, { waitUntil: 'commit' });
    await page.waitForFunction(() => window.__firstFrame !== undefined, null, { timeout: 60_000, polling: 20 });
    const firstFrame = await page.evaluate(() => window.__firstFrame);
    const { metrics } = await cdp.send('Performance.getMetrics');
    const cpu = 1000 * (metrics.find((m) => m.name === 'TaskDuration')?.value ?? NaN);
    const bytesAtFrame = v.counter.bytes;
    await page.evaluate(async () => (navigator.serviceWorker ? navigator.serviceWorker.ready : null));
    await page.waitForTimeout(300);
    return { first_frame_ms: firstFrame, main_cpu_ms: cpu, bytes_at_first_frame: bytesAtFrame, bytes_first_visit: v.counter.bytes, requests: v.counter.requests };
  } finally {
    await context.close().catch(() => {});
    await rm(profile, { recursive: true, force: true });
  }
}

const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : 0.5 * (s[s.length / 2 - 1] + s[s.length / 2]);
};

const variants = [];
if (BEFORE) variants.push(await variant('before', BEFORE, PLAIN ? { compress: false, validators: false } : {}));
variants.push(await variant(BEFORE ? 'after' : 'www', WWW, {}));
try {
  for (let run = 0; run < RUNS; run += 1) {
    for (const v of variants) v.runs.push(await coldRun(v));
  }
} finally {
  for (const v of variants) await v.server.close();
  await rm(tmp, { recursive: true, force: true });
}

const load = (await import('node:os')).loadavg()[0].toFixed(2);
console.log(`cold load of index.html, ${RUNS} runs each (fresh profile, Chromium on core 0), medians; load average ${load}`);
const cols = ['first frame ms', 'main CPU ms', 'KiB at frame', 'KiB first visit', 'requests'];
console.log(`${''.padEnd(8)}${cols.map((c) => c.padStart(17)).join('')}`);
const summary = {};
for (const v of variants) {
  const m = (key) => median(v.runs.map((r) => r[key]));
  summary[v.name] = {
    first_frame_ms: m('first_frame_ms'), main_cpu_ms: m('main_cpu_ms'), bytes_at_first_frame: m('bytes_at_first_frame'),
    bytes_first_visit: m('bytes_first_visit'), requests: m('requests'), runs: v.runs,
  };
  const s = summary[v.name];
  const row = [s.first_frame_ms.toFixed(0), s.main_cpu_ms.toFixed(0), (s.bytes_at_first_frame / 1024).toFixed(0), (s.bytes_first_visit / 1024).toFixed(0), String(s.requests)];
  console.log(`${v.name.padEnd(8)}${row.map((c) => c.padStart(17)).join('')}`);
}
if (BEFORE) {
  const ratio = summary.before.first_frame_ms / summary.after.first_frame_ms;
  console.log(`first frame before/after: ${ratio.toFixed(2)}×`);
}
const jsonFile = flag('--json', null);
if (jsonFile) await writeFile(jsonFile, `${JSON.stringify({ load_average: Number(load), runs: RUNS, ...summary }, null, 2)}\n`);
