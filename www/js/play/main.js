// Boot: load the wasm module, start the first scene (the link's, else the first preset), wire the
// UI modules, then publish the page API. Every path is relative, so the folder works from any
// static server, under any sub-path, offline.

import { App } from './app.js';
import { attach, flockpath } from './api.js';
import { setupControls } from './controls.js';
import { setupDescription } from '../core/describe.js';
import { Editor } from './editor.js';
import { bootPage } from '../core/boot.js';
import { messageOf, showMessage } from '../core/errors.js';
import { setupHistoryButtons } from './history.js';
import { startRemoteLoop } from '../core/remote-loop.js';
import { RemoteSim } from '../core/sim-proxy.js';
import { setupMetrics } from './metrics.js';
import { setupCapacityNotice } from './capacity-notice.js';
import { setupInspector } from './inspector.js';
import { setupLock } from './lock.js';
import { Panel } from './panel.js';
import { setupExport } from './export.js';
import { setupShare } from './share.js';
import { setupActivity } from './activity.js';
import { setupSceneLinks } from './scene-links.js';
import { setupTimeline } from './timeline.js';
import { keepLocationInSync, sceneFromLocation, showSceneInLocation, watchLocation } from '../core/url.js';
import { measure, setupView } from '../core/view.js';
import { prefersReducedMotion } from '../core/motion.js';
import { t, tOr } from '../core/i18n.js';
import { setupNewScene } from './new-scene.js';
import { setupHelp } from './help.js';
import { setupPresent } from './present.js';
import { setupZoom } from './zoom.js';
import { setupHandout } from './handout.js';

bootPage(t('boot.what_play'), async ({ module, wasm }) => {
  const canvas = document.getElementById('scene-canvas');
  const overlay = document.getElementById('overlay-canvas');
  const { width, height } = measure(canvas);
  canvas.width = width;
  canvas.height = height;
  overlay.width = width;
  overlay.height = height;

  const presets = JSON.parse(module.presets_json());
  // The simulation runs in a worker (core/sim-worker.js): a link that steps for seconds never
  // blocks this page. The link's scene is loaded there too (a big one takes seconds to load).
  const remote = new RemoteSim();
  const { linkError: linkRefusal } = await remote.start({
    sceneText: module.preset_scene_json(presets[0].name),
    linked: sceneFromLocation(),
    width,
    height,
  });
  const linkError = linkRefusal === null ? null : messageOf(linkRefusal);

  const app = new App(wasm, module, remote);
  // A reader who asked for less motion starts paused (Play plays).
  if (prefersReducedMotion()) app.playing = false;
  app.watchPanics();
  app.afterLoad();
  setupView(app, canvas, overlay);
  setupZoom(app, canvas, overlay);
  const editor = new Editor(app, overlay, canvas);
  new Panel(app);
  setupControls(app, editor);
  setupHistoryButtons(app, editor);
  watchLocation(app);
  keepLocationInSync(app);
  const share = setupShare(app);
  setupExport(app, canvas, share);
  setupTimeline(app);
  setupSceneLinks(app);
  setupNewScene(app);
  setupHelp(app);
  setupPresent(app, document.getElementById('stage'));
  const onFrame = setupMetrics(app);
  setupCapacityNotice(app);
  setupInspector(app);
  setupActivity(app);
  setupHandout(app);
  // The canvas in words for screen readers (core/describe.js), beside the canvas.
  setupDescription(app, overlay, () => ({
    scene: app.scene,
    planners: app.planners,
    playing: app.playing,
    metrics: app.guard((s) => JSON.parse(s.metrics_json())).value ?? null,
  }), { id: 'scene-description' });
  // Last: the teacher's link hides and locks what the modules above built.
  setupLock(app, editor);
  startRemoteLoop(app, remote, canvas, onFrame);
  document.getElementById('loading').hidden = true;
  if (linkError !== null) {
    const name = tOr(`preset.${presets[0].name}`, presets[0].name);
    showMessage(t('play.link_failed_default', { reason: linkError, name }));
    showSceneInLocation(app);
  }

  attach(app);
  window.flockpath = flockpath;
  window.dispatchEvent(new Event('flockpath-ready'));
});
