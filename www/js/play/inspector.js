// The Diagnose card: overlay switches, the stuck count, and the inspector of one agent. Clicking
// an agent with the Select tool (the editor sends `canvas-click`) or `flockpath.inspect(id)`
// selects it; the core picks the agent (`agent_at`), explains it (`explanation_json`) and draws
// the overlays. This module only shows what the core returns.

import { onLanguageChange, t, tOr } from '../core/i18n.js';
import { unitText } from '../core/params-form.js';

/** How often the inspector and the stuck count refresh while the run goes on (ms). */
const REFRESH_MS = 250;

const OVERLAYS = ['stuck', 'explanation', 'landscape', 'fireflies'];

/** Words the core composes with numbers: [regex over its English, key]. */
const COMPOSED = [
  [/^stuck: no progress towards the goal for 300\+ steps; (?<rest>.+)$/, 'explain.stuck_prefix'],
  [/^the velocity nearest v_pref that keeps all (?<n>\d+) half-planes$/, 'explain.orca_keeps'],
  [/^densely packed: no velocity keeps all (?<n>\d+) half-planes; (?<m>\d+) given up least$/, 'explain.orca_dense'],
];

/** One of the core's explanation words (a state, a force, a point, a value) in the page's language. */
export function explainText(words) {
  for (const [re, key] of COMPOSED) {
    const m = re.exec(words);
    if (m) return t(key, { ...m.groups, ...(m.groups.rest ? { rest: explainText(m.groups.rest) } : {}) });
  }
  return tOr(`explain.${words}`, words);
}

export function setupInspector(app) {
  const panel = document.getElementById('inspector');
  const title = document.getElementById('inspector-title');
  const facts = document.getElementById('inspector-facts');
  const vectors = document.getElementById('inspector-vectors');
  const stuckCount = document.getElementById('stuck-count');
  const hint = document.getElementById('inspector-hint');
  const boxes = Object.fromEntries(OVERLAYS.map((k) => [k, document.getElementById(`overlay-${k}`)]));

  const applyOverlays = () => {
    const on = Object.fromEntries(OVERLAYS.map((k) => [k, Boolean(boxes[k]?.checked)]));
    app.guard((sim) => sim.set_overlays(on.stuck, on.explanation, on.landscape, on.fireflies));
    app.dirty = true;
  };
  for (const box of Object.values(boxes)) box?.addEventListener('change', applyOverlays);
  // The page API changes overlays too: mirror the core's state in the boxes.
  app.addEventListener('overlays', () => {
    const result = app.guard((sim) => JSON.parse(sim.overlays_json()));
    if (!result.ok) return;
    for (const k of OVERLAYS) if (boxes[k]) boxes[k].checked = result.value[k];
  });
  applyOverlays();

  const fact = (label, value, bad = false) => {
    const dt = document.createElement('dt');
    dt.textContent = label;
    const dd = document.createElement('dd');
    dd.textContent = value;
    if (bad) dd.classList.add('bad');
    facts.append(dt, dd);
  };

  const refresh = () => {
    const stuck = app.guard((sim) => sim.stuck_agents().length);
    if (stuck.ok) {
      const text = stuck.value === 0 ? '' : stuck.value === 1 ? t('diagnose.stuck_one') : t('diagnose.stuck_count', { n: stuck.value });
      // Written only when it changed: a write restyles the page (this runs four times a second).
      if (stuckCount.textContent !== text) stuckCount.textContent = text;
    }
    const result = app.guard((sim) => JSON.parse(sim.explanation_json()));
    const e = result.ok ? result.value : null;
    if (panel.hidden !== (e === null)) panel.hidden = e === null;
    if (hint.hidden !== (e !== null)) hint.hidden = e !== null;
    if (e === null) return;
    const group = app.scene.groups?.[e.group];
    title.textContent = t('inspector.title', {
      agent: e.agent,
      group: group?.name ?? t('groups.default_name', { n: e.group + 1 }),
      planner: tOr(`planner.${e.planner}`, e.planner),
    });
    facts.replaceChildren();
    fact(t('inspector.speed'), `${e.speed.toFixed(2)} ${unitText('px/step')}`);
    fact(t('inspector.state'), explainText(e.state), e.stuck);
    fact(t('inspector.position'), `${e.position[0].toFixed(0)}, ${e.position[1].toFixed(0)} ${unitText('px')}`);
    fact(t('inspector.neighbours'), String(e.neighbours.length));
    for (const v of e.values) fact(explainText(v.name), Number.isInteger(v.value) ? String(v.value) : v.value.toFixed(3));
    vectors.replaceChildren();
    for (const v of e.vectors) {
      const li = document.createElement('li');
      const swatch = document.createElement('span');
      swatch.className = 'swatch';
      swatch.style.background = v.color;
      li.append(swatch, `${explainText(v.name)}: ${v.length.toFixed(v.in_px ? 0 : 3)}${v.in_px ? ` ${unitText('px')}` : ''}`);
      vectors.append(li);
    }
    for (const p of e.points) {
      const li = document.createElement('li');
      li.textContent = t('inspector.point_at', { name: explainText(p.name), x: p.point[0].toFixed(0), y: p.point[1].toFixed(0) });
      vectors.append(li);
    }
  };

  const inspect = async (id) => {
    await app.guard((sim) => sim.inspect(id));
    app.dirty = true;
    refresh();
  };
  app.addEventListener('canvas-click', async (event) => {
    const { x, y, tolerance } = event.detail;
    const picked = await app.guard((sim) => sim.agent_at(x, y, tolerance));
    if (picked.ok) inspect(picked.value);
  });
  app.addEventListener('inspection', refresh);
  document.getElementById('inspector-close')?.addEventListener('click', () => inspect(-1));
  for (const name of ['stepped', 'scene']) app.addEventListener(name, refresh);

  let last = -Infinity;
  const tick = (now) => {
    if (!app.crashed) {
      if (app.playing && now - last >= REFRESH_MS) {
        last = now;
        refresh();
      }
      requestAnimationFrame(tick);
    }
  };
  requestAnimationFrame(tick);
  refresh();
  onLanguageChange(refresh);
}
