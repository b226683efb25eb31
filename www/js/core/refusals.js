// Refusals in the reader's language. The core refuses with an English message and, beside it, a
// stable `code` and `args` (src/model/refusal.rs: a field's path, the refused value, what is
// allowed, a limit, known names). English pages show the core's message as it is; other
// languages word it with the table's `error.<code>` template. Messages the core words alone
// (`parse`, `blocked`, `too_costly`, …: one `message` argument) are matched against the few
// patterns below (unknown scene version, the density and planning limits, a missing item, …); any
// other keeps the core's English words. Errors of the other pages come coded by where they arose
// (`compare`, `lab`, `tune`, `validation`, `export`, `theme`, `play`: src/web/mod.rs `worded`) with the
// core's words as `message`, matched against that code's patterns here the same way.

import { en, language, t, tOr } from './i18n.js';

/** [regex over the core's English message, table key]: named groups become the key's args. */
const PATTERNS = [
  [/^unknown scene format version "(?<version>[^"]*)"; this flockpath reads versions (?<readable>.+)$/, 'error.unknown_version'],
  [/^the scene string has no version prefix \(expected "(?<expected>[^"]+)"\)$/, 'error.no_version'],
  [/^the scene string is not valid base64 \((?<reason>.*)\); was it cut short\?$/, 'error.bad_base64'],
  [/^the scene string is damaged or truncated: was it cut short when copied\?$/, 'error.damaged'],
  [/^the scene string does not hold text$/, 'error.not_text'],
  [/^the scene text is empty$/, 'error.empty'],
  [/^the scene text ends too early \((?<at>[^)]*)\): was it cut short\?$/, 'error.cut_short'],
  [/^the scene text is not valid JSON: (?<reason>.*)$/, 'error.not_json'],
  [/^the text is not a scene object \((?<reason>.*)\)$/, 'error.not_scene'],
  [/^group (?<group>\d+) \((?<name>[^)]*)\): (?<count>\d+) agents of radius (?<radius>[\d.]+) px do not fit in its spawn region \((?<w>[\d.]+)×(?<h>[\d.]+) px\): it holds at most (?<max>\d+) apart from each other, the obstacles and the other groups \(the density limit\)$/, 'error.density'],
  [/^group (?<group>\d+) \((?<name>[^)]*)\): igsa path planning of all groups would check (?<checks>\d+) path segments .* over the limit of (?<limit>\d+): lower the population or the iterations$/, 'error.planning_cost'],
  [/^goals\[(?<goal>\d+)\] at \((?<x>[^,]+), (?<y>[^)]+)\) is inside obstacles\[(?<obstacle>\d+)\]; a goal must lie outside every obstacle$/, 'error.goal_in_obstacle'],
  [/^there is no (?<item>\w+) (?<n>\d+)$/, 'error.no_such_item'],
  [/^group (?<group>\d+) uses (?<planner>.+); path following is part of Boids steering$/, 'error.path_needs_boids'],
  [/^(?<given>\d+) start positions for (?<total>\d+) agents$/, 'error.start_positions'],
  [/^unexpected text after the end of the scene \(line (?<line>\d+), column (?<column>\d+)\)$/, 'error.trailing_text'],
  [/^the scene string does not hold a version 2 scene \((?<reason>.*)\)$/, 'error.not_v2_scene'],
  [/^the activity is not valid: (?<reason>.*)$/, 'error.bad_activity'],
  [/^the spec is (?<bytes>\d+) bytes, over the (?<limit>\d+)-byte limit$/, 'error.spec_too_large'],
  [/^the spec is empty$/, 'error.spec_empty'],
  [/^the spec has no version prefix \(expected "(?<expected>[^"]+)"\)$/, 'error.spec_no_version'],
  [/^unknown spec version "(?<version>[^"]*)"; this flockpath reads version (?<readable>\S+)$/, 'error.spec_version'],
  [/^(?<n>\d+) panes; at most (?<max>\d+)$/, 'error.spec_panes'],
  [/^(?<n>\d+) panes; a comparison has 1 to (?<max>\d+)$/, 'error.spec_panes'],
  [/^there is no pane (?<n>\w+)$/, 'error.no_pane'],
  [/^the pane sets group (?<group>\d+) but the scene has (?<count>\d+) group\(s\)$/, 'error.pane_group_missing'],
  [/^(?<text>".*") is not a group number \(groups count from 1\)$/, 'error.pane_not_group'],
  [/^groups count from 1, not 0$/, 'error.pane_group_zero'],
  [/^a pane is empty \(write `scene` for the scene's own planners\)$/, 'error.pane_empty'],
  [/^a pane sets the planner for every group twice$/, 'error.pane_all_twice'],
  [/^a pane sets group (?<group>\d+) twice$/, 'error.pane_group_twice'],
  [/^(?<text>".*"): the parameter list has no closing `\)`$/, 'error.pane_no_paren'],
  [/^(?<planner>\w+) takes (?<n>\d+) parameters, the pane gives (?<given>\d+)$/, 'error.pane_param_count'],
  [/^(?<label>.+) \((?<planner>\w+)\) must be a number, not (?<value>".*")$/, 'error.pane_param_number'],
  [/^(?<label>.+) \((?<planner>\w+)\) = (?<value>\S+) is outside (?<min>[-\d.e]+)…(?<max>[-\d.e]+) ?(?<unit>.*)$/, 'error.pane_param_range'],
  [/^(?<label>.+) \((?<planner>\w+)\) is not a finite number$/, 'error.pane_param_finite'],
  [/^(?<label>.+) \((?<planner>\w+)\) must be one of \[(?<choices>.*)\], not (?<value>".*")$/, 'error.pane_param_choice'],
  [/^this pane runs the scene's own planners: pick a planner for it first$/, 'error.pane_scene_param'],
  [/^the value for (?<key>".*") is not JSON: (?<reason>.*)$/, 'error.value_not_json'],
  [/^the waypoints are not a list of \[x, y\] points: (?<reason>.*)$/, 'error.waypoints_not_list'],
  [/^group (?<group>\d+) does not follow a planned path \(its planner is not igsa\)$/, 'error.not_igsa'],
  [/^unknown planner "(?<name>[^"]*)"; known: (?<known>.+)$/, 'error.unknown_planner'],
  [/^unknown algorithm "(?<name>[^"]*)"; known: (?<known>.+)$/, 'error.unknown_algorithm'],
  [/^unknown function "(?<name>[^"]*)"; known: (?<known>.+)$/, 'error.unknown_function'],
  [/^dimension (?<value>\d+) is outside 1…(?<max>\d+)$/, 'error.lab_dimension'],
  [/^iterations (?<value>\d+) is outside 1…(?<max>\d+)$/, 'error.lab_iterations'],
  [/^cannot read the tuning settings: (?<reason>.*)$/, 'error.tune_settings'],
  [/^unknown behaviour "(?<name>[^"]*)"; known: (?<known>.+)$/, 'error.unknown_behaviour'],
  [/^unknown environment "(?<name>[^"]*)"; known: (?<known>.+)$/, 'error.unknown_environment'],
  [/^frames (?<value>\d+) is outside 1…(?<max>\d+)$/, 'error.tune_frames'],
  [/^generations (?<value>\d+) is outside 1…(?<max>\d+)$/, 'error.tune_generations'],
  [/^population (?<value>\d+) is outside 2…(?<max>\d+)$/, 'error.tune_population'],
  [/^crossover and mutation rates must be in 0…1$/, 'error.tune_rates'],
  [/^the scene has no agents to tune$/, 'error.tune_no_agents'],
  [/^the run evaluated nothing$/, 'error.tune_nothing'],
  [/^unknown test "(?<name>[^"]*)"$/, 'error.unknown_test'],
  [/^(?<planner>.+) has no speed parameter to set$/, 'error.no_speed_param'],
  [/^unknown planner "(?<name>[^"]*)"$/, 'error.unknown_planner_bare'],
  [/^unknown reference curve "(?<name>[^"]*)"; known: (?<known>.+)$/, 'error.unknown_curve'],
  [/^the frame rate must be 1…240 fps, not (?<value>.+)$/, 'error.export_fps'],
  [/^the scale must be a number > 0, not (?<value>.+)$/, 'error.export_scale'],
  [/^unknown theme "(?<name>[^"]*)"; known: (?<known>.+)$/, 'error.unknown_theme'],
];

/** Codes of errors worded by the core alone, with the frame each puts around the matched words. */
const WORDED = { compare: 'error.compare', lab: null, tune: null, validation: null, export: null, theme: null, play: null };

/** What a field allows, in the reader's language: [regex over the core's words, table key]. */
const ALLOWED = [
  // Longer forms first: `a number in 0…800 px (inside the world's width)` is not a plain range.
  [/^a number in (?<min>[-−\d.e]+)…(?<max>[-−\d.e]+) px \(inside the world's (?<side>width|height)\)$/, 'allowed.inside_side'],
  [/^a number in (?<min>[-−\d.e]+)…(?<max>[-−\d.e]+) px \(within (?<margin>[\d.]+) px of the world\)$/, 'allowed.near_side'],
  [/^a number in (?<min>[\d.e]+)…(?<max>[\d.e]+) px per metre \(default (?<default>[\d.]+)\)$/, 'allowed.px_per_metre'],
  [/^a number inside the world \(0…width, 0…height px\)(?<tail>, .+)?$/, 'allowed.inside'],
  [/^a number within (?<margin>[\d.]+) px of the world \(−[\d.]+…width\/height \+ [\d.]+ px\)(?<tail>, .+)?$/, 'allowed.near'],
  [/^a number; the whole circle inside the world$/, 'allowed.circle_inside'],
  [/^a number of at least 1 step$/, 'allowed.one_step'],
  [/^a list of at most (?<max>\d+) (?<items>obstacles|paths|hills)$/, 'allowed.list_at_most'],
  [/^(?<min>\d+)…(?<max>\d+) points of a simple polygon \(edges meet only at shared corners, non-zero area\); at most (?<total>\d+) polygon points in all$/, 'allowed.polygon_points'],
  [/^(?<min>\d+)…(?<max>\d+) points, each (?<each>.+)$/, 'allowed.points_each'],
  [/^inside the world$/, 'allowed.inside_world'],
  [/^a simple polygon: edges meet only at shared corners, non-zero area$/, 'allowed.simple_polygon'],
  [/^at most (?<max>\d+) polygon points over all polygons$/, 'allowed.polygon_total'],
  [/^at most (?<max>\d+) agents over all groups$/, 'allowed.agents_total'],
  [/^at most spawn\.max\[(?<k>\d)\] \((?<v>[^)]+)\)$/, 'allowed.spawn_at_most_max'],
  [/^below max\[(?<k>\d)\] \((?<v>[^)]+)\): a rectangle needs an area$/, 'allowed.rect_below_max'],
  [/^null: the scene has no goals$/, 'allowed.goal_none'],
  [/^null or a goal index 0…(?<max>\d+) \(the scene has (?<n>\d+) goal\(s\)\)$/, 'allowed.goal_index'],
  [/^null \(wander\) or the index of one of the scene's goals, counting from 0$/, 'allowed.goal_any'],
  [/^0 \(none\): the scene has no paths$/, 'allowed.path_none'],
  [/^0 \(none\) or a path number 1…(?<max>\d+) \(the scene has (?<n>\d+) path\(s\)\)$/, 'allowed.path_number'],
  [/^0 \(none\) or the number of one of the scene's paths, counting from 1$/, 'allowed.path_any'],
  [/^(?<min>\d+)…(?<max>\d+) items$/, 'allowed.items_in'],
  [/^at most (?<max>\d+) items$/, 'allowed.items_at_most'],
  [/^at most (?<max>\d+) bytes$/, 'allowed.bytes_at_most'],
  [/^a finite number$/, 'allowed.finite_short'],
  [/^a number$/, 'allowed.number'],
  [/^a whole number ≥ 0$/, 'allowed.whole'],
  [/^text in quotes$/, 'allowed.text'],
  [/^true or false$/, 'allowed.boolean'],
  [/^a list \[…\]$/, 'allowed.list'],
  [/^a list of (?<n>\d+) numbers$/, 'allowed.list_numbers'],
  [/^an object \{…\}$/, 'allowed.object'],
  [/^a number within ±3\.4e38 \(a 32-bit float\)$/, 'allowed.f32'],
  [/^one of the keys (?<keys>.+)$/, 'allowed.keys'],
  [/^no keys here$/, 'allowed.no_keys'],
  [/^a value: this key is required$/, 'allowed.required'],
  [/^a circle \[x, y, radius\], a rectangle \[x0, y0, x1, y1\] or a polygon \[\[x, y\], …\]$/, 'allowed.compact_obstacle'],
  [/^\[x, y, radius\], \[x, y, radius, motion\] or \[x, y, radius, motion or null, "gather" \| "exit"\]$/, 'allowed.compact_goal'],
  [/^(?<choices>"[^"]+"(?:, "[^"]+")* or "[^"]+")$/, 'allowed.choices'],
  [/^a number in (?<min>[-−\d.e]+)…(?<max>[-−\d.e]+)(?: (?<unit>.+))?$/, 'allowed.number_in'],
  [/^a whole number (?<min>\d+)…(?<max>\d+)$/, 'allowed.whole_in'],
  [/^a whole number (?<min>\d+)…(?<max>\d+); all groups together at most (?<total>\d+) agents; 0 is an empty group that spawns nothing$/, 'allowed.count'],
  [/^one of (?<choices>.+)$/, 'allowed.one_of'],
  [/^a finite number \(JSON has no NaN or Infinity\)$/, 'allowed.finite'],
  [/^a number above 0 and at most (?<max>[\d.]+) px$/, 'allowed.positive_px'],
  [/^a colour "#rrggbb"$/, 'allowed.colour'],
  [/^text of at most (?<max>\d+) characters on one line$/, 'allowed.name_text'],
  [/^text in which each \\ud800…\\udbff escape is followed by a \\udc00…\\udfff one \(a surrogate pair\)$/, 'allowed.surrogate_pairs'],
  [/^text whose escapes are \\" \\\\ \\\/ \\b \\f \\n \\r \\t or \\u and 4 hex digits$/, 'allowed.json_escapes'],
  [/^text without raw control characters \(write a line break as \\n\)$/, 'allowed.no_raw_control'],
];

/** The JSON reader's words (serde) about a value of the wrong kind: [regex, table key]. */
const REASONS = [
  [/^invalid value: integer `(?<value>[^`]+)`, expected (?<type>\w+)$/, 'reason.invalid_value'],
  [/^invalid type: (?<found>.+), expected (?<type>[\w ]+)$/, 'reason.invalid_type'],
  [/^invalid length (?<n>\d+), expected (?<type>.+)$/, 'reason.invalid_length'],
  [/^invalid value: (?<found>.+), expected (?<type>.+)$/, 'reason.invalid_value_of'],
  [/^Invalid symbol (?<symbol>\d+), offset (?<offset>\d+)\.$/, 'reason.base64_symbol'],
  [/^Invalid last symbol (?<symbol>\d+), offset (?<offset>\d+)\.$/, 'reason.base64_symbol'],
  [/^Invalid input length\.?$/, 'reason.base64_length'],
  [/^unknown variant `(?<name>[^`]*)`, expected (?:one of )?(?<known>.+)$/, 'reason.unknown_variant'],
  [/^unknown field `(?<name>[^`]*)`, expected (?:one of )?(?<known>.+)$/, 'reason.unknown_field'],
  [/^unknown field `(?<name>[^`]*)`, there are no fields$/, 'reason.no_fields'],
  [/^missing field `(?<name>[^`]*)`$/, 'reason.missing_field'],
  [/^expected value$/, 'reason.expected_value'],
  [/^trailing characters$/, 'reason.trailing'],
  [/^EOF while parsing (?:a |an )?(?<what>.+)$/, 'reason.eof'],
  [/^EOF while parsing$/, 'reason.eof_bare'],
  [/^key must be a string$/, 'reason.key_string'],
  [/^expected `(?<char>[^`]+)` or `(?<other>[^`]+)`$/, 'reason.expected_either'],
  [/^expected `(?<char>[^`]+)`$/, 'reason.expected_char'],
  [/^invalid number$/, 'reason.invalid_number'],
  [/^number out of range$/, 'reason.number_range'],
];

/** serde's words for a kind of value (what it found, what it expected): [regex, table key]. */
const KINDS = [
  [/^string "(?<value>.*)"$/, 'reason.kind.string_value'],
  [/^integer `(?<value>[^`]*)`$/, 'reason.kind.integer_value'],
  [/^floating point `(?<value>[^`]*)`$/, 'reason.kind.float_value'],
  [/^boolean `(?<value>[^`]*)`$/, 'reason.kind.boolean_value'],
  [/^a string$/, 'reason.kind.string'],
  [/^a boolean$/, 'reason.kind.boolean'],
  [/^a sequence$/, 'reason.kind.sequence'],
  [/^(?:a )?map$/, 'reason.kind.map'],
  [/^unit value$/, 'reason.kind.unit'],
  [/^struct (?<name>\w+)$/, 'reason.kind.object'],
  [/^an array of length (?<n>\d+)$/, 'reason.kind.array_of'],
];

/** A JSON reader's reason in the reader's language, or its own words. */
function reasonText(text) {
  if (typeof text !== 'string') return text;
  // `… at line 1 column 17`: the position in the reader's words.
  const at = / at line (?<line>\d+) column (?<column>\d+)$/.exec(text);
  const body = at ? text.slice(0, at.index) : text;
  const worded = match(REASONS, body);
  if (worded === null) return text;
  return at ? `${worded}${t('reason.at', { ...at.groups })}` : worded;
}

/** A kind of value in serde's words (`string "x"`, `a sequence`), in the reader's language. */
function kindText(text) {
  for (const [re, key] of KINDS) {
    const m = re.exec(text);
    if (m) return t(key, { ...m.groups });
  }
  return text;
}

/** Values the core writes in words. */
const VALUES = { missing: 'value.missing', 'an unknown key': 'value.unknown_key', 'not a finite number (too large, infinite or NaN)': 'value.not_finite', refused: 'value.refused' };

/** Values the core writes in words with figures: [regex, table key]. */
const VALUE_PATTERNS = [
  [/^a list of (?<n>\d+)$/, 'value.list_of'],
  [/^(?<n>\d+) polygon points in all$/, 'value.polygon_points'],
  [/^(?<n>\d+) agents in all$/, 'value.agents_in_all'],
  [/^a polygon of (?<n>\d+) distinct point\(s\)$/, 'value.polygon_few'],
  [/^a polygon with no area \(its points lie on one line\)$/, 'value.polygon_no_area'],
  [/^a polygon whose edges (?<a>\d+→\d+) and (?<b>\d+→\d+) fold back onto each other$/, 'value.polygon_folds'],
  [/^a polygon whose edges (?<a>\d+→\d+) and (?<b>\d+→\d+) cross or touch$/, 'value.polygon_cross'],
  [/^an invalid string \(the lone surrogate (?<escape>\\u[0-9a-fA-F]{4})\)$/, 'value.lone_surrogate'],
  [/^an invalid string \(the escape (?<escape>\\.*)\)$/, 'value.bad_escape'],
  [/^an invalid string \(the control character (?<code>U\+[0-9A-F]{4,}) written as it is\)$/, 'value.raw_control'],
  [/^text of (?<n>\d+) character\(s\) \((?<start>".*?")(?<more>…?)\)$/, 'value.text_of'],
  [/^text holding the control character (?<code>U\+[0-9A-F]{4,})$/, 'value.text_control'],
];

/** A refused value in the reader's language (words through the tables; JSON values as they are). */
function valueText(value) {
  if (typeof value !== 'string') return value;
  if (VALUES[value]) return t(VALUES[value]);
  return match(VALUE_PATTERNS, value) ?? value;
}

/** The first pattern of `list` matching `text`, as `t(key, groups)`; null when none does. */
function match(list, text) {
  for (const [re, key] of list) {
    const m = re.exec(text);
    if (!m) continue;
    const groups = { ...m.groups };
    // `1 and 2`: the core's list joined in the reader's language.
    if (groups.readable) groups.readable = groups.readable.split(' and ').join(` ${t('list.and')} `);
    if (groups.reason) groups.reason = reasonText(groups.reason);
    if (groups.found) groups.found = kindText(groups.found);
    if (groups.what) groups.what = tOr(`reason.what.${groups.what}`, groups.what);
    if (groups.type) groups.type = kindText(groups.type);
    if (groups.known) groups.known = groups.known.replace(/`/g, '"');
    if (groups.item) groups.item = tOr(`item.${groups.item}`, groups.item);
    if (groups.items) groups.items = tOr(`items.${groups.items}`, groups.items);
    if (groups.side) groups.side = t(`allowed.side_${groups.side}`);
    if (groups.label) groups.label = labelText(null, groups.label);
    if (groups.planner && /\s/.test(groups.planner)) groups.planner = plannerText(groups.planner);
    if ('tail' in groups) groups.tail = groups.tail ? tailText(groups.tail) : '';
    if (groups.each) groups.each = allowedText(groups.each);
    if (groups.unit !== undefined) groups.unit = groups.unit ? tOr(`unit.${groups.unit}`, groups.unit) : '';
    if (groups.choices) groups.choices = groups.choices.replace(/ or /, ` ${t('list.or')} `);
    return t(key, groups).trim();
  }
  return null;
}

/** `allowed` in the reader's language (units through the tables), or the core's words. */
export function allowedText(text) {
  return typeof text === 'string' ? match(ALLOWED, text) ?? text : text;
}

/** The end of an allowed text (`, outside every obstacle`) in the reader's language. */
function tailText(tail) {
  const key = { ', outside every obstacle': 'allowed.tail_outside', ', at most max': 'allowed.tail_at_most_max', ', at least min': 'allowed.tail_at_least_min', ', below max': 'allowed.tail_below_max', ', above min': 'allowed.tail_above_min' }[tail];
  return key ? t(key) : tail;
}

/** A planner's label (`Boids (Reynolds 1987)`) in the reader's language. */
function plannerText(label) {
  for (const [k, v] of Object.entries(en)) {
    if (v === label && k.startsWith('planner.')) return t(k);
  }
  return label;
}

/** A parameter's label in the reader's language, found by its English label and key. */
function labelText(key, label) {
  for (const [k, v] of Object.entries(en)) {
    if (v === label && k.startsWith('param.') && !k.endsWith('.help') && (key === null || k.endsWith(`.${key}`))) return t(k);
  }
  return label;
}

/** The core's words of a refusal without a code (a validation run's "not measured: …"), or null. */
export function wordsText(text) {
  if (language() === 'en' || typeof text !== 'string') return null;
  return match(PATTERNS, text) ?? sceneWords(text);
}

/** A refused scene's words quoted by another error (`comparison: <the scene's refusal>`), or null. */
function sceneWords(text) {
  const parse = /^cannot read the scene: (?<message>.*)$/.exec(text);
  if (parse) {
    const why = match(PATTERNS, parse.groups.message);
    return why === null ? null : t('error.parse', { message: why });
  }
  const field = /^(?<path>[\w.[\]]+) is (?<value>.+); allowed: (?<allowed>.+)$/.exec(text);
  if (field) return t('error.field', { path: field.groups.path, value: valueText(field.groups.value), allowed: allowedText(field.groups.allowed) });
  return null;
}

/**
 * The refusal `error` (an Error with `code` and `args` from the core) in the page's language;
 * null for English pages and for errors without a code (their message is shown as it is).
 */
export function refusalText(error) {
  const code = error?.code;
  const args = error?.args;
  if (language() === 'en' || typeof code !== 'string' || !args || typeof args !== 'object') return null;
  const a = { ...args };
  switch (code) {
    case 'field':
      return t('error.field', { path: a.path, value: valueText(a.value), allowed: allowedText(a.allowed) });
    case 'param_range':
      return t('error.param_range', {
        label: labelText(a.key, a.label),
        key: a.key,
        value: valueText(a.value),
        allowed: allowedText(a.allowed),
      });
    case 'too_large':
      return t(a.bytes ? 'error.too_large_bytes' : 'error.too_large', { what: tOr(`what.${a.what}`, a.what), bytes: a.bytes, limit: a.limit });
    case 'param_type':
      return t('error.param_type', { label: labelText(null, a.label), problem: reasonText(a.problem) });
    case 'unreadable':
      return t('error.unreadable', { what: tOr(`what.${a.what}`, a.what), reason: reasonText(a.reason) });
    case 'unknown_preset':
    case 'unknown_planner':
    case 'flow_field_memory':
    case 'unknown_param':
    case 'not_finite':
      return t(`error.${code}`, a);
    case 'parse': {
      // The core says `cannot read the scene: <why>`; the why is matched, the frame kept.
      const why = typeof a.message === 'string' ? match(PATTERNS, a.message) : null;
      return why === null ? null : t('error.parse', { message: why });
    }
    default: {
      if (typeof a.message !== 'string') return null;
      if (Object.hasOwn(WORDED, code) && WORDED[code]) {
        // `comparison: <why>`: the why is matched (a refused scene inside it too), the frame kept.
        const why = a.message.replace(/^comparison: /, '');
        const worded = match(PATTERNS, why) ?? sceneWords(why);
        return worded === null ? null : t(WORDED[code], { message: worded });
      }
      return match(PATTERNS, a.message) ?? sceneWords(a.message);
    }
  }
}
