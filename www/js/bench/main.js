// The browser half of the benchmark (scripts/bench.sh): ns per agent-step of Sim.step in wasm on
// the same constant-density scenes as `flockpath bench`, and the 10k-agent frame time
// (step + render + putImageData). Wall-clock time is fine here: this page measures, it does not
// simulate. Results go to the page and to `window.benchResults` (read by the driver script).

import { blitSim } from '../core/blit.js';
import { loadWasm } from '../core/boot.js';

/** The wasm `Sim` class, once loaded. */
let Sim = null;

/** `#smoke` (scripts/bench.sh --smoke, the test command): a hundredth of every size, one short
 * repetition — it checks that the benchmark runs; its figures mean nothing. */
const SMOKE = location.hash.includes('smoke');
const scaled = (n) => (SMOKE ? Math.max(10, Math.floor(n / 100)) : n);

const SIZES = [1_000, 10_000, 100_000].map(scaled);
const FRAME_AGENTS = scaled(10_000);
const CANVAS = { width: 1280, height: 800 };

const out = document.getElementById('out');
const log = (line) => {
  out.textContent += `${line}\n`;
};

function median(samples) {
  const s = [...samples].sort((a, b) => a - b);
  const mid = s.length >> 1;
  return s.length % 2 ? s[mid] : 0.5 * (s[mid - 1] + s[mid]);
}

async function fetchText(file) {
  const response = await fetch(`bench/${file}`, { cache: 'no-store' });
  if (!response.ok) throw new Error(`bench/${file}: HTTP ${response.status} (run scripts/bench.sh)`);
  return response.text();
}

const sceneText = (n) => fetchText(`density-${n}.json`);

/** The per-planner rows (the native bench's names), at 1k and 10k agents. */
const PLANNER_SIZES = [1_000, 10_000].map(scaled);
/** One repetition of one step (a smoke run). */
const SMOKE_PLAN = { warmupSteps: 1, steps: 1, agentsPerRep: 1, reps: 1 };

/**
 * Like the native bench: every repetition steps freshly spawned worlds (same simulated moment
 * for every N: boids clump over time), several worlds for small N so each timing is long enough.
 */
function timeSteps(text, n, plan) {
  const worlds = Math.max(1, Math.ceil(plan.agentsPerRep / n));
  const samples = [];
  for (let rep = 0; rep < plan.reps; rep++) {
    const sims = [];
    for (let w = 0; w < worlds; w++) {
      // A 1×1 frame: these Sims never render, so they must not each hold a 4 MB pixmap.
      const sim = new Sim(text, 1, 1);
      sim.step(plan.warmupSteps);
      sims.push(sim);
    }
    const start = performance.now();
    for (const sim of sims) sim.step(plan.steps);
    const ms = performance.now() - start;
    samples.push((ms * 1e6) / (plan.steps * n * worlds));
    for (const sim of sims) sim.free();
  }
  return { median: median(samples), min: Math.min(...samples), max: Math.max(...samples) };
}

function timeFrames(wasm, text, frames, reps) {
  const canvas = document.getElementById('frame');
  const ctx = canvas.getContext('2d');
  const sim = new Sim(text, CANVAS.width, CANVAS.height);
  const frame = () => {
    sim.step(1);
    sim.render();
    blitSim(ctx, wasm, sim);
  };
  for (let i = 0; i < 20; i++) frame();
  const samples = [];
  for (let rep = 0; rep < reps; rep++) {
    const start = performance.now();
    for (let i = 0; i < frames; i++) frame();
    samples.push((performance.now() - start) / frames);
  }
  sim.free();
  return { median: median(samples), min: Math.min(...samples), max: Math.max(...samples) };
}

async function main() {
  const quick = location.hash.includes('quick');
  const { module, wasm } = await loadWasm();
  Sim = module.Sim;
  const plan = SMOKE
    ? SMOKE_PLAN
    : quick
      ? { warmupSteps: 2, steps: 5, agentsPerRep: 20_000, reps: 3 }
      : { warmupSteps: 3, steps: 10, agentsPerRep: 100_000, reps: 7 };
  out.textContent = '';
  log(`Sim.step in wasm, ns per agent-step (median of ${plan.reps}; min…max)`);
  const results = { quick, smoke: SMOKE, step_ns_per_agent_step: {}, frame_ms: null };
  for (const n of SIZES) {
    const t = timeSteps(await sceneText(n), n, plan);
    results.step_ns_per_agent_step[n] = t.median;
    log(`${String(n).padStart(9)}  ${t.median.toFixed(1).padStart(8)}  ${t.min.toFixed(1)}…${t.max.toFixed(1)}`);
    // Let the page breathe between sizes (keeps the tab responsive, lets GC run).
    await new Promise((resolve) => setTimeout(resolve, 0));
  }
  const f = timeFrames(wasm, await sceneText(FRAME_AGENTS), SMOKE ? 1 : quick ? 10 : 60, SMOKE ? 1 : quick ? 3 : 5);
  results.frame_ms = f.median;
  log(`Frame at ${FRAME_AGENTS} agents, ${CANVAS.width}×${CANVAS.height} (step + render + putImageData): ` +
    `${f.median.toFixed(2)} ms (${f.min.toFixed(2)}…${f.max.toFixed(2)})`);
  // The same per-planner table as the native bench (fewer agent-steps per repetition: the paper
  // planners cost several times a Boids step).
  const planPlanners = SMOKE
    ? SMOKE_PLAN
    : quick
      ? { warmupSteps: 2, steps: 3, agentsPerRep: 10_000, reps: 3 }
      : { warmupSteps: 3, steps: 10, agentsPerRep: 20_000, reps: 5 };
  const names = (await fetchText('planners.txt')).split('\n').map((l) => l.trim()).filter(Boolean);
  results.planner_ns_per_agent_step = {};
  log('Per planner: Sim.step in wasm, ns per agent-step (median)');
  for (const name of names) {
    results.planner_ns_per_agent_step[name] = {};
    for (const n of PLANNER_SIZES) {
      const t = timeSteps(await fetchText(`planner-${name}-${n}.json`), n, planPlanners);
      results.planner_ns_per_agent_step[name][n] = t.median;
      log(`${name.padStart(18)} ${String(n).padStart(7)}  ${t.median.toFixed(1).padStart(8)}`);
      await new Promise((resolve) => setTimeout(resolve, 0));
    }
  }
  window.benchResults = results;
}

main().catch((error) => {
  log(`benchmark failed: ${error.message}`);
  window.benchResults = { error: error.message };
});
