// The live metrics readout and the FPS counter. Values come from `metrics_json()` (DESIGN §4
// keys); wall-clock time is used only to throttle the readout and to count frames.

/** [key, label, format, shown in red when above zero]; tooltips explain the counting rules. */
const ROWS = [
  ['steps', 'Steps', (m) => m.steps.toLocaleString('en-US')],
  ['agents', 'Agents', (m) => m.agents.toLocaleString('en-US')],
  ['arrived_share', 'Arrived', (m) => `${(100 * m.arrived_share).toFixed(1)} %`],
  ['collisions_agent_agent', 'Collisions', (m) => m.collisions_agent_agent.toLocaleString('en-US')],
  ['penetrations_agent_obstacle', 'Penetrations', (m) => m.penetrations_agent_obstacle.toLocaleString('en-US'), true],
  ['mean_speed', 'Mean speed', (m) => `${m.mean_speed.toFixed(2)} px/step`],
  ['stuck_agents', 'Stuck', (m) => m.stuck_agents.toLocaleString('en-US'), true],
];

const TIPS = {
  arrived_share: 'Share of agents inside their goal',
  collisions_agent_agent: 'Pairs of agents whose discs overlap at the end of a step, summed over steps',
  penetrations_agent_obstacle: 'Agents whose centre is inside an obstacle at the end of a step, summed over steps',
  mean_speed: 'Mean speed over agents and steps (60 steps = 1 s)',
  stuck_agents: 'Agents that made no progress towards their goal for 300 steps',
};

/** How often the readout refreshes (ms): fast enough to feel live, slow enough to read. */
const REFRESH_MS = 250;

export function setupMetrics(app) {
  const list = document.getElementById('metrics');
  const fps = document.getElementById('fps');
  const cells = new Map();
  for (const [key, label] of ROWS) {
    const dt = document.createElement('dt');
    dt.textContent = label;
    dt.title = TIPS[key] ?? '';
    const dd = document.createElement('dd');
    dd.dataset.key = key;
    dd.textContent = '–';
    list.append(dt, dd);
    cells.set(key, dd);
  }
  let lastRefresh = -Infinity;
  let frames = 0;
  let fpsSince = null;
  let forced = true;
  const force = () => (forced = true);
  app.addEventListener('stepped', force);
  app.addEventListener('scene', force);

  const refresh = () => {
    const result = app.guard((sim) => JSON.parse(sim.metrics_json()));
    if (!result.ok) return;
    const m = result.value;
    for (const [key, , format, badWhenPositive] of ROWS) {
      const cell = cells.get(key);
      if (typeof m[key] !== 'number') {
        cell.textContent = '–';
        continue;
      }
      cell.textContent = format(m);
      cell.classList.toggle('bad', Boolean(badWhenPositive) && m[key] > 0);
    }
  };

  /** Called by the frame loop after every frame. */
  return (now) => {
    frames += 1;
    if (fpsSince === null) fpsSince = now;
    if (now - fpsSince >= 1000) {
      fps.textContent = `${Math.round((frames * 1000) / (now - fpsSince))} fps`;
      frames = 0;
      fpsSince = now;
    }
    if (forced || (app.playing && now - lastRefresh >= REFRESH_MS)) {
      forced = false;
      lastRefresh = now;
      refresh();
    }
  };
}
