// Benchmarks the real playground (www/index.html, not a page made for benchmarking) in headless
// Chromium pinned to one core: for every planner, 1,000 / 10,000 / 100,000 agents spread over the
// field and packed in a 120×200 px spawn region, played with the default panels open (metrics,
// per-group table, plots, timeline). Prints per case: fps (median and 5th percentile, from
// requestAnimationFrame), simulated steps per second, the latency of a Pause click (from the
// pointerdown event to the button's state changing, and to the next frame), the page's
// main-thread share per function (top five, self time, from a CDP Profiler profile) and the cost
// of one `flockpath.metrics()` call. Beside the wall-clock figures: the main thread's CPU time
// per frame played and per paused step (CDP `Performance.getMetrics` ThreadTime), which other
// processes on the core do not inflate: 1000 / (cpu ms per frame) is about the fps the page
// reaches with the core to itself, and the step's CPU time bounds the wait of a click.
//
// Usage: node scripts/bench-page.mjs [--seconds S] [--planners boids,pso,orca,social_force] [--sizes 1000,10000]
//          [--layouts spread,packed] [--no-profile] [--json FILE] [--www DIR] [--before DIR]
// --before DIR: runs every case on that copy of the page too, right before the same case on
// www/, so a before/after comparison sees the same machine load (printed as two rows).
// Chromium is started through `taskset -c 0` (when taskset exists), so the page and the
// browser's helpers share one core whatever core this script runs on.
//
// Scenes come from the `open-field` preset through the page API (`flockpath.load`): one group,
// its count set to N, its planner to each planner with default parameters, the field (and its
// goal) scaled to the density of the kernel benchmark (`flockpath bench`: about 9 neighbours
// within the 50 px perception radius) at the preset's 8:5 shape. "spread": the spawn region is
// the whole field; "packed": a square at the left with room for 1.5 bodies per agent (the spawn
// keeps bodies apart, so this is about as dense as a scene can start). A scene the page refuses
// prints "refused: <message>"; a case whose one step would take seconds is skipped and says why.

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
  return i >= 0 && args[i + 1] !== undefined ? args[i + 1] : fallback;
};
/** The folder served: www/ unless --www points at another copy (a before/after comparison). */
const WWW = path.resolve(flag('--www', path.join(ROOT, 'www')));
const PLANNERS = ['boids', 'pso', 'firefly', 'forces', 'igsa', 'orca', 'social_force', 'collision_free_speed'];
const SIZES = [1000, 10000, 100000];
const LAYOUTS = ['spread', 'packed'];
const VIEWPORT = { width: 1280, height: 800 };
/** Longest a case may keep the page busy before it is abandoned (ms). */
const CASE_LIMIT_MS = 90_000;
/** A step slower than this (ms) at 10,000 agents skips the 100,000-agent case of that row. */
const SKIP_100K_WHEN_10K_STEP_MS = 150;
/** Pause clicks per case. */
const CLICKS = 3;

const list = (name, fallback) => flag(name, fallback.join(',')).split(',').filter(Boolean);
const seconds = Number(flag('--seconds', '3'));
// `social-force` as the page's menu spells it is `social_force` in a scene.
const planners = list('--planners', PLANNERS).map((p) => p.replace(/-/g, '_'));
const sizes = list('--sizes', SIZES.map(String)).map(Number);
const layouts = list('--layouts', LAYOUTS);
const profiling = !args.includes('--no-profile');
const jsonFile = flag('--json', null);
const BEFORE = flag('--before', null) && path.resolve(flag('--before'));
/** Width of the planner column: the longest name asked for (`social_force`), at least 8. */
const NAME_W = Math.max(8, ...planners.map((p) => p.length));

const server = await serveStatic(BEFORE ? { '/': WWW, '/before/': BEFORE } : { '/': WWW });
const origin = server.origin;
const VARIANTS = BEFORE ? [['before', `${origin}/before/index.html`], ['after', `${origin}/index.html`]] : [['', `${origin}/index.html`]];

// Chromium through `taskset -c 0`: a wrapper script as the executable (Playwright appends its
// own flags, so taskset cannot simply be the executable).
const profileDir = await mkdtemp(path.join(tmpdir(), 'flockpath-bench-page-'));
let executablePath = '/usr/bin/chromium';
let pinned = false;
try {
  const taskset = execFileSync('sh', ['-c', 'command -v taskset'], { encoding: 'utf8' }).trim();
  executablePath = path.join(profileDir, 'chromium-on-core-0.sh');
  await writeFile(executablePath, `#!/bin/sh\nexec ${taskset} -c 0 /usr/bin/chromium "$@"\n`);
  await chmod(executablePath, 0o755);
  pinned = true;
} catch {
  console.error('[bench-page] taskset not found: Chromium runs unpinned');
}

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
const withTimeout = (promise, ms, what) =>
  Promise.race([promise, sleep(ms).then(() => { throw new Error(`${what} took more than ${ms / 1000} s`); })]);
const median = (xs) => {
  if (xs.length === 0) return NaN;
  const s = [...xs].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : 0.5 * (s[s.length / 2 - 1] + s[s.length / 2]);
};
const quantile = (xs, q) => {
  if (xs.length === 0) return NaN;
  const s = [...xs].sort((a, b) => a - b);
  return s[Math.min(s.length - 1, Math.max(0, Math.ceil(q * s.length) - 1))];
};

let context = null;
let page = null;
async function launch() {
  context = await chromium.launchPersistentContext(path.join(profileDir, 'profile'), {
    executablePath,
    headless: true,
    args: CHROMIUM_ARGS,
    viewport: VIEWPORT,
    // The offline service worker would add its fetch handler to every request: not what is measured.
    serviceWorkers: 'block',
  });
  page = context.pages()[0] ?? (await context.newPage());
}
async function relaunch() {
  await withTimeout(context.close(), 20_000, 'closing Chromium').catch(() => {});
  await launch();
}

/** Opens a fresh page and installs the in-page probes (Pause-click latency). */
async function freshPage(url) {
  await page.goto(url);
  await page.waitForFunction(() => window.flockpath !== undefined, null, { timeout: 60_000 });
  await page.evaluate(() => {
    const bench = { downAt: null, clicks: [] };
    window.__benchPage = bench;
    addEventListener('pointerdown', (e) => {
      if (e.target?.id === 'play') bench.downAt = e.timeStamp;
    }, true);
    const button = document.getElementById('play');
    new MutationObserver(() => {
      if (bench.downAt === null || button.getAttribute('aria-pressed') !== 'false') return;
      const changed = performance.now();
      const downAt = bench.downAt;
      bench.downAt = null;
      requestAnimationFrame(() => {
        bench.clicks.push({ handled: changed - downAt, frame: performance.now() - downAt });
      });
    }).observe(button, { attributes: true, childList: true, characterData: true, subtree: true });
  });
}

/** The scene of one case, built in the page from the `open-field` preset. */
async function loadScene(planner, n, layout) {
  return page.evaluate(async ([planner, n, layout]) => {
    const module = await import('./pkg/flockpath.js');
    const scene = JSON.parse(module.preset_scene_json('open-field'));
    const density = 9 / (Math.PI * 50 * 50);
    const width = Math.sqrt((n / density) * 1.6);
    const height = width / 1.6;
    const [sx, sy] = [width / scene.width, height / scene.height];
    scene.width = width;
    scene.height = height;
    for (const goal of scene.goals) {
      goal.position = [goal.position[0] * sx, goal.position[1] * sy];
      goal.radius *= Math.sqrt(sx * sy);
    }
    const group = scene.groups[0];
    group.count = n;
    group.planner = { kind: planner, params: {} };
    const side = Math.sqrt(n * 1.5) * 2 * group.agent_radius;
    group.spawn = layout === 'spread'
      ? { min: [10, 10], max: [width - 10, height - 10] }
      : { min: [40, height / 2 - side / 2], max: [40 + side, height / 2 + side / 2] };
    const started = performance.now();
    try {
      window.flockpath.pause();
      window.flockpath.load(scene);
    } catch (error) {
      return { refused: String(error.message ?? error) };
    }
    return { loadMs: performance.now() - started };
  }, [planner, n, layout]);
}

/** ms of `call` in the page, median of up to `times` calls (one when a call takes over 0.5 s). */
async function timeInPage(call, times) {
  return page.evaluate(([source, count]) => {
    const fn = new Function(source);
    const ms = [];
    for (let i = 0; i < count; i += 1) {
      const t = performance.now();
      fn();
      ms.push(performance.now() - t);
      if (ms[i] > 500) break;
    }
    ms.sort((a, b) => a - b);
    return ms[(ms.length - 1) >> 1];
  }, [call, times]);
}

/** ms of one paused step (the page API's step, with the page's listeners), median of three. */
const stepCost = () => timeInPage('window.flockpath.pause(); window.flockpath.step(1);', 3);

/**
 * CPU time (ms) the page's main thread has used so far (CDP `Performance.getMetrics`,
 * `ThreadTime`): unlike wall-clock time it does not grow while other processes hold the core,
 * so per-frame and per-step figures from it hold on a loaded machine too.
 */
async function mainThreadCpuMs(cdp) {
  const { metrics } = await cdp.send('Performance.getMetrics');
  const t = metrics.find((m) => m.name === 'ThreadTime');
  return t ? 1000 * t.value : NaN;
}

/**
 * Plays for `ms` and returns the frame intervals, the steps simulated and the main thread's CPU
 * time over the timed window.
 */
async function playFor(ms) {
  const cdp = await page.context().newCDPSession(page);
  await cdp.send('Performance.enable', { timeDomain: 'threadTicks' }).catch(() => cdp.send('Performance.enable'));
  // One second to settle (JIT, first allocations, the first metrics refresh).
  await page.evaluate(() => window.flockpath.play());
  await sleep(1000);
  const cpu0 = await mainThreadCpuMs(cdp);
  const played = await page.evaluate(async (window_ms) => {
    const stepNow = () => window.flockpath.timeline().step;
    const stamps = [];
    // Frames delivered: a new picture from the worker put on the scene canvas (an animation frame
    // with no new picture shows the old one again: it is not a frame the user saw change).
    const delivered = [];
    const put = CanvasRenderingContext2D.prototype.putImageData;
    CanvasRenderingContext2D.prototype.putImageData = function (...a) {
      if (this.canvas.id === 'scene-canvas') delivered.push(performance.now());
      return put.apply(this, a);
    };
    const steps0 = stepNow();
    const t0 = performance.now();
    await new Promise((resolve) => {
      const tick = (now) => {
        stamps.push(now);
        if (now - t0 >= window_ms) resolve();
        else requestAnimationFrame(tick);
      };
      requestAnimationFrame(tick);
    });
    const elapsed = performance.now() - t0;
    CanvasRenderingContext2D.prototype.putImageData = put;
    const intervals = stamps.slice(1).map((t, i) => t - stamps[i]);
    const deliveredIntervals = delivered.slice(1).map((t, i) => t - delivered[i]);
    return { intervals, frames: stamps.length, steps: stepNow() - steps0, elapsed, delivered: delivered.length, deliveredIntervals };
  }, ms);
  played.cpuMs = (await mainThreadCpuMs(cdp)) - cpu0;
  await cdp.detach().catch(() => {});
  return played;
}

/** Main-thread CPU ms of one paused step (the page API's step), median of three. */
async function stepCpuMs() {
  const cdp = await page.context().newCDPSession(page);
  await cdp.send('Performance.enable', { timeDomain: 'threadTicks' }).catch(() => cdp.send('Performance.enable'));
  const ms = [];
  for (let i = 0; i < 3; i += 1) {
    const before = await mainThreadCpuMs(cdp);
    await page.evaluate(() => { window.flockpath.pause(); window.flockpath.step(1); });
    ms.push((await mainThreadCpuMs(cdp)) - before);
  }
  await cdp.detach().catch(() => {});
  return median(ms);
}

/**
 * Pause-click latencies: plays, presses and releases the mouse on Pause at a random moment,
 * repeats. The press and release go straight through CDP: Playwright's `click` moves the mouse
 * first and waits for the move to be handled, which would time every press to the page's idle
 * moment right after a frame.
 */
async function pauseClicks() {
  const box = await page.locator('#play').boundingBox();
  const x = box.x + box.width / 2;
  const y = box.y + box.height / 2;
  await page.mouse.move(x, y);
  const cdp = await page.context().newCDPSession(page);
  const mouse = (type) => cdp.send('Input.dispatchMouseEvent', { type, x, y, button: 'left', clickCount: 1 });
  const results = [];
  for (let k = 0; k < CLICKS; k += 1) {
    const before = await page.evaluate(() => {
      window.flockpath.play();
      return window.__benchPage.clicks.length;
    });
    await sleep(400 + Math.random() * 400);
    await mouse('mousePressed');
    await mouse('mouseReleased');
    await page.waitForFunction((n) => window.__benchPage.clicks.length > n, before, { polling: 50, timeout: 60_000 });
    results.push(await page.evaluate(() => window.__benchPage.clicks.at(-1)));
  }
  await cdp.detach().catch(() => {});
  return results;
}

/** Self time per function while playing for `ms`, as shares of the profile's duration. */
async function profileFor(ms) {
  const cdp = await page.context().newCDPSession(page);
  try {
    await cdp.send('Profiler.enable');
    await cdp.send('Profiler.setSamplingInterval', { interval: 500 });
    await page.evaluate(() => window.flockpath.play());
    await sleep(300);
    await cdp.send('Profiler.start');
    await sleep(ms);
    const { profile } = await cdp.send('Profiler.stop');
    await page.evaluate(() => window.flockpath.pause());
    return selfShares(profile);
  } finally {
    await cdp.detach().catch(() => {});
  }
}

/**
 * `[{name, share}]` of self time, largest first, from a CDP CPU profile. The wasm module has no
 * name section, so time in wasm is charged to the JS binding that called into it (`step`,
 * `render`, `metrics_json`, …: "wasm under step").
 */
function selfShares(profile) {
  const byId = new Map(profile.nodes.map((n) => [n.id, n]));
  const parent = new Map();
  for (const n of profile.nodes) for (const c of n.children ?? []) parent.set(c, n.id);
  const isWasm = (node) => /^wasm:|\.wasm$/.test(node?.callFrame?.url ?? '') || /^wasm-function\[/.test(node?.callFrame?.functionName ?? '');
  const self = new Map();
  let total = 0;
  for (let i = 0; i < profile.samples.length; i += 1) {
    // A sample lasts until the next one (the last one: its own delta, as an estimate).
    const dt = profile.timeDeltas[i + 1] ?? profile.timeDeltas[i] ?? 0;
    let node = byId.get(profile.samples[i]);
    let name = functionName(node?.callFrame);
    if (isWasm(node)) {
      while (node && isWasm(node)) node = byId.get(parent.get(node.id));
      name = `wasm under ${node ? functionName(node.callFrame).replace(/ \(flockpath\.js\)$/, '') : '?'}`;
    }
    self.set(name, (self.get(name) ?? 0) + dt);
    total += dt;
  }
  return [...self.entries()]
    .map(([name, t]) => ({ name, share: total > 0 ? t / total : 0 }))
    .sort((a, b) => b.share - a.share);
}

function functionName(frame) {
  if (!frame) return '(unknown)';
  let name = frame.functionName || '(anonymous)';
  // Rust symbols: keep the last two path segments (`boids::plan`), drop hashes and generics.
  name = name.replace(/::h[0-9a-f]{16}$/, '').replace(/<[^<>]*>/g, '');
  const parts = name.split('::').filter(Boolean);
  if (parts.length > 2) name = parts.slice(-2).join('::');
  if (name.startsWith('(')) return name;
  const file = frame.url ? path.basename(frame.url.split('?')[0]) : '';
  return file && !frame.url.startsWith('wasm:') ? `${name} (${file})` : name;
}

/** ms of one `flockpath.metrics()` call (JSON included), median of five, paused. */
async function metricsCost() {
  await page.evaluate(() => window.flockpath.pause());
  return timeInPage('window.flockpath.metrics();', 5);
}

async function runCase(planner, n, layout, skipReason, [variant, url]) {
  const result = { planner, agents: n, layout, variant };
  if (skipReason) return { ...result, skipped: skipReason };
  await freshPage(url);
  const loaded = await loadScene(planner, n, layout);
  if (loaded.refused) return { ...result, refused: loaded.refused };
  result.load_ms = loaded.loadMs;
  result.step_ms = await stepCost();
  result.step_cpu_ms = await stepCpuMs();
  if (result.step_ms > 3000) {
    return { ...result, skipped: `one step takes ${(result.step_ms / 1000).toFixed(1)} s` };
  }
  const played = await playFor(seconds * 1000);
  result.frames = played.intervals.length;
  result.intervals_ms = played.intervals.map((dt) => Math.round(dt * 10) / 10);
  result.fps_median = played.intervals.length ? 1000 / median(played.intervals) : 1000 / played.elapsed;
  result.fps_p5 = played.intervals.length ? 1000 / quantile(played.intervals, 0.95) : 1000 / played.elapsed;
  result.frame_p95_ms = quantile(played.intervals, 0.95);
  // What the user sees change: new pictures per second, and the 5th percentile of their rate.
  result.delivered_fps = (played.delivered * 1000) / played.elapsed;
  result.delivered_p5 = played.deliveredIntervals.length ? 1000 / quantile(played.deliveredIntervals, 0.95) : 0;
  result.steps_per_s = (played.steps * 1000) / played.elapsed;
  result.steps_per_frame = played.steps / Math.max(1, played.frames);
  // On-CPU figures: what the page would do with the core to itself (main thread only).
  result.cpu_ms_per_frame = played.cpuMs / Math.max(1, played.intervals.length);
  result.cpu_share = played.cpuMs / played.elapsed;
  const clicks = await pauseClicks();
  result.pause_ms = clicks.map((c) => c.handled);
  result.pause_frame_ms = clicks.map((c) => c.frame);
  if (profiling) result.profile = (await profileFor(2000)).slice(0, 8);
  result.metrics_ms = await metricsCost();
  return result;
}

const fmt = (x, digits = 1) => (typeof x === 'number' && Number.isFinite(x) ? x.toFixed(digits) : '–');
function printCase(r) {
  const head = `${r.planner.padEnd(NAME_W)}${String(r.agents).padStart(7)} ${r.layout.padEnd(7)}` +
    (r.variant ? r.variant.padEnd(7) : '');
  if (r.refused) return console.log(`${head} refused: ${r.refused}`);
  if (r.skipped) return console.log(`${head} skipped: ${r.skipped}`);
  if (r.failed) return console.log(`${head} failed: ${r.failed}`);
  const cols = [
    fmt(r.delivered_fps), fmt(r.delivered_p5), fmt(r.fps_median), fmt(r.fps_p5), fmt(r.frame_p95_ms), fmt(r.steps_per_frame, 2), fmt(r.step_ms, 2),
    `${fmt(median(r.pause_ms), 0)}/${fmt(Math.max(...r.pause_ms), 0)}`,
    `${fmt(median(r.pause_frame_ms), 0)}/${fmt(Math.max(...r.pause_frame_ms), 0)}`,
    fmt(r.metrics_ms, 2), fmt(r.cpu_ms_per_frame, 1), fmt(r.step_cpu_ms, 1),
  ];
  console.log(`${head}${cols.map((c) => c.padStart(11)).join('')}`);
  if (r.profile) {
    const top = r.profile.filter((p) => p.name !== '(idle)').slice(0, 5);
    const idle = r.profile.find((p) => p.name === '(idle)')?.share ?? 0;
    console.log(`${' '.repeat(NAME_W + 15)}main thread ${fmt(100 * (1 - idle), 0)}% busy; top self: ` +
      top.map((p) => `${p.name} ${fmt(100 * p.share, 0)}%`).join(', '));
  }
}

let failed = false;
const results = [];
const started = Date.now();
try {
  await launch();
  const version = context.browser()?.version() ?? (await page.evaluate(() => navigator.userAgent));
  console.log(`flockpath page benchmark: index.html in headless Chromium (${version}), ` +
    `${pinned ? 'pinned to core 0 (taskset -c 0)' : 'UNPINNED'}, viewport ${VIEWPORT.width}×${VIEWPORT.height}`);
  console.log(`Scenes: open-field preset scaled to the kernel bench's density, one group; ${seconds} s of play per case after 1 s of warm-up; ` +
    `panels as a user first sees them (metrics, plots, timeline). ${CLICKS} Pause clicks per case.`);
  console.log('dlv = frames delivered per second (new pictures from the worker on the canvas) and their p5; ' +
    'fps from requestAnimationFrame; p5 = 5th percentile (1000 / 95th-percentile frame); ' +
    'pause = pointerdown → button state changed / → next frame (median/max ms); step = one paused step; ' +
    'cpu/frm, step cpu = main-thread CPU ms per frame played and per paused step (CDP ThreadTime: holds under load).');
  const cols = ['dlv fps', 'dlv p5', 'fps med', 'fps p5', 'frame p95', 'steps/frm', 'step ms', 'pause ms', 'pause→frm', 'metrics ms',
    'cpu/frm ms', 'step cpu'];
  console.log(`${'planner'.padEnd(NAME_W)}${'agents'.padStart(7)} ${'layout'.padEnd(7)}${BEFORE ? 'page   ' : ''}${cols.map((c) => c.padStart(11)).join('')}`);
  for (const planner of planners) {
    for (const layout of layouts) {
      for (const n of sizes) {
        for (const variant of VARIANTS) {
          const tenK = results.find((r) =>
            r.planner === planner && r.layout === layout && r.agents === 10000 && r.variant === variant[0]);
          let skip = null;
          // The step's CPU time where known: a loaded machine stretches its wall-clock time.
          const tenKStep = tenK && Number.isFinite(tenK.step_cpu_ms) ? tenK.step_cpu_ms : tenK?.step_ms;
          if (n === 100000 && tenK && !(tenKStep <= SKIP_100K_WHEN_10K_STEP_MS)) {
            skip = tenKStep > SKIP_100K_WHEN_10K_STEP_MS
              ? `a 10,000-agent step takes ${fmt(tenKStep, 0)} ms, so 100,000 would take seconds per frame`
              : 'the 10,000-agent case did not run';
          }
          let r;
          try {
            r = await withTimeout(runCase(planner, n, layout, skip, variant), CASE_LIMIT_MS, 'the case');
          } catch (error) {
            r = { planner, agents: n, layout, variant: variant[0],
              failed: `${error.message.split('\n')[0]} (page unresponsive; abandoned)` };
            await relaunch();
          }
          results.push(r);
          printCase(r);
        }
      }
    }
  }
  // metrics() cost against N, per layout (Boids; the planner barely matters).
  const rows = results.filter((r) => r.metrics_ms !== undefined);
  console.log('\nflockpath.metrics() ms per call (median of 5, paused after the run) by agents:');
  for (const planner of planners) {
    for (const layout of layouts) {
      for (const [variant] of VARIANTS) {
        const cells = sizes.map((n) => {
          const r = rows.find((x) => x.planner === planner && x.layout === layout && x.agents === n && x.variant === variant);
          return `${n}: ${r ? fmt(r.metrics_ms, 2) : '–'}`;
        });
        console.log(`  ${planner.padEnd(NAME_W)} ${layout.padEnd(7)} ${variant.padEnd(7)}${cells.join('   ')}`);
      }
    }
  }
  console.log(`\n(${Math.round((Date.now() - started) / 1000)} s in all)`);
  if (jsonFile) await writeFile(jsonFile, `${JSON.stringify({ chromium: version, pinned, seconds, results }, null, 2)}\n`);
} catch (error) {
  console.error(`bench-page: ${error.stack ?? error.message}`);
  failed = true;
} finally {
  await context?.close().catch(() => {});
  await server.close();
  await rm(profileDir, { recursive: true, force: true });
}
process.exit(failed ? 1 : 0);
