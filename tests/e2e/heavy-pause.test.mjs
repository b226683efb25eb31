// Every heavy link of issue 24 answers Pause within 100 ms in the page. Each scene is rebuilt
// from the issue's description, loaded through the page API (the compare page: from its link) and
// played; while a step runs (or IGSA plans), a real click on Pause must be answered within 100 ms
// (median of three clicks, timed as in worker-pause.test.mjs). A scene may instead be refused, with
// a message that names the field and its limit. Each case logs its answer times, or the refusal,
// and how long a step took (the slow-scene readout). Seeking far back on the timeline of the ORCA
// scene at its limit re-simulates in slices: the page shows the jump's progress and still answers
// Play and Pause within 100 ms.
//
// Cost: one browser and one playground page serve every playground case (a scene is loaded over the
// last; the load waits at most for the step the worker is in), the planners' limits are probed on
// that page, and the clicks of a case follow each other without waiting for the worker between them.

import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import { WWW, assertNoUnexpectedErrors, openPage, screenshot, simpleScene } from './helpers.mjs';
import { coveringCircles, seeded, timedPause } from './pause-helpers.mjs';

/** Longest a Pause click may take to be answered on the page (ms): the issue's rule. */
const ANSWER_MS = 100;
/** Pause clicks per case. */
const ROUNDS = 3;
/** Steps of history before the seek case jumps back (at ~0.9 s a step at ORCA's limit). */
const SEEK_HISTORY = 5;
/** The most agents a scene may hold in all (`MAX_AGENTS`): the count that probes a planner's limit. */
const ALL_AGENTS = 200_000;
/**
 * Room per agent (px) in the planner-limit scenes: 10 px apart, bodies of radius 4 px fill 0.64
 * of the density limit (a dense crowd: many neighbours within each agent's reach).
 */
const SPACING = 10;
/**
 * How far the goal lies beyond the crowd's corner (px, each axis): beyond the parking pass's
 * reach, so a crowd of a parking planner (Boids, forces) is charged its crowd figure, not the
 * jam's (`can_jam` in src/sim/cost.rs).
 */
const GOAL_BEYOND = 440;

/** The planners' parameter tables (`planners_json()` of the page's wasm module). */
let planners = [];

/** The one playground page of every case: `{ page, server, errors, close }` of `openPage()`. */
let shared = null;
/** Times a case reloaded the shared page (its worker was inside a long step). */
let reloads = 0;

before(async () => {
  const pkg = path.join(WWW, 'pkg');
  const m = await import(path.join(pkg, 'flockpath.js'));
  m.initSync({ module: await readFile(path.join(pkg, 'flockpath_bg.wasm')) });
  planners = JSON.parse(m.planners_json());
  shared = await openPage();
});

after(async () => {
  console.log(`the shared page was reloaded ${reloads} times between cases`);
  await shared?.close();
});

/**
 * A planner's parameters at their largest allowed values: every number at its table's maximum
 * (`path`, the number of a scene path to follow, stays 0: the scene has none), every choice at
 * its default. As a params object, or as the compare spec's value list.
 */
function largest(kind) {
  const table = planners.find((p) => p.name === kind);
  assert.ok(table, `planner ${kind} in planners_json()`);
  const entries = table.params.map((s) => {
    if (s.choices.length > 0) return [s.key, s.choices[s.default]];
    return [s.key, s.key === 'path' ? 0 : s.max];
  });
  return { params: Object.fromEntries(entries), values: entries.map(([, v]) => v).join(',') };
}

const group = (overrides) => ({ ...simpleScene().groups[0], ...overrides });

/**
 * `count` agents of `kind` at its largest parameters packed SPACING px apart in a square that
 * would hold `room` of them, heading for a goal GOAL_BEYOND px past its far corner.
 */
function plannerScene(kind, count, room) {
  const square = Math.ceil(Math.sqrt(room) * SPACING);
  const side = square + GOAL_BEYOND + 160;
  return simpleScene({
    name: `limit-${kind}`,
    width: side,
    height: side,
    goals: [{ position: [side - 150, side - 150], radius: 100 }],
    groups: [group({ count, spawn: { min: [10, 10], max: [10 + square, 10 + square] }, planner: { kind, params: largest(kind).params } })],
  });
}

/** `n` circles of radius 3 px scattered over the box `[x0, y0]–[x1, y1]`. */
function scatteredCircles(n, [x0, y0], [x1, y1], seed = 12345) {
  const unit = seeded(seed);
  return Array.from({ length: n }, () => ({ shape: 'circle', center: [x0 + unit() * (x1 - x0), y0 + unit() * (y1 - y0)], radius: 3 }));
}

/**
 * A ring-shaped frame (a "C": the ring with a narrow slit, so it is one simple polygon) of
 * `points` corners round `center`, between radii `inner` and `outer`, its slit at `turn`.
 */
function frame(center, inner, outer, points, turn) {
  const half = points / 2;
  const gap = 0.02;
  const ring = (r, from, to) =>
    Array.from({ length: half }, (_, k) => {
      const a = turn + from + ((to - from) * k) / (half - 1);
      return [center[0] + r * Math.cos(a), center[1] + r * Math.sin(a)];
    });
  return { shape: 'polygon', points: [...ring(outer, gap, 2 * Math.PI - gap), ...ring(inner, 2 * Math.PI - gap, gap)] };
}

/** The playground's heavy scenes (besides the per-planner limits). */
const SCENES = [
  {
    name: '1,000 Boids among 5,000 circles covering the world',
    scene: simpleScene({
      name: 'heavy-covering-circles',
      width: 1000,
      height: 1000,
      obstacles: coveringCircles(5_000, 1000),
      goals: [{ position: [900, 900], radius: 60 }],
      groups: [group({ count: 1_000, spawn: { min: [600, 600], max: [980, 980] } })],
    }),
  },
  {
    name: '50 polygon frames of 756 points',
    scene: (() => {
      const side = 4_400;
      const c = [side / 2, side / 2];
      return simpleScene({
        name: 'heavy-frames',
        width: side,
        height: side,
        obstacles: Array.from({ length: 50 }, (_, k) => frame(c, 150 + 40 * k, 160 + 40 * k, 756, k * 2.4)),
        goals: [{ position: c, radius: 60 }],
        // Spread over the world: most agents stand among the frames, inside their bounding boxes.
        groups: [group({ count: 1_000, spawn: { min: [10, 10], max: [side - 10, side - 10] } })],
      });
    })(),
  },
  {
    name: '50 one-agent flow-field groups with a jumping goal in a 20,000 px world',
    scene: (() => {
      const side = 20_000;
      const unit = seeded(77);
      const corner = () => [unit() < 0.5 ? 100 : side - 100, unit() < 0.5 ? 100 : side - 100];
      return simpleScene({
        name: 'heavy-jumping-goals',
        width: side,
        height: side,
        // Obstacles make the baseline planners walk the goal's flow field (none: straight).
        obstacles: scatteredCircles(20, [1000, 1000], [side - 1000, side - 1000]),
        // Each goal jumps between far corners every step: a new flow field each step.
        goals: Array.from({ length: 50 }, () => ({
          position: corner(),
          radius: 20,
          motion: { kind: 'polyline', points: Array.from({ length: 1000 }, corner), speed: side },
        })),
        groups: Array.from({ length: 50 }, (_, k) =>
          group({
            name: `walker ${k + 1}`,
            count: 1,
            goal: k,
            spawn: { min: [side / 2 - 500, side / 2 - 500], max: [side / 2 + 500, side / 2 + 500] },
            planner: { kind: 'orca', params: {} },
          })),
      });
    })(),
  },
  {
    name: '10 flow-field agents among 5,000 circles with a moving goal',
    scene: (() => {
      // The covering circles: every cell of the goal's flow field tests every circle, and the
      // goal moves to another cell every step, so the field is rebuilt every step.
      const side = 1_000;
      const unit = seeded(5);
      const free = () => 800 + unit() * 150;
      return simpleScene({
        name: 'heavy-moving-goal',
        width: side,
        height: side,
        obstacles: coveringCircles(5_000, side),
        goals: [{ position: [950, 950], radius: 20, motion: { kind: 'polyline', points: Array.from({ length: 1000 }, () => [free(), free()]), speed: 100 } }],
        groups: [group({ count: 10, spawn: { min: [900, 900], max: [990, 990] }, planner: { kind: 'orca', params: {} } })],
      });
    })(),
  },
  {
    name: '100,000 Boids in four squares 95 px from a 5 px goal',
    scene: (() => {
      // Four squares of 25,000 packed 10 px apart, their near corners 95 px from the goal
      // (beyond the jam reach of 5 + 80 px: not charged as a jam).
      const square = Math.ceil(Math.sqrt(25_000) * SPACING);
      const gap = 95;
      const side = 2 * (square + gap) + 40;
      const c = side / 2;
      const at = [[-1, -1], [1, -1], [-1, 1], [1, 1]];
      return simpleScene({
        name: 'heavy-four-squares',
        width: side,
        height: side,
        goals: [{ position: [c, c], radius: 5 }],
        groups: at.map(([sx, sy], k) => {
          const x = sx < 0 ? c - gap - square : c + gap;
          const y = sy < 0 ? c - gap - square : c + gap;
          return group({ name: `square ${k + 1}`, count: 25_000, spawn: { min: [x, y], max: [x + square, y + square] } });
        }),
      });
    })(),
  },
  {
    name: '100,000 Boids following a 1,000-point path',
    scene: (() => {
      const side = 8_000;
      const unit = seeded(99);
      return simpleScene({
        name: 'heavy-path',
        width: side,
        height: side,
        paths: [{ points: Array.from({ length: 1000 }, () => [100 + unit() * (side - 200), 100 + unit() * (side - 200)]), radius: 30 }],
        goals: [{ position: [side - 200, side - 200], radius: 100 }],
        groups: [group({ count: 100_000, spawn: { min: [10, 10], max: [side - 10, side - 10] }, planner: { kind: 'boids', params: { path: 1 } } })],
      });
    })(),
  },
  {
    name: '5,000 one-agent groups',
    scene: simpleScene({
      name: 'heavy-groups',
      width: 4_000,
      height: 4_000,
      goals: [{ position: [3_900, 3_900], radius: 60 }],
      groups: Array.from({ length: 5_000 }, (_, k) =>
        group({ name: `g${k}`, count: 1, spawn: { min: [10 + (k % 70) * 50, 10 + Math.floor(k / 70) * 50], max: [50 + (k % 70) * 50, 50 + Math.floor(k / 70) * 50] } })),
    }),
  },
  {
    name: 'IGSA: two groups at the largest planning among 5,000 obstacles',
    planning: true,
    scene: simpleScene({
      name: 'heavy-igsa',
      obstacles: scatteredCircles(5_000, [160, 10], [640, 490]),
      goals: [{ position: [745, 250], radius: 40 }],
      groups: [0, 1].map((k) =>
        group({
          name: `planners ${k + 1}`,
          count: 40,
          spawn: { min: [20, 40 + 220 * k], max: [110, 200 + 220 * k] },
          planner: { kind: 'igsa', params: { population: 200, iterations: 3000, waypoint_count: 8 } },
        })),
    }),
  },
];

/** A refusal must say what is wrong: a field or item, and the limit it broke. */
function assertReadableRefusal(message) {
  assert.ok(message && message.length > 20, `a readable refusal (${message})`);
  assert.match(message, /\d/, `the refusal names a limit: ${message}`);
  assert.match(message, /limit|at most|over|outside/i, `the refusal says which limit: ${message}`);
}

/** The median of `values`. */
const median = (values) => [...values].sort((a, b) => a - b)[Math.floor(values.length / 2)];

/**
 * Plays the loaded scene and clicks Pause while it steps, ROUNDS times: the first once the page
 * shows the slow-scene readout (a step runs past 100 ms, or no frame came for 500 ms), the others
 * 300 ms after Play again (the worker may still be in the step it was in: the page answers
 * anyway). Returns the answer times (ms) and the readout's step time (ms, or null when the scene
 * is not slow).
 */
async function pauseWhileStepping(page, api, { planning = false } = {}) {
  const times = [];
  let stepMs = null;
  for (let round = 0; round < ROUNDS; round += 1) {
    // Not awaited: play() resolves once the worker plays, after the step it may still be in.
    await page.evaluate((name) => {
      window[name].play();
    }, api);
    if (round === 0) {
      const slow = await page.waitForSelector('#slow-scene:not([hidden])', { timeout: 5_000 }).then(() => true, () => false);
      if (slow) stepMs = await page.evaluate(() => Number(document.getElementById('slow-scene').title.match(/\((\d[\d,]*) ms/)[1].replace(/,/g, '')));
    } else {
      await page.waitForTimeout(300);
    }
    if (planning) assert.ok((await page.evaluate(() => window.flockpath.planningProgress())) < 1, 'IGSA is still planning');
    times.push(await timedPause(page, api));
    assert.equal(await page.getAttribute('#play', 'aria-pressed'), 'false', 'the button shows Play again');
    assert.equal(await page.evaluate((name) => window[name].isPlaying(), api), false, 'the page is paused');
  }
  return { times, stepMs };
}

/** Logs and checks a case's answer times. */
function report(name, { times, stepMs }) {
  const m = median(times);
  console.log(`${name}: Pause answered in ${times.map((t) => t.toFixed(0)).join(', ')} ms (median ${m.toFixed(0)}); step ${stepMs === null ? 'not slow' : `${stepMs} ms`}`);
  assert.ok(m <= ANSWER_MS, `${name}: Pause took ${m.toFixed(0)} ms (median of ${times.map((t) => t.toFixed(0)).join(', ')})`);
}

/** How long (ms) a paused worker may take to answer before the next case reloads the page instead. */
const REUSE_WAIT_MS = 300;

/**
 * Pauses the shared playground and loads `scene`; resolves to the refusal's message, or null.
 * When the worker is still inside a long step of the last case's scene (up to ~18 s here), the
 * page is reloaded instead of waiting for it (the worker ends with the page).
 */
/**
 * Goes on in a new tab at `url` and closes the shared one without waiting for it: a renderer
 * busy with a huge scene's frames can hold a reload of its own page past any timeout (the
 * worker ends with the closed tab).
 */
async function replacePage(url) {
  const old = shared.page;
  const fresh = await shared.context.newPage();
  fresh.on('console', (msg) => {
    if (msg.type() === 'error') shared.errors.push(`console: ${msg.text()}`);
  });
  fresh.on('pageerror', (error) => shared.errors.push(`page error: ${error.message}`));
  old.close({ runBeforeUnload: false }).catch(() => {});
  shared.page = fresh;
  await fresh.goto(url);
}

async function loadShared(scene) {
  const idle = await Promise.race([
    shared.page
      .evaluate(async () => {
        await window.flockpath.pause();
        return true;
      })
      .catch(() => false),
    new Promise((resolve) => setTimeout(() => resolve(false), REUSE_WAIT_MS)),
  ]);
  if (!idle) {
    await replacePage(shared.server.url);
    await shared.page.waitForFunction(() => window.flockpath !== undefined, null, { timeout: 30_000 });
    reloads += 1;
  }
  return shared.page.evaluate(async (s) => {
    await window.flockpath.pause();
    try {
      await window.flockpath.load(s);
      return null;
    } catch (error) {
      return error instanceof Error ? error.message : String(error);
    }
  }, scene);
}

/** Loads `scene` in the shared playground and checks Pause while it steps, or its refusal. */
async function playgroundCase(name, scene, options = {}) {
  const { errors } = shared;
  errors.length = 0;
  const refusal = await loadShared(scene);
  const { page } = shared;
  if (refusal) {
    console.log(`${name}: refused: ${refusal}`);
    assertReadableRefusal(refusal);
    return;
  }
  assert.equal(await page.evaluate(() => window.flockpath.scene().name), scene.name, 'the scene is loaded');
  report(name, await pauseWhileStepping(page, 'flockpath', options));
  // A Pause the worker could not answer in 1 s restarts it, with a message in the banner (not
  // an error of the page's scripts).
  assertNoUnexpectedErrors(errors);
}

/**
 * The most agents of `kind` a scene of this shape may hold, as the page's refusal of
 * ALL_AGENTS of them says ("… (N alone)"), or ALL_AGENTS when it accepts them.
 */
async function plannerLimit(kind) {
  const refusal = await loadShared(plannerScene(kind, ALL_AGENTS, ALL_AGENTS));
  if (refusal === null) return ALL_AGENTS;
  const alone = refusal.match(/\(([\d,]+) alone\)/);
  assert.ok(alone, `the refusal names ${kind}'s limit: ${refusal}`);
  return Number(alone[1].replace(/,/g, ''));
}

/** Each planner's limit, probed once. */
const limits = new Map();
async function limitOf(kind) {
  if (!limits.has(kind)) limits.set(kind, await plannerLimit(kind));
  return limits.get(kind);
}

// ORCA last: the seek case below goes on with its scene.
for (const kind of ['boids', 'pso', 'firefly', 'forces', 'igsa', 'social_force', 'orca']) {
  test(`heavy link: ${kind} at its agent limit with its largest parameters answers Pause`, { timeout: 180_000 }, async () => {
    const limit = await limitOf(kind);
    await playgroundCase(`${kind} × ${limit}`, plannerScene(kind, limit, limit));
  });
}

test('heavy link: seeking far back in the ORCA scene at its limit shows its progress and answers Pause', { timeout: 180_000 }, async () => {
  const limit = await limitOf('orca');
  let { page } = shared;
  const { errors } = shared;
  errors.length = 0;
  // The ORCA case's scene when it is still loaded (its case ran just before), else loaded here.
  const scene = plannerScene('orca', limit, limit);
  const loaded = await page.evaluate(() => window.flockpath.scene().name);
  if (loaded !== scene.name) {
    const refusal = await loadShared(scene);
    if (refusal) {
      console.log(`orca × ${limit}, seek: refused: ${refusal}`);
      assertReadableRefusal(refusal);
      return;
    }
    ({ page } = shared);
  }
  // A history of SEEK_HISTORY steps, all after the first checkpoint (step 0).
  await page.evaluate(() => {
    window.flockpath.play();
  });
  await page.waitForFunction((n) => window.flockpath.timeline().end_step >= n, SEEK_HISTORY, { timeout: 120_000 });
  await page.evaluate(() => window.flockpath.pause());
  const before = await page.evaluate(() => window.flockpath.timeline());
  assert.ok(before.checkpoint_every > before.end_step, `no checkpoint between 0 and the end: ${JSON.stringify(before)}`);
  // Back to one step before the end, as a drag of the slider does: everything since step 0 is
  // re-simulated (seconds at this size; before issue 24 all in one blocking call).
  // The slider shows the whole history (it follows the run within 100 ms, paused too).
  await page.waitForFunction((end) => document.getElementById('timeline').max === String(end), before.end_step, { timeout: 5_000 });
  const target = await page.evaluate(() => {
    const slider = document.getElementById('timeline');
    const k = Number(slider.max) - 1;
    slider.value = String(k);
    slider.dispatchEvent(new Event('input', { bubbles: true }));
    return k;
  });
  assert.equal(target, before.end_step - 1);
  await page.waitForSelector('#timeline-seek:not([hidden])', { timeout: 10_000 });
  const progress = () => page.evaluate(() => document.getElementById('timeline-seek').textContent);
  const first = await progress();
  await screenshot(page, 'heavy-orca-seek-progress');
  const times = [];
  for (let round = 0; round < ROUNDS; round += 1) {
    // Play while the jump runs (it plays on from the step reached), then Pause.
    await page.evaluate(() => {
      window.flockpath.play();
    });
    await page.waitForTimeout(200);
    times.push(await timedPause(page));
  }
  report(`orca × ${limit}, seek to step ${target} (history ${before.end_step} steps)`, { times, stepMs: null });
  // The progress moves on, then the jump ends on the step asked for.
  await page.waitForFunction((shown) => document.getElementById('timeline-seek').textContent !== shown, first, { timeout: 60_000 });
  const later = await progress();
  console.log(`seek progress: "${first}" → "${later}"`);
  assert.match(later, new RegExp(`^Jumping to step ${target}: \\d+ of ${target} steps re-simulated$`));
  await page.waitForSelector('#timeline-seek', { state: 'hidden', timeout: 120_000 });
  await page.evaluate(() => window.flockpath.settled());
  assert.equal(await page.evaluate(() => window.flockpath.timeline().step), target, 'the jump ends on the step asked for');
  assert.equal(await page.evaluate(() => window.flockpath.isPlaying()), false);
  assertNoUnexpectedErrors(errors);
});

for (const c of SCENES) {
  test(`heavy link: ${c.name} answers Pause`, { timeout: 180_000 }, async () => {
    await playgroundCase(c.name, c.scene, { planning: c.planning });
  });
}

test('heavy link: PSO at its agent limit among 256 hills answers Pause', { timeout: 180_000 }, async () => {
  const limit = await limitOf('pso');
  const scene = { ...plannerScene('pso', limit, limit), name: 'heavy-pso-hills' };
  scene.groups[0].planner = { kind: 'pso', params: {} };
  const unit = seeded(256);
  scene.hills = Array.from({ length: 256 }, () => ({ center: [unit() * scene.width, unit() * scene.height], radius: 100 + unit() * 400, height: 50 + unit() * 500 }));
  await playgroundCase(`pso × ${limit} among 256 hills`, scene);
});

test('heavy link: the compare page with four heavy panes answers Pause', { timeout: 180_000 }, async () => {
  // One crowd, four planners each just under its own agent limit (ORCA's 85,714 is the lowest
  // of the four), the three named panes at their largest parameters. The shared page goes there
  // (the playground's worker ends with it).
  const scene = { ...plannerScene('orca', 85_000, 85_000), name: 'heavy-compare' };
  scene.groups[0].planner = { kind: 'orca', params: {} };
  const spec = `1.${['orca', 'boids', 'firefly'].map((k) => `${k}(${largest(k).values})`).join('~')}~scene`;
  const { server, errors } = shared;
  errors.length = 0;
  await replacePage(`${server.url}compare.html#s=${encodeURIComponent(JSON.stringify(scene))}&c=${encodeURIComponent(spec)}`);
  const { page } = shared;
  await page.waitForFunction(() => window.flockpathCompare !== undefined, null, { timeout: 30_000 });
  const refusal = await page.evaluate(async () => {
    try {
      await window.flockpathCompare.settled();
      return window.flockpathCompare.panes().length === 4 ? null : document.getElementById('banner-text')?.textContent ?? 'no panes';
    } catch (error) {
      return error instanceof Error ? error.message : String(error);
    }
  });
  if (refusal) {
    console.log(`compare, four panes: refused: ${refusal}`);
    assertReadableRefusal(refusal);
    return;
  }
  report('compare, four panes × 85,000', await pauseWhileStepping(page, 'flockpathCompare'));
  assertNoUnexpectedErrors(errors);
});
