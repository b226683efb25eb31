// Languages (issue #15 item 7): every user-visible string of the pages comes from one table per
// language (www/js/core/strings/*.js). Checked here:
// - the tables: same keys in every shipped language, no empty value, the same `{placeholders}`,
//   no key written twice; the core's tables (planners, parameters, choices, presets, metric
//   series, from the wasm module) all have their keys, in English with the core's own words;
// - the pages' HTML: no visible literal text outside `data-i18n` (a static scan, no browser);
// - in Chromium: `?lang=zh` shows Chinese on every page and leaves no English words in the header
//   and the panels; a browser whose language is zh-CN picks Chinese without `?lang`; switching
//   language keeps the scene and the run; a refused input is worded in Chinese.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import { CHROMIUM_ARGS, WWW, assertNoUnexpectedErrors, launchBrowser, simpleScene } from './helpers.mjs';

const STRINGS = path.join(WWW, 'js', 'core', 'strings');
const SHIPPED = ['en', 'zh'];

async function table(code) {
  return (await import(path.join(STRINGS, `${code}.js`))).default;
}

const placeholders = (text) => [...text.matchAll(/\{(\w+)\}/g)].map((m) => m[1]).sort();

/** The page's wasm module (www/pkg), set up here in Node: the core's own words and errors, no browser. */
async function wasmModule() {
  const pkg = path.join(WWW, 'pkg');
  const m = await import(path.join(pkg, 'flockpath.js'));
  m.initSync({ module: await readFile(path.join(pkg, 'flockpath_bg.wasm')) });
  return m;
}

/** One of the pages' scripts, `www/js/<parts>`. */
const pageModule = (...parts) => import(path.join(WWW, 'js', ...parts));

/** The error `fn` throws; fails the test when it throws none. */
function refused(fn) {
  try {
    fn();
  } catch (error) {
    return error;
  }
  throw new Error('not refused');
}

test('every shipped table has the same keys, no empty value and the same placeholders', async () => {
  const en = await table('en');
  assert.ok(Object.keys(en).length > 300, 'the English table holds the pages’ words');
  for (const code of SHIPPED) {
    const other = await table(code);
    const missing = Object.keys(en).filter((k) => !Object.hasOwn(other, k));
    const extra = Object.keys(other).filter((k) => !Object.hasOwn(en, k));
    assert.deepEqual(missing, [], `${code} lacks keys of en`);
    assert.deepEqual(extra, [], `${code} has keys en lacks`);
    for (const [key, value] of Object.entries(other)) {
      assert.equal(typeof value, 'string', `${code} ${key} is text`);
      assert.ok(value.trim().length > 0, `${code} ${key} is not empty`);
      assert.deepEqual(placeholders(value), placeholders(en[key]), `${code} ${key}: the same {placeholders} as en`);
    }
  }
});

test('no table writes a key twice (a later duplicate would silently win)', async () => {
  for (const code of SHIPPED) {
    const source = await readFile(path.join(STRINGS, `${code}.js`), 'utf8');
    const keys = [...source.matchAll(/^\s*(['"])((?:(?!\1).)+)\1\s*:/gm)].map((m) => m[2]);
    const seen = new Set();
    const twice = keys.filter((k) => (seen.has(k) ? true : (seen.add(k), false)));
    assert.deepEqual(twice, [], `${code}.js writes these keys twice`);
  }
});

test('the Chinese table is Chinese: most values hold CJK characters', async () => {
  const zh = await table('zh');
  const values = Object.values(zh);
  const cjk = values.filter((v) => /[\u4e00-\u9fff]/.test(v)).length;
  assert.ok(cjk / values.length > 0.85, `only ${cjk} of ${values.length} zh values hold Chinese`);
});

test('the core’s planners, parameters, choices, units, presets, series and validation tests all have their keys', async () => {
  const m = await wasmModule();
  const en = await table('en');
  const zh = await table('zh');
  const expect = new Map();
  const planners = JSON.parse(m.planners_json());
  for (const p of planners) {
    expect.set(`planner.${p.name}`, p.label);
    for (const s of p.params) {
      expect.set(`param.${p.name}.${s.key}`, s.label);
      expect.set(`param.${p.name}.${s.key}.help`, s.help);
      for (const c of s.choices ?? []) expect.set(`choice.${c}`, c);
    }
  }
  for (const p of JSON.parse(m.presets_json())) {
    expect.set(`preset.${p.name}`, p.name);
    expect.set(`preset.${p.name}.description`, p.description);
  }
  const sim = new m.Sim(m.preset_scene_json('open-field'), 200, 150);
  for (const s of JSON.parse(sim.history_json()).series) expect.set(`series.${s.key}`, s.label);
  sim.free();
  for (const test of JSON.parse(m.validation_options_json()).tests) {
    expect.set(`validation.test.${test.id}`, test.title);
    expect.set(`validation.test.${test.id}.criterion`, test.criterion);
    expect.set(`validation.test.${test.id}.setup`, test.setup);
    expect.set(`validation.test.${test.id}.measurement`, test.measurement);
  }
  assert.ok(expect.size > 250, `${expect.size} core words`);
  for (const [key, words] of expect) {
    assert.equal(en[key], words, `en ${key} is the core’s own words`);
    assert.ok(Object.hasOwn(zh, key), `zh has ${key}`);
  }
  // Every unit a parameter shows in px terms is translated (international units are shown as is).
  for (const p of planners) {
    for (const s of p.params) {
      if (/px|step|body/.test(s.unit)) assert.ok(Object.hasOwn(zh, `unit.${s.unit}`), `zh has unit.${s.unit}`);
    }
  }
});

test('the core’s refusals are worded in Chinese (real errors from the wasm module, no browser)', async () => {
  const m = await wasmModule();
  const i18n = await pageModule('core', 'i18n.js');
  const { errorText: refusalText } = await pageModule('core', 'messages.js');
  const base = JSON.parse(m.preset_scene_json('open-field'));
  const dense = structuredClone(base);
  Object.assign(dense.groups[0], { count: 5000, spawn: { min: [10, 10], max: [60, 60] } });
  // src/sim/cost.rs: 571 one-agent ORCA groups, each heading for a goal of its own round an
  // obstacle in a 20,000 px world, keep 571 distinct flow fields of 1.9 MB: over 1 GiB.
  const memory = structuredClone(base);
  Object.assign(memory, { width: 20000, height: 20000, obstacles: [{ shape: 'circle', center: [10000, 10000], radius: 300 }] });
  memory.goals = Array.from({ length: 571 }, (_, k) => ({ position: [19700, 100 + 19 * k], radius: 8 }));
  memory.groups = memory.goals.map((_, k) => ({
    ...base.groups[0], name: `g${k}`, count: 1, goal: k, spawn: { min: [100, 100 + 19 * k], max: [110, 110 + 19 * k] }, planner: { kind: 'orca', params: {} },
  }));
  const sim = new m.Sim(m.preset_scene_json('open-field'), 200, 100);
  const cases = {
    density: refused(() => new m.Sim(JSON.stringify(dense), 100, 100)),
    memory: refused(() => new m.Sim(JSON.stringify(memory), 100, 100)),
    planner: refused(() => sim.set_group_planner(0, 'teleport')),
    preset: refused(() => m.preset_scene_json('no-such-preset')),
    range: refused(() => sim.set_group_param(0, 'max_speed', '1000000')),
    type: refused(() => sim.set_group_param(0, 'max_speed', '"fast"')),
    base64: refused(() => sim.load('2.!!!')),
    damaged: refused(() => sim.load('2.AAAA')),
    version: refused(() => sim.load('7.abc')),
    field: refused(() => sim.edit(JSON.stringify({ op: 'set_group', index: 0, group: { ...base.groups[0], agent_radius: 500 } }))),
    negative: refused(() => sim.edit(JSON.stringify({ op: 'set_group', index: 0, group: { ...base.groups[0], count: -5 } }))),
  };
  sim.free();
  // Identifiers the messages quote (preset and planner names) are no language.
  const names = new Set(JSON.parse(m.presets_json()).map((p) => p.name));
  try {
    for (const [k, e] of Object.entries(cases)) assert.equal(refusalText(e), e.message, `${k}: the English template is the core’s words`);
    await i18n.setLanguage('zh', null);
    const zh = Object.fromEntries(Object.entries(cases).map(([k, e]) => [k, refusalText(e)]));
    for (const [k, text] of Object.entries(zh)) {
      assert.equal(typeof cases[k].code, 'string', `${k} carries a code`);
      assert.ok(text && /[\u4e00-\u9fff]/.test(text), `${k} in Chinese: ${text} (core: ${cases[k].message})`);
      const english = (text.match(/[A-Za-z][\w'-]{3,}/g) ?? []).filter((w) => !names.has(w) && !['flock', 'boids', 'teleport', 'firefly', 'forces', 'igsa', 'orca', 'social_force', 'collision_free_speed', 'fast', 'string', 'flockpath', 'pillars', 'open', 'field', 'groups', 'agent_radius', 'max_speed', 'count', 'preset', 'such', 'base64'].includes(w) && !/^[a-z]+(-[a-z0-9]+)+$/.test(w));
      assert.deepEqual(english, [], `${k}: no English words left in ${text}`);
    }
    assert.equal(zh.density, '群组 1（flock）：5000 个半径 4 像素的个体放不进其出生区域（50×50 像素）：在彼此、障碍物和其他群组之间保持间隔时最多只能放 49 个（密度上限）');
    assert.equal(cases.memory.code, 'scene.flow_field_memory');
    assert.match(cases.memory.message, /^groups\[570\]: the groups' 571 distinct flow fields \(156816 cells each.* over the 1024 MB limit/);
    assert.match(zh.memory, /^groups\[570\]：各群组共需 571 个不同的流场（每个 156816 个格子.*超过 1024 MB 的上限/);
    assert.equal(zh.range, '最大速度（max_speed）的值为 1000000；允许：0.1…20 像素/步 之间的数');
    assert.equal(zh.version, '无法读取场景：未知的场景格式版本“7”；此 flockpath 能读取的版本为 1 和 2');
    assert.equal(zh.field, 'groups[0].agent_radius 的值为 500；允许：0.5…100 像素 之间的数');
    assert.equal(zh.negative, '无法读取编辑操作：无效的值：整数 -5，应为 u32');
  } finally {
    await i18n.setLanguage('en', null);
  }
});

/** Words of `text` that look English (4+ Latin letters), leaving out identifiers in `names`. */
function englishWords(text, names) {
  return (text.match(/[A-Za-z][\w'-]{3,}/g) ?? []).filter((w) => !names.has(w) && !/^[a-z]+(-[a-z0-9.]+)+$/.test(w) && !/^[a-z]+(_[a-z]+)+$/.test(w));
}

test('every other refusal is worded in Chinese too: scene fields, items, compare specs, lab, tune, validation, export, theme (real errors from the wasm module)', async () => {
  const m = await wasmModule();
  const i18n = await pageModule('core', 'i18n.js');
  const { errorText: refusalText } = await pageModule('core', 'messages.js');
  const en = await table('en');
  const zhTable = await table('zh');
  const base = JSON.parse(m.preset_scene_json('open-field'));
  const scene = (change) => {
    const s = structuredClone(base);
    change(s);
    return JSON.stringify(s);
  };
  const load = (text) => refused(() => new m.Sim(text, 100, 100));
  const sim = new m.Sim(m.preset_scene_json('open-field'), 200, 100);
  const group = base.groups[0];
  const cases = {
    // The scene's own checks (src/model/scene.rs): what each field allows, in words.
    inside_world: load(scene((s) => { s.groups[0].spawn.min = [-5, 10]; })),
    near_world: load(scene((s) => { s.obstacles.push({ shape: 'circle', center: [1e6, 10], radius: 5 }); })),
    rect_area: load(scene((s) => { s.obstacles.push({ shape: 'rect', min: [50, 50], max: [40, 60] }); })),
    polygon: load(scene((s) => { s.obstacles.push({ shape: 'polygon', points: [[10, 10], [60, 60], [60, 10], [10, 60]] }); })),
    spawn_order: load(scene((s) => { s.groups[0].spawn = { min: [300, 100], max: [200, 200] }; })),
    goal_index: load(scene((s) => { s.groups[0].goal = 9; })),
    path_number: load(scene((s) => { s.groups[0].planner = { kind: 'boids', params: { path: 3 } }; })),
    scale: load(scene((s) => { s.px_per_metre = 1e6; })),
    unknown_key: load(scene((s) => { s.groups[0].colour = '#ff0000'; })),
    missing_key: load(scene((s) => { delete s.width; })),
    list_of: load(scene((s) => { s.paths = [{ points: [[10, 10]], radius: 10 }]; })),
    // Items and edits.
    no_item: refused(() => sim.edit(JSON.stringify({ op: 'delete', item: { kind: 'obstacle', index: 99 } }))),
    path_boids: refused(() => {
      sim.set_group_planner(0, 'pso');
      sim.edit(JSON.stringify({ op: 'add_path', points: [[10, 10], [90, 90]], group: 0 }));
    }),
    trailing: refused(() => sim.load(`${m.preset_scene_json('open-field')} }`)),
    no_group: refused(() => sim.set_group_param(9, 'max_speed', '1')),
    not_json: refused(() => sim.set_group_param(0, 'max_speed', '{')),
    waypoints: refused(() => sim.set_group_waypoints(0, '[1]')),
    not_igsa: refused(() => sim.set_group_waypoints(0, '[]')),
    // The compare page's spec (`c=`) and panes.
    spec_planner: refused(() => m.compare_spec_check('1.zz')),
    spec_version: refused(() => m.compare_spec_check('7.scene')),
    spec_empty_pane: refused(() => m.compare_spec_check('1.scene~')),
    spec_count: refused(() => m.compare_spec_check(`1.pso(${Array(40).fill(1).join(',')})`)),
    spec_number: refused(() => m.compare_spec_check('1.boids(x)')),
    spec_range: refused(() => m.compare_spec_check('1.boids(1e9)')),
    spec_group_zero: refused(() => m.compare_spec_check('1.0=pso')),
    spec_panes: refused(() => m.compare_spec_check('1.scene~scene~scene~scene~scene')),
    spec_group_missing: refused(() => new m.CompareSim(m.preset_scene_json('open-field'), '1.5=pso', 100, 100)),
    spec_scene: refused(() => new m.CompareSim(JSON.stringify({ ...base, groups: [{ ...group, count: 5000, spawn: { min: [10, 10], max: [60, 60] } }] }), '', 100, 100)),
    // The lab, the tune page, the validation suite, the exports, the theme.
    lab_algorithm: refused(() => new m.Lab('zz', 'sphere', 2, 10, 10, 1)),
    lab_function: refused(() => new m.Lab('pso', 'zz', 2, 10, 10, 1)),
    lab_settings: refused(() => m.lab_best_of_run('pso', 'sphere', 2, 1, 10, 1, 0)),
    tune_settings: refused(() => new m.TuneRun('{"frames": "many"}')),
    tune_frames: refused(() => new m.TuneRun('{"frames": 0}')),
    tune_behaviour: refused(() => new m.TuneRun('{"behaviour": "b9"}')),
    tune_scene: refused(() => new m.TuneRun(JSON.stringify({ scene: '7.abc' }))),
    validation_test: refused(() => m.validation_run_json('zz', 'boids')),
    validation_curve: refused(() => m.validation_reference_speeds('zz', Float64Array.from([1]))),
    export_fps: refused(() => sim.export_maya_mel(0, 1)),
    export_scale: refused(() => sim.export_blender_py(30, -1)),
    theme: refused(() => sim.set_theme('zz')),
  };
  sim.free();
  // Identifiers the messages quote: preset, planner, algorithm, function, theme and field names.
  const options = JSON.parse(m.lab_options_json());
  const names = new Set([...JSON.parse(m.presets_json()).map((p) => p.name), ...JSON.parse(m.planners_json()).map((p) => p.name),
    ...options.algorithms.map((a) => a.name), ...options.functions.map((f) => f.name), 'standard', 'projector', 'weidmann', 'seyfried',
    'scene', 'null', 'true', 'false', 'flockpath', 'groups', 'spawn', 'goal', 'goals', 'obstacles', 'points', 'path', 'params', 'planner',
    'width', 'height', 'colour', 'color', 'kind', 'shape', 'center', 'radius', 'agent_radius', 'px_per_metre', 'name', 'count',
    'paths', 'hills', 'view', 'seed', 'activity', 'base64', 'JSON', 'many', ...ALLOWED_WORDS, 'Reynolds']);
  // Each key a case's Chinese text comes from has its pair in both tables.
  for (const key of Object.keys(zhTable).filter((k) => /^(error|allowed|value|item|items|validation\.measured)\./.test(k))) {
    assert.ok(Object.hasOwn(en, key), `en has ${key}`);
  }
  try {
    for (const [k, e] of Object.entries(cases)) assert.equal(typeof e.code, 'string', `${k} carries a code (${e.message})`);
    for (const [k, e] of Object.entries(cases)) assert.equal(refusalText(e), e.message, `${k}: the English template is the core’s words`);
    assert.match(cases.spec_planner.message, /^comparison: unknown planner "zz"/, 'the English message is unchanged');
    await i18n.setLanguage('zh', null);
    const zh = Object.fromEntries(Object.entries(cases).map(([k, e]) => [k, refusalText(e)]));
    for (const [k, text] of Object.entries(zh)) {
      assert.ok(text && /[\u4e00-\u9fff]/.test(text), `${k} in Chinese: ${text} (core: ${cases[k].message})`);
      assert.deepEqual(englishWords(text, names), [], `${k}: no English words left in ${text} (core: ${cases[k].message})`);
      if (process.env.I18N_SHOW) console.log(`${k} | ${text}`);
    }
    assert.equal(zh.no_item, '不存在障碍物 100');
    assert.match(zh.spec_planner, /^比较：未知的规划器“zz”；可用的有：/);
    assert.match(zh.polygon, /^obstacles\[\d+\]\.points 的值为 边 \d+→\d+ 与 \d+→\d+ 相交或接触的多边形；允许：简单多边形/);
    assert.match(zh.tune_scene, /^无法读取场景：未知的场景格式版本“7”/, 'a tuning scene keeps its own code');
  } finally {
    await i18n.setLanguage('en', null);
  }
});

// Issue 24: a name of 7 MiB, a lone surrogate in a name, a link longer than a browser keeps and
// lab sizes past the form's maxima are refused naming the field and the limit, in both languages.
test('names, strings that are no text, links too long and lab sizes are refused by field and limit, in English and Chinese (wasm module, no browser)', async () => {
  const m = await wasmModule();
  const i18n = await pageModule('core', 'i18n.js');
  const { errorText: refusalText } = await pageModule('core', 'messages.js');
  const base = JSON.parse(m.preset_scene_json('open-field'));
  const withName = (name) => {
    const s = structuredClone(base);
    s.groups[0].name = name;
    return JSON.stringify(s);
  };
  const load = (text) => refused(() => new m.Sim(text, 100, 100));
  // Empty groups with 100 random CJK characters each: their link outgrows what a browser keeps.
  const many = structuredClone(base);
  let seed = 24;
  const cjk = () => String.fromCharCode(0x4e00 + (((seed = (Math.imul(seed, 1103515245) + 12345) >>> 0) >>> 8) % 32768));
  for (let i = 0; i < 8500; i++) many.groups.push({ name: Array.from({ length: 100 }, cjk).join(''), count: 0, spawn: base.groups[0].spawn });
  const cases = {
    long_name: load(withName('x'.repeat(7 << 20))),
    // JSON.stringify writes a lone surrogate as the escape `\ud800`, as a hand-edited file would.
    surrogate: load(withName('\ud800x')),
    escape: load(withName('ab').replace('"ab"', '"a\\qb"')),
    long_link: load(JSON.stringify(many)),
    lab_dimension: refused(() => new m.Lab('pso', 'sphere', 201, 30, 300, 1)),
    lab_population: refused(() => new m.Lab('pso', 'sphere', 2, 501, 300, 1)),
    lab_iterations: refused(() => m.lab_best_of_run('pso', 'sphere', 2, 30, 10001, 1, 0)),
  };
  assert.equal(cases.long_name.message, 'groups[0].name is text of 7340032 character(s) ("xxxxxxxxxxxxxxxxxxxxxxxx"…); allowed: text of at most 100 characters on one line');
  assert.equal(cases.surrogate.message, 'groups[0].name is an invalid string (the lone surrogate \\ud800); allowed: text in which each \\ud800…\\udbff escape is followed by a \\udc00…\\udfff one (a surrogate pair)');
  assert.equal(cases.escape.message, 'groups[0].name is an invalid string (the escape \\q); allowed: text whose escapes are \\" \\\\ \\/ \\b \\f \\n \\r \\t or \\u and 4 hex digits');
  assert.match(cases.long_link.message, /^the scene's link is too large \(\d+ bytes; limit 2000000 bytes\)$/);
  assert.equal(cases.lab_dimension.message, 'dimension 201 is outside 1…200');
  assert.equal(cases.lab_population.message, 'population 501 is outside 2…500');
  assert.equal(cases.lab_iterations.message, 'iterations 10001 is outside 1…10000');
  // The lab's form offers exactly what the core accepts: its maxima load, one more is refused.
  const html = await readFile(path.join(WWW, 'lab.html'), 'utf8');
  const max = (id) => Number(new RegExp(`id="${id}"[^>]*max="(\\d+)"`).exec(html)?.[1]);
  assert.deepEqual([max('lab-dim'), max('lab-pop'), max('lab-iters')], [200, 500, 10000]);
  new m.Lab('pso', 'sphere', max('lab-dim'), max('lab-pop'), max('lab-iters'), 1).free();
  try {
    for (const [k, e] of Object.entries(cases)) assert.equal(refusalText(e), e.message, `${k}: the English template is the core’s words`);
    await i18n.setLanguage('zh', null);
    const zh = Object.fromEntries(Object.entries(cases).map(([k, e]) => [k, refusalText(e)]));
    assert.equal(zh.long_name, 'groups[0].name 的值为 7340032 个字符的文本（"xxxxxxxxxxxxxxxxxxxxxxxx"…）；允许：单行文本，最多 100 个字符');
    assert.equal(zh.surrogate, 'groups[0].name 的值为 无效的字符串（孤立的代理项 \\ud800）；允许：文本，其中每个 \\ud800…\\udbff 转义之后必须紧跟一个 \\udc00…\\udfff 转义（代理对）');
    assert.equal(zh.escape, 'groups[0].name 的值为 无效的字符串（无效的转义 \\q）；允许：文本，其中的转义只能是 \\" \\\\ \\/ \\b \\f \\n \\r \\t，或 \\u 加 4 位十六进制数字');
    assert.match(zh.long_link, /^场景链接太大（\d+ 字节；上限 2000000 字节）$/);
    assert.equal(zh.lab_dimension, '维数 201 超出 1…200 的范围');
    assert.equal(zh.lab_population, '种群规模 501 超出 2…500 的范围');
    assert.equal(zh.lab_iterations, '迭代次数 10001 超出 1…10000 的范围');
  } finally {
    await i18n.setLanguage('en', null);
  }
});

test('the validation suite’s "measured" words are Chinese for every test (real rows from the wasm module)', async () => {
  const m = await wasmModule();
  const i18n = await pageModule('core', 'i18n.js');
  const { measuredText } = await pageModule('validation', 'measured.js');
  const rows = [];
  for (const test of JSON.parse(m.validation_options_json()).tests) {
    rows.push(...JSON.parse(m.validation_run_json(test.id, 'forces')).rows);
  }
  try {
    assert.equal(measuredText(rows[0].measured), rows[0].measured, 'English pages show the core’s words');
    await i18n.setLanguage('zh', null);
    for (const row of rows) {
      const text = measuredText(row.measured);
      assert.match(text, /[\u4e00-\u9fff]/, `${row.test}: ${text}`);
      assert.deepEqual(englishWords(text, new Set()), [], `${row.test}: no English words left in ${text} (core: ${row.measured})`);
    }
  } finally {
    await i18n.setLanguage('en', null);
  }
});

// ---- static scan of the pages' HTML ----

/** Pages a student meets; bench.html is a developer benchmark (not linked from any page). */
const PAGES = ['index.html', 'embed.html', 'compare.html', 'tune.html', 'lab.html', 'validation.html', 'activities.html'];

/** Words that are no language: units, proper names, file formats, key names. */
const NEUTRAL_WORDS = new Set(['fps', 'px', 'flock', 'path', 'flockpath', 'Ctrl', 'Esc', 'Del', 'Space', 'Enter', 'Boids', 'PSO',
  'IGSA', 'GSA', 'ORCA', 'Gsum', 'Weidmann', 'Jülich', 'RiMEA', 'REC', 'MEL', 'CSV', 'JSON', 'SVG', 'PNG', 'WebM', 'Maya',
  'Blender', 'Python']);

/** Whether a text is no language: numbers, symbols, single letters and neutral words only. */
const neutral = (text) => (text.match(/[A-Za-zÀ-ÿ][A-Za-zÀ-ÿ’'-]*/g) ?? []).every((w) => w.length === 1 || NEUTRAL_WORDS.has(w));

/**
 * The visible text nodes of an HTML page outside a `data-i18n` element (a tokenizer good enough
 * for the pages' own HTML): `<script>`, `<style>`, comments and `<code>` (commands) are skipped.
 */
function literalTexts(html) {
  const found = [];
  const stack = [];
  const VOID = new Set(['meta', 'link', 'input', 'br', 'img', 'hr', 'source', 'col', 'wbr', 'path']);
  const re = /<!--[\s\S]*?-->|<![^>]*>|<(script|style)\b[\s\S]*?<\/\1>|<\/?([a-zA-Z][\w-]*)([^>]*)>|([^<]+)/g;
  for (const m of html.matchAll(re)) {
    if (m[2]) {
      const tag = m[2].toLowerCase();
      if (m[0].startsWith('</')) {
        while (stack.length && stack.pop().tag !== tag);
      } else if (!VOID.has(tag) && !m[0].endsWith('/>')) {
        const marked = /\sdata-i18n(?:-html)?=/.test(m[3]);
        stack.push({ tag, marked });
      }
    } else if (m[4] !== undefined) {
      const text = m[4].replace(/&[a-z]+;|&#\d+;/g, ' ').trim();
      if (!text) continue;
      if (stack.some((s) => s.marked || s.tag === 'code' || s.tag === 'kbd' || s.tag === 'svg')) continue;
      if (neutral(text)) continue;
      found.push(text);
    }
  }
  return found;
}

test('static: no page holds visible literal text outside data-i18n', async () => {
  for (const page of PAGES) {
    const html = await readFile(path.join(WWW, page), 'utf8');
    assert.deepEqual(literalTexts(html), [], `${page}: text not from the tables`);
    assert.match(html, /js\/core\/language-menu\.js/, `${page} loads the language module`);
    // Attributes a reader meets (title, aria-label, placeholder, alt) carry their key too.
    for (const m of html.matchAll(/<[a-z][^>]*\s(title|aria-label|placeholder|alt)="([^"]*[A-Za-z]{3}[^"]*)"[^>]*>/g)) {
      const attribute = m[1];
      assert.ok(m[0].includes(`data-i18n-${attribute}=`), `${page}: ${attribute}="${m[2]}" has no data-i18n-${attribute}`);
    }
  }
  // The scanner does see literal text (a check that could fail).
  assert.deepEqual(literalTexts('<p>Hello <b data-i18n="x">World</b> 42 px</p>'), ['Hello']);
});

test('static: the course notes’ element fallbacks come from the tables', async () => {
  const html = await readFile(path.join(WWW, 'examples', 'course-notes.html'), 'utf8');
  const body = html.replace(/<!--[\s\S]*?-->/g, '');
  const fallbacks = [...body.matchAll(/<flock-path\s[^>]*>([\s\S]*?)<\/flock-path>/g)].map((m) => m[1]);
  assert.ok(fallbacks.length >= 2);
  for (const inner of fallbacks) assert.deepEqual(literalTexts(inner), [], 'fallback text of <flock-path>');
});

// ---- in Chromium ----

/**
 * Chromium (in `locale`, when given) and the server, nothing opened yet. Failed requests are not
 * counted as errors here: these tests leave pages while their requests are in flight.
 */
async function openBrowser({ locale } = {}) {
  const { page, errors, close, server } = await launchBrowser(
    {
      args: [...CHROMIUM_ARGS, ...(locale ? [`--lang=${locale}`] : [])],
      viewport: { width: 1280, height: 900 },
      serviceWorkers: 'block',
      ...(locale ? { locale } : {}),
    },
    { requestFailures: false, profilePrefix: 'flockpath-i18n-' },
  );
  return { page, errors, close, url: server.url };
}

/** Words of visible text nodes under `selector` that look English (3+ Latin letters, not allowed). */
async function englishLeftovers(page, selector) {
  return page.evaluate(
    ({ selector, allowed }) => {
      const ok = new Set(allowed);
      const words = [];
      for (const root of document.querySelectorAll(selector)) {
        const walker = document.createTreeWalker(root, NodeFilter.SHOW_TEXT);
        for (let node = walker.nextNode(); node; node = walker.nextNode()) {
          const el = node.parentElement;
          if (!el || el.closest('script, style, code, kbd, #lang-select, [hidden]')) continue;
          if (el.getClientRects().length === 0) continue;
          const style = getComputedStyle(el);
          if (style.visibility === 'hidden' || style.display === 'none') continue;
          for (const word of node.textContent.match(/[A-Za-z][A-Za-z’'-]{2,}/g) ?? []) {
            if (!ok.has(word)) words.push(word);
          }
        }
      }
      return words;
    },
    { selector, allowed: ALLOWED_WORDS },
  );
}

/** Proper names, units and file formats shown as they are in every language. */
const ALLOWED_WORDS = ['flock', 'path', 'flockpath', 'Boids', 'PSO', 'IGSA', 'GSA', 'ORCA', 'Gsum', 'Ctrl', 'Esc', 'Del', 'Tab', 'Shift', 'Enter',
  'Space', 'fps', 'CSV', 'JSON', 'SVG', 'PNG', 'WebM', 'MEL', 'Maya', 'Blender', 'Python', 'Chen', 'Lin', 'Zhang', 'Liu',
  'Helbing', 'Molnár', 'van', 'den', 'Berg', 'RiMEA', 'Jülich', 'Weidmann', 'Web', 'Worker', 'MiB', 'KiB', 'iframe', 'LMS',
  'Markdown', 'rastrigin', 'sphere', 'ackley', 'griewank', 'igsa', 'pso', 'firefly', 'boids', 'forces', 'orca', 'social_force', 'collision_free_speed',
  'Tordeux',
  'Gm', 'Gg', 'Gc', 'Ga', 'Gd', 'Vmax', 'max', 'r_safe', 'c_obs', 'v_pref'];

/** Each page with `?lang=zh`: what must be Chinese, and where no English may be left. */
const ZH_PAGES = [
  { page: 'index.html', ready: () => window.flockpath !== undefined, chinese: { '#play': '暂停', '#metrics-title > span[data-i18n]': '指标', '#planner-title': '规划器', '#groups-title': '群组' }, scan: 'header, .toolbar, .timeline, .panel' },
  { page: 'compare.html', ready: () => window.flockpathCompare !== undefined, chinese: { '#play': '暂停', '#table-title': '指标', '#add-pane': '添加窗格' }, scan: 'header, .toolbar, .compare-side, .pane-head' },
  { page: 'tune.html', ready: () => document.getElementById('loading').hidden, chinese: { '#tune': '调优', '#setup-title': '设置', '#status': '尚未开始。' }, scan: 'header, .panel' },
  { page: 'lab.html', ready: () => window.flockpathLab !== undefined || document.querySelector('#lab-function option') !== null, chinese: { '#lab-play': '播放', '#lab-plot-title': '收敛曲线（目前最优，对数坐标）' }, scan: 'header, .lab-toolbar' },
  { page: 'validation.html', ready: () => document.querySelector('#val-planners input') !== null, chinese: { '#val-run': '运行', '#val-table-title': '结果' }, scan: 'header, #val-run-title, fieldset legend, .row-buttons' },
  { page: 'activities.html', ready: () => window.flockpathActivities !== undefined, chinese: { '#print-guide': '打印教师指南', '#topic-flocking': '群集行为' }, scan: 'header, main' },
  { page: 'embed.html#s=open-field', ready: () => document.getElementById('embedded')?.host !== undefined && document.getElementById('embedded').host !== null, chinese: { '#open-full': '在 flockpath 中打开 ↗' }, scan: 'body' },
];

test('?lang=zh: every page speaks Chinese and leaves no English UI words in its header and panels', async () => {
  const { page, errors, close, url } = await openBrowser();
  try {
    for (const { page: name, ready, chinese, scan } of ZH_PAGES) {
      const [file, hash] = name.split('#');
      await page.goto(`${url}${file}?lang=zh${hash ? `#${hash}` : ''}`);
      await page.waitForFunction(ready, null, { timeout: 30_000 });
      assert.equal(await page.evaluate(() => document.documentElement.lang), 'zh-Hans', `${file}: <html lang>`);
      for (const [selector, text] of Object.entries(chinese)) {
        assert.equal((await page.textContent(selector)).trim(), text, `${file} ${selector}`);
      }
      const left = await englishLeftovers(page, scan);
      assert.deepEqual(left, [], `${file}: English words left in ${scan}`);
      const description = await page.evaluate(() => document.querySelector('meta[name="description"]')?.content ?? null);
      if (description !== null) assert.match(description, /[\u4e00-\u9fff]/, `${file}: the meta description in Chinese`);
      if (file !== 'embed.html') {
        assert.equal(await page.inputValue('#lang-select'), 'zh', `${file}: the language menu shows zh`);
      }
    }
    // The element on the embed page words its own controls in Chinese too.
    assert.equal(await page.evaluate(() => document.getElementById('embedded').shadowRoot.querySelector('.reset').textContent), '重置');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('a browser whose language is zh-CN gets Chinese without ?lang; ?lang=en still wins', async () => {
  const { page, errors, close, url } = await openBrowser({ locale: 'zh-CN' });
  try {
    assert.equal(await page.evaluate(() => navigator.language), 'zh-CN');
    await page.goto(`${url}index.html`);
    await page.waitForFunction(() => window.flockpath !== undefined);
    assert.equal((await page.textContent('#planner-title')).trim(), '规划器');
    assert.equal((await page.textContent('#step')).trim(), '单步');
    await page.goto(`${url}index.html?lang=en`);
    await page.waitForFunction(() => window.flockpath !== undefined);
    assert.equal((await page.textContent('#planner-title')).trim(), 'Planner');
    assert.equal(await page.evaluate(() => document.documentElement.lang), 'en');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('switching language in the menu keeps the scene and the run, and is remembered', async () => {
  const { page, errors, close, url } = await openBrowser();
  try {
    await page.goto(`${url}index.html`);
    await page.waitForFunction(() => window.flockpath !== undefined);
    await page.evaluate((scene) => window.flockpath.load(scene), simpleScene({ seed: 7 }));
    await page.evaluate(async () => {
      await window.flockpath.pause();
      await window.flockpath.step(40);
    });
    const before = await page.evaluate(async () => (await window.flockpath.settled(), ({ scene: window.flockpath.sceneString(), digest: window.flockpath.digest(), steps: window.flockpath.metrics().steps })));
    assert.equal((await page.textContent('#play')).trim(), 'Play');
    assert.ok((await englishLeftovers(page, 'header, .toolbar, .timeline, .panel')).length > 50, 'the scan sees English words');
    await page.waitForFunction((s) => location.hash.includes(s.slice(0, 20)), before.scene);

    await page.selectOption('#lang-select', 'zh');
    // The Chinese table is fetched on the first switch (an English page does not download it).
    await page.waitForFunction(() => document.documentElement.lang === 'zh-Hans');
    assert.equal((await page.textContent('#play')).trim(), '播放', 'the paused Play button in Chinese');
    assert.equal((await page.textContent('#planner-title')).trim(), '规划器');
    assert.equal(await page.evaluate(() => document.documentElement.lang), 'zh-Hans');
    // Generated controls follow: the parameter labels, the metric names, the planner menu.
    assert.equal(await page.evaluate(() => document.querySelector('#params .param label').textContent), '感知半径');
    assert.equal(await page.evaluate(() => document.querySelector('#metrics dt').textContent), '步数');
    assert.equal(await page.evaluate(() => document.querySelector('#planner option[value="firefly"]').textContent), '萤火虫算法人群（Zhang 等 2017）');
    const after = await page.evaluate(async () => (await window.flockpath.settled(), ({ scene: window.flockpath.sceneString(), digest: window.flockpath.digest(), steps: window.flockpath.metrics().steps })));
    assert.deepEqual(after, before, 'same scene, same state, same step');
    const location = await page.evaluate(() => ({ search: location.search, hash: location.hash }));
    assert.equal(location.search, '?lang=zh');
    assert.ok(location.hash.includes(before.scene), 'the scene stays in the fragment');
    assert.deepEqual(await englishLeftovers(page, 'header, .toolbar, .timeline, .panel'), [], 'no English left after the switch');
    // The inspector words the core's explanation (state, forces) in Chinese too.
    await page.evaluate(() => window.flockpath.inspect(0));
    await page.waitForSelector('#inspector:not([hidden])');
    assert.equal(await page.textContent('#inspector-facts dt'), '速度');
    assert.match(await page.textContent('#inspector-facts dd:nth-of-type(2)'), /[\u4e00-\u9fff]/, 'the state in Chinese');
    assert.deepEqual(await englishLeftovers(page, '#inspector'), [], 'no English in the inspector');

    // Remembered: another page opened without ?lang speaks Chinese.
    await page.goto(`${url}compare.html`);
    await page.waitForFunction(() => window.flockpathCompare !== undefined);
    assert.equal((await page.textContent('#add-pane')).trim(), '添加窗格');
    await page.selectOption('#lang-select', 'en');
    await page.waitForFunction(() => document.documentElement.lang === 'en');
    assert.equal((await page.textContent('#add-pane')).trim(), 'Add pane');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('refused input is worded in Chinese: a field out of range, an unknown scene version, a preset name', async () => {
  const { page, errors, close, url } = await openBrowser();
  try {
    await page.goto(`${url}index.html?lang=zh#s=9.abcdef`);
    await page.waitForFunction(() => window.flockpath !== undefined);
    const banner = () => page.textContent('#banner-text');
    assert.match(await banner(), /^无法加载链接中的场景：无法读取场景：未知的场景格式版本“9”；此 flockpath 能读取的版本为 1 和 2。改为显示默认场景“立柱”。$/);

    // The group editor's Radius field: 500 px is over the limit.
    await page.fill('#group-editor input[name="agent_radius"]', '500');
    await page.$eval('#group-editor input[name="agent_radius"]', (input) => input.dispatchEvent(new Event('change')));
    await page.waitForFunction(() => !document.getElementById('banner').hidden && document.getElementById('banner-text').textContent.includes('agent_radius'));
    assert.equal(await banner(), 'groups[0].agent_radius 的值为 500；允许：0.5…100 像素 之间的数');

    // A parameter through the page API keeps the English message on the Error for scripts, and the
    // banner words it in Chinese.
    const thrown = await page.evaluate(async () => {
      try {
        await window.flockpath.load('no-such-preset');
        return null;
      } catch (error) {
        return { message: error.message, code: error.code };
      }
    });
    assert.equal(thrown.code, 'scene.unknown_preset');
    assert.match(thrown.message, /^unknown preset 'no-such-preset'/);
    assert.match(await banner(), /^未知的预设场景“no-such-preset”（可用的有：pillars, /);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('in Chinese: a per-group compare pane’s label, a refused comparison and polygon, the web app manifest, a tune worker’s refusal', async () => {
  const { page, errors, close, url } = await openBrowser();
  try {
    // Two groups, each with its own planner in pane B: the label names both in Chinese.
    const scene = simpleScene();
    scene.groups.push({ ...scene.groups[0], name: '右侧', spawn: { min: [500, 100], max: [560, 160] } });
    await page.goto(`${url}compare.html?lang=zh#s=${encodeURIComponent(JSON.stringify(scene))}&c=1.scene~1=pso;2=boids`);
    await page.waitForFunction(() => window.flockpathCompare !== undefined);
    const label = await page.textContent('.pane[data-pane="B"] .pane-label');
    assert.match(label, /^flock：PSO 粒子群人群；右侧：类鸟群/, `pane B's label: ${label}`);
    assert.deepEqual(await englishLeftovers(page, '.pane-head'), [], 'no English in the pane heads');
    // A refused comparison in the link: the banner words the compare spec's refusal in Chinese.
    await page.goto('about:blank');
    await page.goto(`${url}compare.html?lang=zh#s=open-field&c=1.scene~zz`);
    await page.waitForFunction(() => window.flockpathCompare !== undefined && !document.getElementById('banner').hidden);
    assert.match(await page.textContent('#banner-text'), /比较：未知的规划器“zz”；可用的有：scene, boids/);
    const manifest = await page.evaluate(async () => {
      const link = document.querySelector('link[rel="manifest"]');
      return link ? { href: link.getAttribute('href'), json: await (await fetch(link.href)).json() } : null;
    });
    if (manifest) {
      assert.equal(manifest.href, 'manifest.zh.webmanifest');
      assert.match(manifest.json.description, /[\u4e00-\u9fff]/);
    }
    await page.goto(`${url}index.html?lang=zh`);
    await page.waitForFunction(() => window.flockpath !== undefined);
    const play = await page.evaluate(async () => {
      const link = document.querySelector('link[rel="manifest"]');
      return { href: link.getAttribute('href'), json: await (await fetch(link.href)).json() };
    });
    assert.equal(play.href, 'manifest.zh.webmanifest', 'the playground links the Chinese manifest');
    assert.match(play.json.name, /群体规划器/);
    assert.match(await page.getAttribute('meta[name="description"]', 'content'), /[\u4e00-\u9fff]/);
    // A scene refused by the geometry checks (a polygon whose edges cross), through the page API:
    // the script gets the English message, the banner the Chinese words.
    const crossing = simpleScene({ obstacles: [{ shape: 'polygon', points: [[100, 100], [300, 300], [300, 100], [100, 300]] }] });
    const thrown = await page.evaluate(async (scene) => {
      try {
        await window.flockpath.load(scene);
        return null;
      } catch (error) {
        return error.message;
      }
    }, crossing);
    assert.match(thrown, /^obstacles\[0\]\.points is a polygon whose edges 0→1 and 2→3 cross or touch; allowed: a simple polygon/);
    assert.equal(await page.textContent('#banner-text'), 'obstacles[0].points 的值为 边 0→1 与 2→3 相交或接触的多边形；允许：简单多边形：边只在共同的角点相交，面积不为零');
    await page.selectOption('#lang-select', 'en');
    await page.waitForFunction(() => document.documentElement.lang === 'en');
    assert.equal(await page.getAttribute('link[rel="manifest"]', 'href'), 'manifest.webmanifest', 'English again');
    await page.selectOption('#lang-select', 'zh');
    await page.waitForFunction(() => document.documentElement.lang.startsWith('zh'));

    // The tune worker's refusal comes back with its code and is worded in the page's language.
    await page.goto(`${url}tune.html?lang=zh`);
    await page.waitForFunction(() => window.flocktune !== undefined && document.getElementById('loading').hidden);
    await page.evaluate(() => {
      document.getElementById('frames').value = '0';
      window.flocktune.start();
    });
    await page.waitForFunction(() => window.flocktune.state().error !== null, null, { timeout: 30_000 });
    assert.match(await page.textContent('#banner-text'), /^帧数 0 超出 1…\d+ 的范围$/);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
