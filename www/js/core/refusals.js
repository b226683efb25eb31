// Refusals in the reader's language. The core refuses with an English message and, beside it, a
// stable `code` and `args` (src/model/refusal.rs: a field's path, the refused value, what is
// allowed, a limit, known names). English pages show the core's message as it is; other
// languages word it with the table's `error.<code>` template. Messages the core words alone
// (`parse`, `blocked`, `too_costly`, …: one `message` argument) are matched against the few
// patterns below (unknown scene version, the density and cost limits, …); any other keeps the
// core's English words.

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
  [/^group (?<group>\d+) \((?<name>[^)]*)\): (?<count>\d+) (?<planner>\w+) agents would make a step take about (?<ms>\d+) ms in the browser, over the (?<limit>\d+) ms limit; at most (?<fit>\d+) \w+ agents fit beside the other groups \((?<alone>\d+) alone\)$/, 'error.step_cost'],
  [/^group (?<group>\d+) \((?<name>[^)]*)\): igsa path planning of all groups would check (?<checks>\d+) path segments .* over the limit of (?<limit>\d+): lower the population or the iterations$/, 'error.planning_cost'],
  [/^goals\[(?<goal>\d+)\] at \((?<x>[^,]+), (?<y>[^)]+)\) is inside obstacles\[(?<obstacle>\d+)\]; a goal must lie outside every obstacle$/, 'error.goal_in_obstacle'],
  [/^there is no (?<what>\w+) (?<n>\d+)$/, 'error.no_such_item'],
];

/** What a field allows, in the reader's language: [regex over the core's words, table key]. */
const ALLOWED = [
  [/^a number in (?<min>[-−\d.e]+)…(?<max>[-−\d.e]+)(?: (?<unit>.+))?$/, 'allowed.number_in'],
  [/^a whole number (?<min>\d+)…(?<max>\d+)$/, 'allowed.whole_in'],
  [/^a whole number (?<min>\d+)…(?<max>\d+); all groups together at most (?<total>\d+) agents; 0 is an empty group that spawns nothing$/, 'allowed.count'],
  [/^one of (?<choices>.+)$/, 'allowed.one_of'],
  [/^a finite number \(JSON has no NaN or Infinity\)$/, 'allowed.finite'],
  [/^a number above 0 and at most (?<max>[\d.]+) px$/, 'allowed.positive_px'],
  [/^a colour "#rrggbb"$/, 'allowed.colour'],
];

/** The JSON reader's words (serde) about a value of the wrong kind: [regex, table key]. */
const REASONS = [
  [/^invalid value: integer `(?<value>[^`]+)`, expected (?<type>\w+)$/, 'reason.invalid_value'],
  [/^invalid type: (?<found>.+), expected (?<type>[\w ]+)$/, 'reason.invalid_type'],
  [/^Invalid symbol (?<symbol>\d+), offset (?<offset>\d+)\.$/, 'reason.base64_symbol'],
  [/^Invalid last symbol (?<symbol>\d+), offset (?<offset>\d+)\.$/, 'reason.base64_symbol'],
  [/^Invalid input length\.?$/, 'reason.base64_length'],
];

/** A JSON reader's reason in the reader's language, or its own words. */
function reasonText(text) {
  return typeof text === 'string' ? match(REASONS, text) ?? text : text;
}

/** Values the core writes in words. */
const VALUES = { missing: 'value.missing', 'an unknown key': 'value.unknown_key', 'not a finite number (too large, infinite or NaN)': 'value.not_finite' };

/** The first pattern of `list` matching `text`, as `t(key, groups)`; null when none does. */
function match(list, text) {
  for (const [re, key] of list) {
    const m = re.exec(text);
    if (!m) continue;
    const groups = { ...m.groups };
    // `1 and 2`: the core's list joined in the reader's language.
    if (groups.readable) groups.readable = groups.readable.split(' and ').join(` ${t('list.and')} `);
    if (groups.reason) groups.reason = reasonText(groups.reason);
    return t(key, groups);
  }
  return null;
}

/** `allowed` in the reader's language (units through the tables), or the core's words. */
export function allowedText(text) {
  for (const [re, key] of ALLOWED) {
    const m = re.exec(text);
    if (!m) continue;
    const groups = { ...m.groups };
    if ('unit' in groups) groups.unit = groups.unit ? tOr(`unit.${groups.unit}`, groups.unit) : '';
    return t(key, groups).trim();
  }
  return text;
}

/** A parameter's label in the reader's language, found by its English label and key. */
function labelText(key, label) {
  for (const [k, v] of Object.entries(en)) {
    if (v === label && k.startsWith('param.') && !k.endsWith('.help') && (key === null || k.endsWith(`.${key}`))) return t(k);
  }
  return label;
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
      return t('error.field', { path: a.path, value: VALUES[a.value] ? t(VALUES[a.value]) : a.value, allowed: allowedText(a.allowed) });
    case 'param_range':
      return t('error.param_range', {
        label: labelText(a.key, a.label),
        key: a.key,
        value: VALUES[a.value] ? t(VALUES[a.value]) : a.value,
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
    case 'unknown_param':
    case 'not_finite':
      return t(`error.${code}`, a);
    case 'parse': {
      // The core says `cannot read the scene: <why>`; the why is matched, the frame kept.
      const why = typeof a.message === 'string' ? match(PATTERNS, a.message) : null;
      return why === null ? null : t('error.parse', { message: why });
    }
    default:
      return typeof a.message === 'string' ? match(PATTERNS, a.message) : null;
  }
}
