// Drives www/bench.html in headless Chromium (playwright-core, Debian's /usr/bin/chromium; nothing
// is downloaded) and prints the wasm figures next to the native ones.
// Usage: node scripts/bench-browser.mjs [--quick] [--native target/bench-native.json] [--json FILE]
// Run it under `taskset -c 0` (scripts/bench.sh does): Chromium inherits the pinning.

import { createServer } from 'node:http';
import { mkdtemp, readFile, rm, stat, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const WWW = path.join(ROOT, 'www');
const CHROMIUM_ARGS = [
  '--no-sandbox', '--disable-dev-shm-usage', '--disable-gpu', '--disable-quic', '--no-first-run',
  '--disable-background-networking', '--disable-component-update', '--disable-sync',
];
const MIME = { '.html': 'text/html', '.js': 'text/javascript', '.json': 'application/json', '.wasm': 'application/wasm' };

const args = process.argv.slice(2);
const flag = (name) => {
  const i = args.indexOf(name);
  return i >= 0 ? args[i + 1] : undefined;
};
const quick = args.includes('--quick');

const server = createServer(async (req, res) => {
  const file = path.join(WWW, decodeURIComponent(new URL(req.url, 'http://x').pathname));
  try {
    if (!file.startsWith(WWW) || !(await stat(file)).isFile()) throw new Error('not a file');
    res.writeHead(200, { 'content-type': MIME[path.extname(file)] ?? 'application/octet-stream' });
    res.end(await readFile(file));
  } catch {
    res.writeHead(404).end('not found');
  }
});
await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
const url = `http://127.0.0.1:${server.address().port}/bench.html${quick ? '#quick' : ''}`;

const profile = await mkdtemp(path.join(tmpdir(), 'flockpath-bench-'));
let failed = false;
const context = await chromium.launchPersistentContext(profile, {
  executablePath: '/usr/bin/chromium',
  headless: true,
  args: CHROMIUM_ARGS,
  viewport: { width: 1400, height: 1000 },
});
try {
  const page = context.pages()[0] ?? (await context.newPage());
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
  console.log(`${'agents'.padStart(9)}  ${'wasm'.padStart(9)}  ${'native'.padStart(9)}  ${'wasm/native'.padStart(11)}`);
  for (const [n, ns] of Object.entries(wasm.step_ns_per_agent_step)) {
    const nat = native?.step_ns_per_agent_step?.[n];
    const ratio = nat ? (ns / nat).toFixed(2) : '–';
    console.log(`${n.padStart(9)}  ${ns.toFixed(1).padStart(9)}  ${(nat ? nat.toFixed(1) : '–').padStart(9)}  ${ratio.padStart(11)}`);
  }
  console.log(`10,000-agent frame (step + render + putImageData) at 1280×800: ${wasm.frame_ms.toFixed(2)} ms`);
  const jsonFile = flag('--json');
  if (jsonFile) await writeFile(jsonFile, `${JSON.stringify({ wasm, native }, null, 2)}\n`);
} catch (error) {
  console.error(`bench-browser: ${error.message}`);
  failed = true;
} finally {
  await context.close().catch(() => {});
  server.close();
  await rm(profile, { recursive: true, force: true });
}
process.exit(failed ? 1 : 0);
