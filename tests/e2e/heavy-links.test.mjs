// No link freezes the page (issue 12): each heavy scene of the issue is loaded through the page
// API while the default scene runs; for a few seconds a trace collects the main thread's tasks
// (none may take over 500 ms of the page's CPU time, which unlike wall time does not grow with
// the machine's load) and a real click on Pause must stop the run. A scene may
// instead be refused with a readable message, the previous scene running on. IGSA scenes plan
// their path in slices with a progress bar and Cancel (the ~5,000-circle scene plans to the end
// and runs; the largest one is cancelled), and the sliced plan is the one-shot plan.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { bannerText, openPage, simpleScene } from './helpers.mjs';
import { traceMainThreadTasks } from './main-thread.mjs';

/** Longest task allowed on the main thread (ms of the page's CPU time: see main-thread.mjs). */
const LONG_TASK_LIMIT_MS = 500;
/** How long each scene plays while long tasks are watched (ms). */
const PLAY_MS = 3_000;
/** Longest wait for the page to answer a call (ms): longer means the main thread is blocked. */
const ANSWER_MS = 10_000;

const group = (overrides) => ({
  name: 'crowd',
  color: '#2f6fdf',
  count: 100,
  spawn: { min: [20, 20], max: [140, 220] },
  goal: 0,
  agent_radius: 4,
  planner: { kind: 'boids', params: {} },
  ...overrides,
});

/** ~5,000 circles of radius 3 px on a jittered field between the group and its goal. */
function smallCircles(count) {
  let state = 12345;
  const unit = () => {
    state = (Math.imul(state, 1664525) + 1013904223) >>> 0;
    return (state >>> 8) / (1 << 24);
  };
  return Array.from({ length: count }, () => ({
    shape: 'circle',
    center: [160 + unit() * 480, 10 + unit() * 480],
    radius: 3,
  }));
}

const IGSA_PILLARS = [
  [[260, 260], 70],
  [[430, 165], 65],
  [[450, 365], 60],
  [[610, 255], 55],
].map(([center, radius]) => ({ shape: 'circle', center, radius }));

const igsaGroup = (params) =>
  group({ count: 40, spawn: { min: [20, 190], max: [110, 310] }, planner: { kind: 'igsa', params } });

const CASES = [
  {
    name: '200,000 agents in a 120×200 px region',
    scene: simpleScene({ name: 'heavy-200k', groups: [group({ count: 200_000 })] }),
  },
  {
    name: '20,000 agents in a small region',
    scene: simpleScene({ name: 'heavy-20k', groups: [group({ count: 20_000, spawn: { min: [20, 20], max: [120, 120] } })] }),
  },
  {
    name: '~5,000 small circles with one IGSA group',
    igsa: true,
    scene: simpleScene({
      name: 'heavy-igsa-circles',
      obstacles: smallCircles(5_000),
      goals: [{ position: [745, 250], radius: 40 }],
      groups: [igsaGroup({})],
    }),
  },
  {
    name: 'IGSA at its largest parameters',
    igsa: true,
    cancel: true,
    scene: simpleScene({
      name: 'heavy-igsa-largest',
      obstacles: IGSA_PILLARS,
      goals: [{ position: [745, 250], radius: 50 }],
      groups: [igsaGroup({ population: 200, iterations: 3000, waypoint_count: 8 })],
    }),
  },
  {
    name: '1,000 fireflies in a 10×10 world',
    scene: simpleScene({
      name: 'heavy-fireflies',
      width: 10,
      height: 10,
      goals: [{ position: [5, 5], radius: 2 }],
      groups: [group({ count: 1_000, spawn: { min: [0, 0], max: [10, 10] }, planner: { kind: 'firefly', params: {} } })],
    }),
  },
  {
    name: 'PSO with 2,000 agents in a 50×100 px region',
    scene: simpleScene({
      name: 'heavy-pso',
      groups: [group({ count: 2_000, spawn: { min: [20, 20], max: [70, 120] }, planner: { kind: 'pso', params: {} } })],
    }),
  },
  {
    name: 'forces agents of radius 4 in a 10×10 world with a radius-2 circle',
    scene: simpleScene({
      name: 'heavy-forces',
      width: 10,
      height: 10,
      obstacles: [{ shape: 'circle', center: [5, 5], radius: 2 }],
      goals: [{ position: [9, 9], radius: 1 }],
      groups: [group({ count: 1_000, spawn: { min: [0, 0], max: [10, 10] }, planner: { kind: 'forces', params: {} } })],
    }),
  },
];

/** `promise`, or a failure saying the page stopped answering (its main thread is blocked). */
function answered(promise, what) {
  let timer;
  const late = new Promise((_, reject) => {
    timer = setTimeout(() => reject(new Error(`the page did not answer ${what} within ${ANSWER_MS} ms`)), ANSWER_MS);
  });
  return Promise.race([promise, late]).finally(() => clearTimeout(timer));
}

/** Starts loading `scene` in a task of its own, so a long load shows as a long task. */
async function startLoad(page, scene) {
  await page.evaluate((s) => {
    window.__loadError = undefined;
    window.__planningShown = null;
    setTimeout(async () => {
      try {
        await window.flockpath.load(s);
        window.__progressAfterLoad = window.flockpath.planningProgress();
        // What the page shows the first time the progress bar appears.
        const seen = new MutationObserver(() => {
          const label = document.querySelector('.planning-label');
          if (!label || window.__planningShown) return;
          window.__planningShown = {
            label: label.textContent,
            cancel: Boolean(document.querySelector('.planning-cancel:not([hidden])')),
            steps: window.flockpath.metrics().steps,
          };
          seen.disconnect();
        });
        seen.observe(document.body, { subtree: true, childList: true, characterData: true });
        window.__loadError = null;
      } catch (error) {
        window.__loadError = error instanceof Error ? error.message : String(error);
      }
    }, 0);
  }, scene);
}

const state = (page) =>
  page.evaluate(async () => (await window.flockpath.settled(), ({
    name: window.flockpath.scene().name,
    steps: window.flockpath.metrics().steps,
    playing: window.flockpath.isPlaying(),
    planning: window.flockpath.planningProgress(),
    bar: document.querySelector('.planning-label')?.textContent ?? null,
    cancel: Boolean(document.querySelector('.planning-cancel:not([hidden])')),
  })));

let opened = null;

before(async () => {
  opened = await openPage();
});

after(async () => {
  await opened?.close();
});

/** A fresh page for a case after one that blocked the previous page. */
async function page() {
  if (!opened) opened = await openPage();
  return opened.page;
}

async function reopen() {
  await opened?.close();
  opened = null;
}

for (const c of CASES) {
  test(`heavy link: ${c.name}`, { timeout: 60_000 }, async () => {
    const p = await page();
    try {
      await answered(p.evaluate(async () => (await window.flockpath.load(window.flockpath.scene())) && window.flockpath.play()), 'a reload of the running scene');
      const previous = (await state(p)).name;
      const trace = await traceMainThreadTasks(p);
      await startLoad(p, c.scene);
      await answered(p.waitForFunction(() => window.__loadError !== undefined, null, { timeout: ANSWER_MS }), 'load()');
      const refusal = await p.evaluate(() => window.__loadError);
      if (refusal) {
        // Refused up front: a readable message, and the previous scene runs on.
        const shown = await bannerText(p);
        assert.ok(shown && shown.toLowerCase().includes(refusal.toLowerCase()), `the page shows "${refusal}" (banner: ${shown})`);
        const s0 = await state(p);
        assert.equal(s0.name, previous, 'the previous scene stays');
        await p.waitForFunction((n) => window.flockpath.metrics().steps > n, s0.steps, { timeout: ANSWER_MS });
      } else {
        assert.equal((await state(p)).name, c.scene.name, 'the scene is loaded');
        await answered(p.waitForTimeout(PLAY_MS).then(() => state(p)), 'while playing');
        if (c.igsa) {
          assert.equal(await p.evaluate(() => window.__progressAfterLoad), 0, 'load() leaves the planning to the frame loop');
          const shown = await p.evaluate(() => window.__planningShown);
          assert.ok(shown, 'a progress bar was shown');
          assert.match(shown.label, /Planning the group path… \d+%/, 'the progress is shown');
          assert.ok(shown.cancel, 'Cancel is offered');
          assert.equal(shown.steps, 0, 'no step before the path is known');
        }
      }
      // A real click on Pause stops the run, and it is answered at once.
      await answered(p.evaluate(() => window.flockpath.play()), 'play()');
      const pauseAt = Date.now();
      await answered(p.click('#play', { timeout: ANSWER_MS }), 'a click on Pause');
      const paused = await answered(state(p), 'a state read after Pause');
      assert.equal(paused.playing, false, 'Pause pauses');
      await p.waitForTimeout(300);
      assert.equal((await state(p)).steps, paused.steps, 'no step after Pause');
      assert.ok(Date.now() - pauseAt < ANSWER_MS, 'Pause answered');

      if (c.igsa && !c.cancel && !refusal) {
        // Planned in slices to the end, the scene runs.
        await p.waitForFunction(() => window.flockpath.planningProgress() === 1, null, { timeout: 40_000 });
        assert.equal(await p.$('.planning'), null, 'the progress bar is gone');
        await p.evaluate(() => window.flockpath.play());
        await p.waitForFunction(() => window.flockpath.metrics().steps > 5, null, { timeout: ANSWER_MS });
      }
      if (c.cancel && !refusal) {
        // Cancel goes back to the scene shown before, which runs on.
        await answered(p.click('.planning-cancel', { timeout: ANSWER_MS }), 'a click on Cancel');
        const back = await state(p);
        assert.equal(back.name, previous, 'Cancel brings the previous scene back');
        assert.equal(back.bar, null, 'the progress bar is gone');
        await p.evaluate(() => window.flockpath.play());
        await p.waitForFunction((n) => window.flockpath.metrics().steps > n, back.steps, { timeout: ANSWER_MS });
      }
      const tasks = await trace.stop();
      const worst = tasks[0]?.cpuMs ?? 0;
      const listed = tasks.map((task) => `${task.cpuMs} (wall ${task.wallMs})`).join(', ');
      assert.ok(worst <= LONG_TASK_LIMIT_MS, `the longest task took ${worst} ms of CPU (tasks over 50 ms: ${listed})`);
    } catch (error) {
      await reopen();
      throw error;
    }
  });
}

test('an IGSA path planned in slices by the page is the path planned in one go', { timeout: 60_000 }, async () => {
  const p = await page();
  const scene = simpleScene({
    name: 'igsa-sliced',
    obstacles: IGSA_PILLARS,
    goals: [{ position: [745, 250], radius: 50 }],
    groups: [igsaGroup({ iterations: 200 })],
  });
  // One go: step() right after load() plans in the same task.
  const oneGo = await p.evaluate(async (s) => {
    await window.flockpath.pause();
    await window.flockpath.load(s);
    await window.flockpath.step(50);
    return window.flockpath.digest();
  }, scene);
  // Slices: the frame loop plans while paused; step only once the path is known.
  await p.evaluate((s) => window.flockpath.load(s), scene);
  const sliced = await p.evaluate(async () => (await window.flockpath.settled(), window.flockpath.planningProgress()));
  assert.ok(sliced < 1, 'the load leaves the planning to the frame loop');
  await p.waitForFunction(() => window.flockpath.planningProgress() === 1, null, { timeout: 30_000 });
  const inSlices = await p.evaluate(async () => {
    await window.flockpath.step(50);
    return window.flockpath.digest();
  });
  assert.equal(inSlices, oneGo);
});
