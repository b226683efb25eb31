// The student handout (issue #27 §3): what the playground prints. A print-only head above the
// canvas gives the scene's title, its description (the preset's line; an activity's prompt is on
// its card) and a legend of the groups (colour, name, planner); under
// `@media print` (style.css) the canvas's still (core/print.js) takes the full width at the
// canvas's own aspect, followed by the activity's question, the metrics card and the plots, and every
// button, slider and other panel is left out, so a run prints on at most two A4 pages.

import { onLanguageChange, setText, t, tOr } from '../core/i18n.js';

const el = (tag, props = {}, ...children) => {
  const node = Object.assign(document.createElement(tag), props);
  node.append(...children);
  return node;
};

/** Builds the print-only head and keeps it in step with the scene and the language. */
export function setupHandout(app) {
  const stage = document.getElementById('stage');
  if (!stage) return;
  const head = el('section', { id: 'handout-head', className: 'handout-head' });
  head.setAttribute('aria-hidden', 'true'); // a copy of what the page already shows, for paper only
  stage.before(head);
  // The metrics and the plots over time print; every other card (settings, editing) does not.
  for (const id of ['metrics-title', 'plots-title']) document.getElementById(id)?.closest('section.card')?.classList.add('handout-keep');

  const fill = () => {
    const scene = app.scene ?? {};
    const preset = app.presets?.find((p) => p.name === scene.name);
    const title = preset ? tOr(`preset.${preset.name}`, preset.name) : scene.name || t('play.edited_scene');
    // An activity's prompt is printed on its card below the canvas.
    const description = preset ? tOr(`preset.${preset.name}.description`, preset.description) : '';
    const legend = el('ul', { className: 'handout-legend' }, ...(scene.groups ?? []).map((g) => {
      const swatch = el('span', { className: 'handout-swatch' });
      swatch.style.setProperty('background', g.color);
      const planner = app.planners?.find((p) => p.name === g.planner?.kind);
      const plannerName = tOr(`planner.${g.planner?.kind}`, planner?.label ?? g.planner?.kind ?? '');
      return el('li', {}, swatch, `${g.name} — ${plannerName} (${g.count})`);
    }));
    head.replaceChildren(
      el('h2', { className: 'handout-title' }, title),
      el('p', { className: 'handout-description' }, description),
      setText(el('h3', { className: 'handout-legend-title' }), 'activities.handout_legend'),
      legend,
    );
  };
  /** The stage prints at the canvas's own aspect, so its still fills the width without bands. */
  const sizeStage = () => {
    const canvas = document.getElementById('scene-canvas');
    if (canvas?.width && canvas.height) stage.style.setProperty('--handout-aspect', `${canvas.width} / ${canvas.height}`);
    fill();
  };
  app.addEventListener('scene', fill);
  onLanguageChange(fill);
  addEventListener('beforeprint', sizeStage);
  matchMedia('print').addEventListener?.('change', (event) => {
    if (event.matches) sizeStage();
  });
  fill();
}
