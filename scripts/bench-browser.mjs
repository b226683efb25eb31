// Drives www/bench.html in headless Chromium (playwright-core, Debian's /usr/bin/chromium; nothing
// is downloaded) and prints the wasm figures next to the native ones.
// Usage: node scripts/bench-browser.mjs [--quick|--smoke] [--native target/bench-native.json] [--json FILE]
// (--smoke: a hundredth of every size, one repetition: checks the benchmark runs.)
// Run it under `taskset -c 0` (scripts/bench.sh does): Chromium inherits the pinning.

import { readFile, writeFile } from 'node:fs/promises';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { launchChromium } from './chromium.mjs';
import { serveStatic } from './static-server.mjs';

const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const WWW = path.join(ROOT, 'www');

const args = process.argv.slice(2);
const flag = (name) => {
  const i = args.indexOf(name);
  return i >= 0 ? args[i + 1] : undefined;
};
const quick = args.includes('--quick');
const smoke = args.includes('--smoke');

const server = await serveStatic({ '/': WWW });
const url = `${server.origin}/bench.html${smoke ? '#smoke' : quick ? '#quick' : ''}`;

let failed = false;
const { context, page, close } = await launchChromium('flockpath-bench-', { width: 1400, height: 1000 });
try {
  page.on('pageerror', (error) => console.error(`page error: ${error.message}`));
  await page.goto(url);
  await page.waitForFunction(() => window.benchResults !== undefined, null, { timeout: 15 * 60_000, polling: 500 });
  const wasm = await page.evaluate(() => window.benchResults);
  if (wasm.error) throw new Error(wasm.error);
  const version = context.browser()?.version() ?? 'Chromium';

  let native = null;
  const nativeFile = flag('--native');
  if (nativeFile) native = JSON.parse(await readFile(nativeFile, 'utf8'));

  console.log(`\nwasm in headless ${version} (Sim.step), ns per agent-step, medians`);
  // The native bench reports wall-clock and on-CPU medians; on a busy machine the wall-clock one
  // includes time other processes held the core, so both ratios are shown.
  const cols = ['agents', 'wasm', 'native', 'native cpu', 'wasm/native', 'wasm/cpu'];
  console.log(cols.map((c) => c.padStart(13)).join(''));
  const fmt = (x, digits = 1) => (x === undefined || x === null ? '–' : x.toFixed(digits));
  for (const [n, ns] of Object.entries(wasm.step_ns_per_agent_step)) {
    const wall = native?.step_ns_per_agent_step?.[n];
    const cpu = native?.step_cpu_ns_per_agent_step?.[n];
    const row = [n, fmt(ns), fmt(wall), fmt(cpu), wall ? fmt(ns / wall, 2) : '–', cpu ? fmt(ns / cpu, 2) : '–'];
    console.log(row.map((c) => String(c).padStart(13)).join(''));
  }
  console.log(`10,000-agent frame (step + render + putImageData) at 1280×800: ${wasm.frame_ms.toFixed(2)} ms`);
  // The per-planner table, against the native bench's wall-clock medians of the same scenes.
  const nativePlanners = native?.planner_ns_per_agent_step ?? {};
  console.log(`\nper planner, wasm vs native, ns per agent-step`);
  console.log(['planner', 'agents', 'wasm', 'native', 'wasm/native'].map((c) => c.padStart(18)).join(''));
  for (const [name, bySize] of Object.entries(wasm.planner_ns_per_agent_step ?? {})) {
    for (const [n, ns] of Object.entries(bySize)) {
      const entry = nativePlanners?.[name]?.[n];
      const nat = typeof entry === 'number' ? entry : entry?.median;
      const row = [name, n, fmt(ns), fmt(nat), nat ? fmt(ns / nat, 2) : '–'];
      console.log(row.map((c) => String(c).padStart(18)).join(''));
    }
  }
  const jsonFile = flag('--json');
  if (jsonFile) await writeFile(jsonFile, `${JSON.stringify({ wasm, native }, null, 2)}\n`);
} catch (error) {
  console.error(`bench-browser: ${error.message}`);
  failed = true;
} finally {
  await close();
  await server.close();
}
process.exit(failed ? 1 : 0);
