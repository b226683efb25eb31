// A validation row's "measured" text in the page's language. The suite (Rust,
// src/experiments/validation/suite.rs) writes it in English with its figures already formatted;
// other languages word it with the table's `validation.measured.*` templates, the figures kept as
// the core wrote them. A text no pattern matches is shown as the core wrote it (i18n.test.mjs
// runs the suite's tests in Chinese and fails on English words left).

import { language, t } from '../core/i18n.js';

const NUM = '[-+]?[\\d.]+';

/** A time, `12.3 s` or the core's words for none. */
function seconds(text) {
  if (text === 'not all out in 60 s') return t('validation.measured.not_all_out');
  const m = new RegExp(`^(${NUM}) s$`).exec(text);
  return m ? t('validation.measured.seconds', { t: m[1] }) : text;
}

/** A walker's time out: a time, or the core's words for nobody out. */
function firstOut(text) {
  return text === 'nobody out' ? t('validation.measured.nobody_out') : seconds(text);
}

/** A flow, `1.23/s` or `none`. */
function flow(text) {
  if (text === 'none') return t('validation.measured.flow_none');
  const m = new RegExp(`^(${NUM})/s$`).exec(text);
  return m ? t('validation.measured.flow', { f: m[1] }) : text;
}

/** [regex, key, how the named groups are worded]. */
const PATTERNS = [
  [new RegExp(`^(?<v>${NUM}) m/s \\((?<dev>${NUM})%\\): 40 m in (?<t>${NUM}) s$`), 'speed_forty'],
  [/^did not walk from 5 m to 35 m within 50 s$/, 'no_walk'],
  [new RegExp(`^mean \\|Δv\\| (?<mean>${NUM}) m/s \\(largest (?<worst>${NUM}) at (?<at>${NUM}) (?<unit>persons/m²|persons/m)\\); mean \\|ΔJ\\| (?<meanFlow>${NUM}) (?<flowUnit>persons/\\(m·s\\)|persons/s), peak J (?<peak>${NUM}) at (?<peakAt>${NUM}) (?:persons/m²|persons/m)$`), 'diagram',
    (g) => {
      const line = g.unit === 'persons/m';
      return { ...g, unit: t(line ? 'validation.measured.unit_m' : 'validation.measured.unit_m2'), flowUnit: t(line ? 'validation.measured.flow_unit_m' : 'validation.measured.flow_unit_m2') };
    }],
  [new RegExp(`^(?<out>\\d+)/20 out across the exit line \\((?:no flow|flow (?<flow>${NUM})/s)(?:; the world counted (?<world>\\d+) exits)?\\), (?<crossings>\\d+) crossed a wall$`), 'exit_line',
    (g) => ({
      out: g.out,
      crossings: g.crossings,
      flow: g.flow === undefined ? t('validation.measured.no_flow') : t('validation.measured.flow', { f: g.flow }),
      world: g.world === undefined ? '' : t('validation.measured.world_counted', { n: g.world }),
    })],
  [new RegExp(`^mean arrival (?<m0>${NUM}) s vs (?<m1>${NUM}) s turned, last (?<l0>${NUM}) s vs (?<l1>${NUM}) s: (?<rel>${NUM})%$`), 'rotation'],
  [/^arrived (?<n0>\d+)\/10, turned (?<n1>\d+)\/10 within 40 s$/, 'rotation_failed'],
  [new RegExp(`^closest gap (?<gap>\\?|${NUM} m), (?<arrived>both arrived|not both arrived in 30 s)$`), 'gap',
    (g) => ({
      gap: g.gap === '?' ? '?' : t('validation.measured.gap_m', { gap: g.gap.replace(/ m$/, '') }),
      arrived: t(g.arrived === 'both arrived' ? 'validation.measured.both_arrived' : 'validation.measured.not_both_arrived'),
    })],
  [new RegExp(`^lane order (?<end>${NUM}) over the last 10 s \\(start (?<start>${NUM})\\)$`), 'lanes'],
  [new RegExp(`^flow (?<f4>none|${NUM}/s) with 4 exits \\((?<n4>\\d+) out\\), (?<f2>none|${NUM}/s) with 2 \\((?<n2>\\d+) out\\) in (?<s>${NUM}) s: ratio (?<ratio>\\?|${NUM})$`), 'exits',
    (g) => ({ ...g, f4: flow(g.f4), f2: flow(g.f2) })],
  [new RegExp(`^flow out of the corridor (?<a>none|${NUM}/s), at the last exit (?<b>none|${NUM}/s); (?<out>\\d+)/150 out in 90 s$`), 'bottleneck',
    (g) => ({ ...g, a: flow(g.a), b: flow(g.b) })],
  [/^(?<inside>\d+)\/(?<n>\d+) walkers inside their range$/, 'range'],
  [/^evacuation at \[(?<speeds>[^\]]*)\] m\/s: (?<times>.*) s$/, 'evacuation',
    (g) => ({ speeds: g.speeds, times: g.times.split(', ').map((x) => (/^\d+ out$/.test(x) ? t('validation.measured.out', { n: x.replace(/ out$/, '') }) : x)).join(t('list.comma')) })],
  [/^first out: short (?<a>.+?) ≤ corner (?<b>.+?) ≤ long (?<c>.+?); last out: short (?<d>.+?) ≤ corner (?<e>.+?) \(long (?<f>.+)\)$/, 'corner_crowd',
    (g) => ({ a: firstOut(g.a), b: firstOut(g.b), c: firstOut(g.c), d: seconds(g.d), e: seconds(g.e), f: seconds(g.f) })],
  [/^not measured: (?<message>.*)$/, 'not_measured'],
];

/** T4's band: the properties a diagram fails, as the core names them (suite.rs `fd_properties_failed`). */
const PROPERTIES = {
  'free speed': 'validation.measured.prop_free',
  'monotone fall': 'validation.measured.prop_monotone',
  'jam below 0.2 m/s': 'validation.measured.prop_jam',
  'flow peak 1.2…2.0': 'validation.measured.prop_peak',
};

/** `text` (a row's `measured`) in the page's language. */
export function measuredText(text) {
  if (language() === 'en' || typeof text !== 'string') return text;
  const fails = /^fails (?<list>.+?); (?<rest>mean \|Δv\|.*)$/.exec(text);
  if (fails) {
    const list = fails.groups.list.split(', ').map((p) => (PROPERTIES[p] ? t(PROPERTIES[p]) : p)).join(t('list.comma'));
    return t('validation.measured.fails', { list, rest: measuredText(fails.groups.rest) });
  }
  for (const [re, key, words] of PATTERNS) {
    const m = re.exec(text);
    if (m) return t(`validation.measured.${key}`, words ? words({ ...m.groups }) : { ...m.groups });
  }
  return text;
}
