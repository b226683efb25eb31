// The words inside a refused scene field that the core still sends as English text: what a field
// allows (`a number in 0.5…100 px`) and the JSON reader's reason (serde's `invalid type: …`).
// messages.js words every refusal from its code's template; it asks these tables only for those
// two text arguments, in languages other than English. They go when the core sends allowed and
// reason as coded messages too.

import { t, tOr } from './i18n.js';

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
export function reasonText(text) {
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

