// The compare page's activity card: the scene's prompt and prediction above the metrics, and the
// goal checked over the panes ("PSO arrives before Boids": `{"before": [{"pane": 1}, {"pane": 0}]}`)
// when the run ends. The card is core/activity-card.js; the check is the core's, fed after every
// lockstep step (sim/activity_check.rs).

import { mountActivityCard } from '../core/activity-card.js';

export function setupActivity(app) {
  const side = document.querySelector('.compare-side');
  const box = document.createElement('div');
  box.id = 'activity';
  side.prepend(box);
  let panes = [];
  let groups = [];
  const card = mountActivityCard(app, box, {
    readActivity: () =>
      app.guard((sim) => {
        const scene = JSON.parse(sim.scene_json());
        groups = scene.groups ?? [];
        panes = JSON.parse(sim.panes_json());
        return scene.activity ?? null;
      }).value ?? null,
    readReport: () => app.guard((sim) => JSON.parse(sim.activity_report_json())).value ?? null,
    groupName: (i) => groups[i]?.name ?? '',
    paneName: (i) => (panes[i] ? `${panes[i].pane} (${panes[i].label})` : 'ABCD'[i] ?? String(i + 1)),
  });
  app.addEventListener('panes', () => card.refresh());
  return card;
}
