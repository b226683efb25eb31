// The compare page in words, for screen readers: a visually hidden, polite live region after the
// panes with one paragraph for the scene (core/describe.js's words) and one per pane naming its
// planner, then its run (step, arrived share, collisions, penetrations, stuck agents). Only a
// paragraph whose words changed is rewritten, at most once every DESCRIBE_EVERY_MS. The figures
// are the core's (scene JSON, panes JSON, metrics JSON); this module only puts them into words.

import { DESCRIBE_EVERY_MS, describeRun, describeScene } from '../core/describe.js';
import { onLanguageChange, t } from '../core/i18n.js';
import { paneLabel } from './panes.js';

/** Adds the description after `anchor` (the panes area) and keeps it current; returns it. */
export function setupCompareDescription(app, anchor, every = DESCRIBE_EVERY_MS) {
  const element = document.createElement('div');
  element.id = 'compare-description';
  element.className = 'visually-hidden scene-description';
  element.setAttribute('aria-live', 'polite');
  const sceneText = document.createElement('p');
  // Each pane's canvas points here (`aria-describedby`, panes.js): the scene, then its pane.
  sceneText.id = 'compare-description-scene';
  element.append(sceneText);
  anchor.after(element);

  const put = (p, words) => {
    if (p.textContent !== words) p.textContent = words;
  };
  let last = -Infinity;
  let timer = null;
  const write = () => {
    timer = null;
    last = performance.now();
    const state = app.guard((sim) => ({
      scene: JSON.parse(sim.scene_json()),
      panes: JSON.parse(sim.panes_json()),
      metrics: JSON.parse(sim.metrics_json()),
    }));
    if (!state.ok) return;
    const { scene, panes, metrics } = state.value;
    put(sceneText, `${t(`compare.describe.intro.${panes.length === 1 ? 'one' : 'other'}`, { n: panes.length })} ${describeScene(scene, app.planners)}`);
    const paragraphs = [...element.querySelectorAll('p[data-pane]')];
    for (const p of paragraphs.slice(panes.length)) p.remove();
    panes.forEach((pane, i) => {
      let p = paragraphs[i];
      if (!p) element.append((p = document.createElement('p')));
      p.dataset.pane = pane.pane;
      p.id = `compare-description-${pane.pane}`;
      const head = t('compare.describe.pane', { pane: pane.pane, label: paneLabel(app, pane) });
      put(p, `${head} ${describeRun(metrics[i], app.playing)}`);
    });
  };
  const update = () => {
    if (timer !== null) return;
    timer = setTimeout(write, Math.max(0, last + every - performance.now()));
  };
  for (const name of ['panes', 'stepped', 'playing']) app.addEventListener(name, update);
  onLanguageChange(update);
  setInterval(() => {
    if (app.playing && !document.hidden && !app.crashed) update();
  }, every);
  write();
  return element;
}
