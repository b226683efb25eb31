// An independent recount of what the page shows (issue 23 §3), for the end-to-end tests: from
// the page's `positions()` one step apart, `goals()` (each goal where it is now) and `scene()`
// (group sizes, body radii, which goal each group heads for, whether it is an exit) only — never
// from the metrics code — it counts the agents inside their goal, the pairs of bodies at rest
// that overlap and the agents at rest outside their goal, and sets them beside `metrics()`.
// The same definitions as the native recount in tests/arrival_recount.rs.

/** A body that moved less than this (px) during the last step is at rest. */
export const AT_REST_PX = 0.05;

/** Two discs overlap when their centres are closer than the sum of radii less this (px). */
const OVERLAP_SLACK_PX = 1e-3;

/** The body radius a group has when the scene JSON leaves it out (the scene format's default). */
const DEFAULT_AGENT_RADIUS = 4;

/**
 * Per agent, in the page's agent order (groups in scene order, `count` each): its group index,
 * body radius and goal index (null: it wanders).
 */
export function agentsOf(scene) {
  const agents = [];
  scene.groups.forEach((group, g) => {
    const radius = group.agent_radius ?? DEFAULT_AGENT_RADIUS;
    const goal = group.goal ?? null;
    for (let k = 0; k < group.count; k += 1) agents.push({ group: g, radius, goal });
  });
  return agents;
}

/**
 * Recounts a frame. `before` and `after` are `positions()` one step apart, `goals` is
 * `goals()` at `after`. Returns per agent whether it is inside its goal and at rest, and the
 * totals: `inside`, `insideByGroup`, `exitedByGroup` (inside an exit goal: gone from the scene),
 * `restingOutsideByGroup`, `overlappingAtRest` (pairs, with `overlaps` naming up to 5).
 */
export function recount(scene, goals, before, after) {
  const agents = agentsOf(scene);
  if (agents.length !== after.length || before.length !== after.length) {
    throw new Error(`the scene's groups have ${agents.length} agents, positions() gave ${before.length} and ${after.length}`);
  }
  const groups = scene.groups.length;
  const insideByGroup = new Array(groups).fill(0);
  const exitedByGroup = new Array(groups).fill(0);
  const restingOutsideByGroup = new Array(groups).fill(0);
  const inside = [];
  const atRest = [];
  agents.forEach((agent, i) => {
    const [x, y] = after[i];
    const moved = Math.hypot(x - before[i][0], y - before[i][1]);
    const goal = agent.goal === null ? null : goals[agent.goal];
    const isInside = goal !== null && Math.hypot(x - goal.x, y - goal.y) <= goal.radius;
    const isExit = agent.goal !== null && scene.goals[agent.goal]?.on_arrival === 'exit';
    const exited = isInside && isExit;
    // An agent that went out through an exit is not drawn and is solid to nobody.
    const resting = moved < AT_REST_PX && !exited;
    inside.push(isInside);
    atRest.push(resting);
    if (isInside) insideByGroup[agent.group] += 1;
    if (exited) exitedByGroup[agent.group] += 1;
    if (resting && goal !== null && !isInside) restingOutsideByGroup[agent.group] += 1;
  });
  const resting = agents.map((_, i) => i).filter((i) => atRest[i]);
  let overlappingAtRest = 0;
  const overlaps = [];
  for (let a = 0; a < resting.length; a += 1) {
    const i = resting[a];
    for (let b = a + 1; b < resting.length; b += 1) {
      const j = resting[b];
      const d = Math.hypot(after[i][0] - after[j][0], after[i][1] - after[j][1]);
      if (d < agents[i].radius + agents[j].radius - OVERLAP_SLACK_PX) {
        overlappingAtRest += 1;
        if (overlaps.length < 5) overlaps.push(`${i} at (${after[i]}) and ${j} at (${after[j]}): ${d.toFixed(3)} px apart`);
      }
    }
  }
  return {
    agents: agents.length,
    withGoal: agents.filter((a) => a.goal !== null).length,
    inside: insideByGroup.reduce((s, v) => s + v, 0),
    insideByGroup,
    exitedByGroup,
    restingOutsideByGroup,
    atRest: resting.length,
    overlappingAtRest,
    overlaps,
    perAgent: { inside, atRest },
  };
}

/**
 * Sets a recount beside the page's metrics and returns the list of disagreements (empty when
 * they agree): arrived = inside (overall and per group), waiting agents no more than the agents
 * at rest outside their goal (each waiting agent is one of them), exited agents = those inside
 * an exit, and no two bodies at rest overlapping.
 */
export function disagreements(label, counted, metrics) {
  const out = [];
  const arrived = Math.round(metrics.arrived_share * metrics.agents);
  if (metrics.agents !== counted.agents) out.push(`${label}: metrics has ${metrics.agents} agents, the scene ${counted.agents}`);
  if (arrived !== counted.inside) out.push(`${label}: metrics arrived ${arrived}, inside their goal ${counted.inside}`);
  metrics.groups.forEach((gm, g) => {
    const here = counted.insideByGroup[g];
    const groupArrived = Math.round(gm.arrived_share * gm.agents);
    if (groupArrived !== here) out.push(`${label}: group ${g} metrics arrived ${groupArrived}, inside ${here}`);
    const waiting = gm.waiting_agents ?? 0;
    if (waiting > counted.restingOutsideByGroup[g]) {
      out.push(`${label}: group ${g} has ${waiting} waiting but only ${counted.restingOutsideByGroup[g]} at rest outside its goal`);
    }
    if (typeof gm.exited_agents === 'number' && gm.exited_agents !== counted.exitedByGroup[g]) {
      out.push(`${label}: group ${g} metrics exited ${gm.exited_agents}, inside its exit ${counted.exitedByGroup[g]}`);
    }
  });
  if (typeof metrics.waiting_agents !== 'number') out.push(`${label}: metrics() has no waiting_agents`);
  if (counted.overlappingAtRest !== 0) {
    out.push(`${label}: ${counted.overlappingAtRest} pairs of bodies at rest overlap: ${counted.overlaps.join('; ')}`);
  }
  return out;
}

/**
 * In the page: pauses, goes back to step 0, steps to `steps - 1`, reads the positions, steps
 * once more and reads positions, goals, scene, metrics and digest (one evaluate: no frame runs
 * between the two reads).
 */
export async function runAndRead(page, steps) {
  return page.evaluate(async (n) => {
    const api = window.flockpath;
    await api.pause();
    await api.reset();
    await api.step(n - 1);
    const before = await api.positions();
    const step = await api.step(1);
    return {
      step,
      before,
      after: await api.positions(),
      goals: api.goals(),
      scene: api.scene(),
      metrics: api.metrics(),
      digest: api.digest(),
    };
  }, steps);
}

/** The scene of preset `name` as the page loads it from its Scene menu. */
export async function presetScene(page, name) {
  await page.selectOption('#preset', name);
  return page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene()));
}

/** Loads `scene` through the page API, runs it to `steps` and recounts; returns [recount, read]. */
export async function loadRunAndCount(page, scene, steps) {
  await page.evaluate((s) => window.flockpath.load(s), scene);
  const read = await runAndRead(page, steps);
  if (read.step !== steps) throw new Error(`stepped to ${read.step}, not ${steps}`);
  return [recount(read.scene, read.goals, read.before, read.after), read];
}
