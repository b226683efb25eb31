// The canvas in words, for screen readers: a visually hidden, polite live region beside a scene
// canvas with two paragraphs, the scene (size, obstacles by shape, goals, each group with its
// agent count, planner and goal, paths) and the run (step, playing or paused, arrived share,
// overlapping pairs now and in total, obstacle penetrations, stuck agents). Only a paragraph whose
// text changed is announced (aria-atomic is off), and the region is rewritten at most once every
// DESCRIBE_EVERY_MS. The figures are the core's (the scene JSON and the metrics JSON, computed in
// Rust); this module only puts them into words. Shared by the playground and <flock-path>
// elements (so also embed.html).

import { language, t } from './i18n.js';

/** The shortest time between two rewrites of a description (ms): a screen reader keeps up. */
export const DESCRIBE_EVERY_MS = 4000;

/** The number format of each language, built once: a scene of thousands of groups counts every one. */
const formats = new Map();

function numbers() {
  const locale = language() === 'zh' ? 'zh-CN' : 'en-US';
  if (!formats.has(locale)) formats.set(locale, new Intl.NumberFormat(locale));
  return formats.get(locale);
}

/** `t(key.one | key.other, { n })` by count (Chinese has one form; both keys exist). */
function counted(key, n, vars = {}) {
  return t(`${key}.${n === 1 ? 'one' : 'other'}`, { n: numbers().format(n), ...vars });
}

/** `items` (already words) as one list: groups, which hold commas, with semicolons. */
function list(items, separator = 'describe.list.separator') {
  return items.join(t(separator));
}

/**
 * The scene in words. `scene` is the core's scene JSON (an object), `planners` its planner list
 * (`[{name, label}]`) for the planners' readable names.
 */
export function describeScene(scene, planners = []) {
  if (!scene) return '';
  const fmt = numbers();
  const sentences = [];
  const size = { width: fmt.format(scene.width ?? 0), height: fmt.format(scene.height ?? 0) };
  sentences.push(scene.name ? t('describe.scene.named', { name: scene.name, ...size }) : t('describe.scene', size));

  const obstacles = scene.obstacles ?? [];
  if (obstacles.length === 0) sentences.push(t('describe.obstacles.none'));
  else {
    const shapes = ['circle', 'rect', 'polygon']
      .map((shape) => [shape, obstacles.filter((o) => o.shape === shape).length])
      .filter(([, n]) => n > 0)
      .map(([shape, n]) => counted(`describe.shape.${shape}`, n));
    sentences.push(t('describe.obstacles', { count: counted('describe.obstacle', obstacles.length), shapes: list(shapes, 'describe.shapes.separator') }));
  }

  const goals = scene.goals ?? [];
  sentences.push(goals.length ? counted('describe.goals', goals.length) : t('describe.goals.none'));

  const groups = scene.groups ?? [];
  if (groups.length === 0) sentences.push(t('describe.groups.none'));
  else {
    const label = (kind) => planners.find((p) => p.name === kind)?.label ?? kind;
    const each = groups.map((g) =>
      t(Number.isInteger(g.goal) ? 'describe.group' : 'describe.group.nogoal', {
        name: g.name || '',
        agents: counted('describe.agents', g.count ?? 0),
        planner: label(g.planner?.kind),
        goal: Number.isInteger(g.goal) ? fmt.format(g.goal + 1) : '',
      }),
    );
    sentences.push(t('describe.groups', { count: counted('describe.group.count', groups.length), groups: list(each) }));
  }

  const paths = scene.paths?.length ?? 0;
  if (paths) sentences.push(counted('describe.paths', paths));
  return sentences.join(' ');
}

/** The run in words, from the core's metrics JSON (an object). */
export function describeRun(metrics, playing) {
  if (!metrics) return '';
  const fmt = numbers();
  const percent = new Intl.NumberFormat(language() === 'zh' ? 'zh-CN' : 'en-US', { style: 'percent', maximumFractionDigits: 0 });
  const sentences = [
    t(playing ? 'describe.step.playing' : 'describe.step.paused', { step: fmt.format(metrics.steps ?? 0) }),
    t('describe.arrived', { share: percent.format(metrics.arrived_share ?? 0), agents: counted('describe.agents', metrics.agents ?? 0) }),
    t('describe.collisions', {
      now: counted('describe.pairs', metrics.collisions_last_step ?? 0),
      total: fmt.format(metrics.collisions_agent_agent ?? 0),
    }),
    counted('describe.penetrations', metrics.penetrations_agent_obstacle ?? 0),
    (metrics.stuck_agents ?? 0) === 0 ? t('describe.stuck.none') : counted('describe.stuck', metrics.stuck_agents),
  ];
  return sentences.join(' ');
}

/**
 * Adds the live description after `anchor` (a canvas) and keeps it current: on the host's
 * `scene`, `stepped` and `playing` events and, while playing, every `every` ms, never more often.
 * `read()` returns `{ scene, metrics, planners, playing }` (null when there is nothing to say).
 * Returns `{ element, update(), stop() }`: `update()` asks for a rewrite (a scene load),
 * `stop()` ends the timers (a removed element).
 */
export function setupDescription(host, anchor, read, { id = '', every = DESCRIBE_EVERY_MS } = {}) {
  const doc = anchor.ownerDocument;
  const element = doc.createElement('div');
  element.className = 'visually-hidden scene-description';
  if (id) element.id = id;
  element.setAttribute('aria-live', 'polite');
  const sceneText = doc.createElement('p');
  const runText = doc.createElement('p');
  element.append(sceneText, runText);
  anchor.after(element);

  let last = -Infinity;
  let timer = null;
  const write = () => {
    timer = null;
    last = performance.now();
    const state = read();
    if (!state) return;
    const words = [describeScene(state.scene, state.planners), describeRun(state.metrics, state.playing)];
    // A paragraph is rewritten only when its words change: only what changed is read out.
    if (sceneText.textContent !== words[0]) sceneText.textContent = words[0];
    if (runText.textContent !== words[1]) runText.textContent = words[1];
  };
  const update = () => {
    if (timer !== null) return;
    timer = setTimeout(write, Math.max(0, last + every - performance.now()));
  };
  for (const name of ['scene', 'stepped', 'playing']) host.addEventListener(name, update);
  const interval = setInterval(() => {
    if (host.playing && !doc.hidden) update();
  }, every);
  write();
  return {
    element,
    update,
    stop() {
      clearInterval(interval);
      clearTimeout(timer);
      timer = null;
      for (const name of ['scene', 'stepped', 'playing']) host.removeEventListener(name, update);
    },
  };
}
