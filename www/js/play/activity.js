// The playground's activity card (issue #15 item 4): the scene's prompt at the top of the side
// panel, its prediction asked before the first Play, and the goal's check with the measured values
// when the run ends. The card itself is core/activity-card.js (shared with <flock-path> and the
// compare page); this wires it to the playground's App.

import { mountActivityCard } from '../core/activity-card.js';

export function setupActivity(app) {
  const panel = document.querySelector('aside.panel');
  const box = document.createElement('div');
  box.id = 'activity';
  panel.prepend(box);
  const card = mountActivityCard(app, box, {
    readActivity: () => app.guard((sim) => JSON.parse(sim.activity_json())).value ?? null,
    readReport: () => app.guard((sim) => JSON.parse(sim.activity_report_json())).value ?? null,
    groupName: (i) => app.scene.groups?.[i]?.name ?? '',
  });
  app.addEventListener('scene', () => card.refresh());
  return card;
}
