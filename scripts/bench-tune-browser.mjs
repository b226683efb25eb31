// Times a full tuning run on the Tune page in headless Chromium (playwright-core, Debian's
// /usr/bin/chromium; nothing is downloaded): the Web Worker runs the GA on one thread. Prints
// generations, evaluations, seconds and evaluations per second, and the best weights and Gsum,
// which must equal `flockpath tune` with the same pair and seed.
// Usage: node scripts/bench-tune-browser.mjs [--behaviour b1] [--environment e1] [--seed 1]
//          [--population 200] [--generations 30] [--frames 400] [--json FILE]
// Build the page first (bash scripts/build-wasm.sh); run under `taskset -c 0` to pin Chromium.

import { writeFile } from 'node:fs/promises';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { launchChromium } from './chromium.mjs';
import { serveStatic } from './static-server.mjs';

const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const WWW = path.join(ROOT, 'www');

const args = process.argv.slice(2);
const flag = (name, fallback) => {
  const i = args.indexOf(name);
  return i >= 0 ? args[i + 1] : fallback;
};
const setup = {
  behaviour: flag('--behaviour', 'b1'),
  environment: flag('--environment', 'e1'),
  seed: flag('--seed', '1'),
  population: flag('--population', '200'),
  generations: flag('--generations', '30'),
  frames: flag('--frames', '400'),
};

const server = await serveStatic({ '/': WWW });
const query = new URLSearchParams({ ...setup, autostart: '1' });
const url = `${server.origin}/tune.html?${query}`;

let failed = false;
const { context, page, close } = await launchChromium('flockpath-tune-bench-', { width: 1280, height: 800 });
try {
  page.on('pageerror', (error) => console.error(`page error: ${error.message}`));
  const start = Date.now();
  await page.goto(url);
  let reported = 0;
  for (;;) {
    const s = await page.evaluate(() => window.flocktune?.state() ?? null);
    if (s?.error) throw new Error(s.error);
    if (s && s.history.length > reported) {
      reported = s.history.length;
      const last = s.history[reported - 1];
      console.error(`gen ${String(last.generation).padStart(2)}: best ${last.best_gsum.toFixed(3)} mean ` +
        `${last.mean_gsum.toFixed(3)} | ${s.evaluations} evals, worker ${(s.workerMs / 1000).toFixed(1)} s, ` +
        `wall ${((Date.now() - start) / 1000).toFixed(1)} s`);
    }
    if (s?.finished) break;
    if (Date.now() - start > 20 * 60_000) throw new Error('no result after 20 minutes');
    await new Promise((resolve) => setTimeout(resolve, 500));
  }
  const wall = (Date.now() - start) / 1000;
  const s = await page.evaluate(() => window.flocktune.state());
  const result = {
    browser: context.browser()?.version() ?? 'Chromium',
    setup: s.setup,
    agents: s.agents,
    frames: s.frames,
    generations: s.history.length,
    evaluations: s.evaluations,
    worker_seconds: s.workerMs / 1000,
    wall_seconds: wall,
    evaluations_per_second: s.evaluations / (s.workerMs / 1000),
    best: s.best,
  };
  console.log(`Tune page in headless Chromium, ${s.setup.behaviour.toUpperCase()}-${s.setup.environment.toUpperCase()} ` +
    `seed ${s.setup.seed}: population ${s.setup.population}, ${s.agents} agents × ${s.frames} frames per evaluation`);
  console.log(`${result.generations} generations, ${result.evaluations} evaluations: worker ${result.worker_seconds.toFixed(1)} s ` +
    `(${result.evaluations_per_second.toFixed(1)} evaluations/s on one thread), page load to finish ${wall.toFixed(1)} s`);
  console.log(`best Gsum ${s.best.gsum} with s = [${s.best.weights.join(', ')}]`);
  const out = flag('--json');
  if (out) await writeFile(out, `${JSON.stringify(result, null, 2)}\n`);
} catch (error) {
  console.error(`bench-tune-browser: ${error.message}`);
  failed = true;
} finally {
  await close();
  await server.close();
}
process.exit(failed ? 1 : 0);
