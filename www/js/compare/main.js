// The compare page: boot, the lockstep frame loop, playback controls, the URL
// (`compare.html#s=<scene>&c=<comparison>`) and the page API `window.flockpathCompare`.
// Rust owns the panes, their runs, metrics, series and summary; this shell only draws and wires.
// The panes (`CompareSim`) run in a Web Worker (core/sim-worker.js, issue 24): calls that change
// them return Promises, reads answer from the mirror of the last frame or reply.

import { bootPage } from '../core/boot.js';
import { messageOf, showMessage } from '../core/errors.js';
import { fragmentValue } from '../core/fragment.js';
import { setupPlayback } from '../core/playback.js';
import { onPage } from '../core/keys.js';
import { prefersReducedMotion } from '../core/motion.js';
import { SimHost, after } from '../core/sim-host.js';
import { RemoteSim } from '../core/sim-proxy.js';
import { startRemoteLoop } from '../core/remote-loop.js';
import { buildPanes, drawPanes, measurePane } from './panes.js';
import { drawPlots, drawTable, explainTable } from './plots.js';
import { download } from '../core/download.js';
import { setupActivity } from './activity.js';
import { setupCompareDescription } from './describe.js';
import { onLanguageChange, setText, t, tOr } from '../core/i18n.js';

const $ = (id) => document.getElementById(id);

/** How often the table and plots refresh while playing (ms, display only). */
const REFRESH_MS = 250;
/** How long changes settle before the address bar is rewritten (ms). */
const WRITE_DELAY_MS = 300;

/** `{ s, c }` from a fragment (`#s=…&c=…`), each null when absent. */
export function parseHash(hash = location.hash) {
  return { s: fragmentValue('s', hash), c: fragmentValue('c', hash) };
}

/** The compare page's state: the wasm handle of the panes behind the shared guarded door. */
class CompareApp extends SimHost {
  /**
   * A change of the panes or the scene (restarts every pane): redraw everything, rewrite the URL.
   * A Promise of the guarded result (the worker answers it).
   */
  change(fn, options = {}) {
    return after(this.guard(fn, options), (result) => {
      if (!result.ok) return;
      this.dirty = true;
      this.dispatchEvent(new Event('panes'));
    });
  }

  /** The link that reopens this comparison. */
  link() {
    const url = new URL(location.href);
    const s = this.guard((sim) => sim.scene_string()).value ?? '';
    const c = this.guard((sim) => sim.spec_string()).value ?? '';
    url.hash = `s=${s}&c=${c}`;
    return url.href;
  }
}

function setupControls(app) {
  const playbackKey = setupPlayback(app);

  $('add-pane').addEventListener('click', () => {
    const used = new Set(JSON.parse(app.guard((sim) => sim.panes_json()).value ?? '[]').map((p) => p.planner));
    const next = app.planners.find((p) => !used.has(p.name))?.name ?? app.planners[0].name;
    app.change((sim) => sim.add_pane(next));
  });
  const refreshAdd = () => {
    const count = app.guard((sim) => sim.pane_count()).value ?? 0;
    $('add-pane').disabled = count >= (app.guard((sim) => sim.max_panes()).value ?? 4);
  };
  app.addEventListener('panes', refreshAdd);
  refreshAdd();

  $('export-csv').addEventListener('click', async () => {
    const csv = await app.guard((sim) => sim.summary_csv());
    if (csv.ok) download('flockpath-comparison.csv', csv.value, 'text/csv');
  });
  $('copy-link').addEventListener('click', async () => {
    const link = app.link();
    try {
      await navigator.clipboard.writeText(link);
      setText($('copy-link'), 'compare.link_copied');
    } catch {
      showMessage(t('compare.clipboard_refused', { link }));
    }
    setTimeout(() => setText($('copy-link'), 'share.copy_link'), 2000);
  });

  const preset = $('preset');
  for (const p of app.presets) {
    preset.append(Object.assign(document.createElement('option'), {
      value: p.name,
      textContent: tOr(`preset.${p.name}`, p.name),
      title: tOr(`preset.${p.name}.description`, p.description),
    }));
  }
  const linkedOption = Object.assign(document.createElement('option'), { value: '', textContent: t('compare.linked_scene'), disabled: true });
  preset.append(linkedOption);
  onLanguageChange(() => {
    for (const option of preset.options) {
      const p = app.presets.find((q) => q.name === option.value);
      if (p) Object.assign(option, { textContent: tOr(`preset.${p.name}`, p.name), title: tOr(`preset.${p.name}.description`, p.description) });
    }
    linkedOption.textContent = t('compare.linked_scene');
    app.dirty = true;
    refresh(app);
  });
  const showPreset = () => {
    const name = JSON.parse(app.guard((sim) => sim.scene_json()).value ?? '{}').name;
    preset.value = app.presets.some((p) => p.name === name) ? name : '';
  };
  preset.addEventListener('change', () => {
    const text = app.guard(() => app.module.preset_scene_json(preset.value));
    if (text.ok) app.change((sim) => sim.load(text.value));
  });
  app.addEventListener('panes', showPreset);
  showPreset();

  document.addEventListener('keydown', (e) => {
    // Single-key shortcuts only while the page or a canvas has focus (core/keys.js).
    if (app.crashed || !onPage(e) || e.ctrlKey || e.metaKey || e.altKey) return;
    if (playbackKey(e)) e.preventDefault();
  });
}

/** Keeps the address bar and the playground link on the current comparison (debounced). */
function keepLocationInSync(app) {
  let timer = null;
  const write = () => {
    timer = null;
    if (app.crashed) return;
    history.replaceState(null, '', app.link());
    const s = app.guard((sim) => sim.scene_string()).value ?? '';
    $('playground-link').href = `index.html#s=${s}`;
  };
  app.addEventListener('panes', () => {
    clearTimeout(timer);
    timer = setTimeout(write, WRITE_DELAY_MS);
  });
  write();
}

/**
 * The frame loop: the worker steps every pane the same fixed steps per frame (hidden tabs do not
 * step) and renders them; each animation frame draws the newest panes and refreshes the table.
 */
function startLoop(app, canvases) {
  let lastRefresh = -Infinity;
  let forced = true;
  const force = () => (forced = true);
  app.addEventListener('stepped', force);
  app.addEventListener('panes', force);
  const onFrame = (now) => {
    if (forced || (app.playing && now - lastRefresh >= REFRESH_MS)) {
      forced = false;
      lastRefresh = now;
      refresh(app);
    }
  };
  startRemoteLoop(app, app.remote, null, onFrame, {
    readout: false,
    stage: $('panes').parentElement,
    draw: (frame) => drawPanes(frame, canvases()),
  });
}

function refresh(app) {
  const result = app.guard((sim) => ({
    steps: sim.steps(),
    metrics: JSON.parse(sim.metrics_json()),
    panes: JSON.parse(sim.panes_json()),
    series: JSON.parse(sim.series_json()),
  }));
  if (!result.ok) return;
  const { steps, metrics, panes, series } = result.value;
  setText($('steps'), 'playback.step_count', { n: steps.toLocaleString('en-US') });
  drawTable($('metrics-table'), panes, metrics);
  explainTable($('metrics-table'));
  drawPlots($('plots'), series);
}

bootPage(t('boot.what_compare'), async ({ module, wasm }) => {
  const presets = JSON.parse(module.presets_json());
  const fallback = module.preset_scene_json(presets[0].name);
  const linked = parseHash();
  const problems = [];
  const { width, height } = measurePane();

  // The link's scene and comparison are checked and loaded in the worker (a big one takes time).
  const remote = new RemoteSim();
  const { sceneError, specError } = await remote.start({
    kind: 'CompareSim',
    sceneText: linked.s ?? fallback,
    fallbackText: fallback,
    specText: linked.c ?? '',
    width,
    height,
  });
  if (sceneError) {
    problems.push(t('compare.link_scene_failed', { reason: messageOf(sceneError), name: tOr(`preset.${presets[0].name}`, presets[0].name) }));
  }
  if (specError) problems.push(t('compare.link_spec_failed', { reason: messageOf(specError) }));

  const app = new CompareApp(wasm, module, remote.handle);
  app.remote = remote;
  // A reader who asked for less motion starts paused (Play plays).
  if (prefersReducedMotion()) app.playing = false;
  app.watchPanics();
  const canvases = buildPanes(app);
  setupControls(app);
  keepLocationInSync(app);
  setupActivity(app);
  // The panes in words for screen readers (core/describe.js's words), after the panes.
  setupCompareDescription(app, $('panes'));
  startLoop(app, canvases);
  $('loading').hidden = true;
  if (problems.length) showMessage(problems.join(' '));

  addEventListener('hashchange', () => {
    const next = parseHash();
    const specChanged = next.c !== null && next.c !== app.guard((s) => s.spec_string()).value;
    const sceneChanged = next.s !== null && next.s !== app.guard((s) => s.scene_string()).value;
    // Both at once: each is checked against the other, not against the one it replaces.
    if (specChanged && sceneChanged) app.change((s) => s.load_with_spec(next.s, next.c));
    else if (specChanged) app.change((s) => s.set_spec(next.c));
    else if (sceneChanged) app.change((s) => s.load(next.s));
  });

  /** Resolves once the worker has answered every call so far (the reads then show it). */
  const settled = async () => {
    do {
      await remote.call('steps').catch(() => {});
      await new Promise((resolve) => setTimeout(resolve, 0));
    } while (remote.busy());
  };
  // Calls that change the panes resolve once the worker did it; reads answer at once.
  window.flockpathCompare = Object.freeze({
    play: () => {
      app.setPlaying(true);
      return settled();
    },
    pause: () => {
      app.setPlaying(false);
      return settled();
    },
    settled,
    isPlaying: () => app.playing,
    step: async (n = 1) => (await app.stepNow(n, { rethrow: true })).value,
    reset: async () => void (await app.reset({ rethrow: true })),
    steps: () => JSON.parse(app.guard((s) => s.pane_steps_json(), { rethrow: true }).value),
    metrics: () => JSON.parse(app.guard((s) => s.metrics_json(), { rethrow: true }).value),
    panes: () => JSON.parse(app.guard((s) => s.panes_json(), { rethrow: true }).value),
    digests: () => JSON.parse(app.guard((s) => s.digests_json(), { rethrow: true }).value),
    series: () => JSON.parse(app.guard((s) => s.series_json(), { rethrow: true }).value),
    summary: () => JSON.parse(app.guard((s) => s.summary_json(), { rethrow: true }).value),
    summaryCsv: () => app.guard((s) => s.summary_csv(), { rethrow: true }).value,
    specString: () => app.guard((s) => s.spec_string(), { rethrow: true }).value,
    sceneString: () => app.guard((s) => s.scene_string(), { rethrow: true }).value,
    setSpec: async (text) => void (await app.change((s) => s.set_spec(text), { rethrow: true })),
    load: async (text) => void (await app.change((s) => s.load(typeof text === 'string' ? text : JSON.stringify(text)), { rethrow: true })),
    link: () => app.link(),
  });
  window.dispatchEvent(new Event('flockpath-compare-ready'));
});
