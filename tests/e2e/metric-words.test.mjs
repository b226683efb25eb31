// Numbers a student can read (issue 23 §4): every metric the playground's Metrics card and the
// compare page's table show has a definition with its unit, as a hover on its name (title, and a
// description reachable with Tab) and as an entry of the "What do these numbers mean?" card, in
// the README's words; the card opens and closes from the keyboard, at a desktop and a phone size.
// The Validation page's plots have legends and axis labels with units, a flow–density plot beside
// the speed–density one, and a paragraph per test on how it is measured.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import { ROOT, WWW, assertNoUnexpectedErrors, frames, openPage, openPath, screenshot, simpleScene } from './helpers.mjs';

const strings = async (code) => (await import(path.join(WWW, 'js', 'core', 'strings', `${code}.js`))).default;
const { METRIC_KEYS } = await import(path.join(WWW, 'js', 'core', 'metric-words.js'));

/** The hover text of `key` in table `table`: what the page shows and the README repeats. */
const hover = (table, key) =>
  table['metrics.hover'].replace('{definition}', table[`metric.def.${key}`]).replace('{unit}', table[`metric.unit.${key}`]);

/** Collapses runs of white space, as Markdown does when it wraps a line. */
const flat = (text) => text.replace(/\s+/g, ' ');

test('the README lists every explained metric in the page’s English words, and Chinese has its own', async () => {
  const en = await strings('en');
  const zh = await strings('zh');
  const readme = flat(await readFile(path.join(ROOT, 'README.md'), 'utf8'));
  assert.ok(METRIC_KEYS.length >= 15, `${METRIC_KEYS.length} keys explained`);
  for (const key of ['waiting_agents', 'waiting_share', 'arrived_share']) assert.ok(METRIC_KEYS.includes(key), key);
  for (const key of METRIC_KEYS) {
    for (const part of ['def', 'unit', 'name']) {
      assert.ok(en[`metric.${part}.${key}`]?.trim(), `en metric.${part}.${key}`);
      assert.ok(zh[`metric.${part}.${key}`]?.trim(), `zh metric.${part}.${key}`);
    }
    assert.ok(readme.includes(`- \`${key}\`: ${hover(en, key)}`), `README's "Metrics keys" has ${key} as the page words it: ${hover(en, key)}`);
    assert.match(zh[`metric.def.${key}`], /[\u4e00-\u9fff]/, `zh metric.def.${key} is Chinese`);
  }
  // The redefined arrival, word for word as the issue gives it.
  assert.equal(
    en['metric.def.arrived_share'],
    "Share of agents whose centre is inside their goal's disc now (a moving goal: where it is now), or that left through an exit.",
  );
  // No tooltip sends a student to the design notes instead of explaining.
  for (const table of [en, zh]) {
    for (const [key, text] of Object.entries(table)) assert.ok(!/DESIGN §/.test(text), `${key} points at DESIGN: ${text}`);
  }
});

/**
 * Every shown metric name under `root` (a selector): its key, hover, the card entry its
 * description points at, and whether that entry lies in the page's card.
 */
async function shownTerms(page, root) {
  return page.$$eval(`${root} .metric-term`, (terms) =>
    terms
      .filter((el) => !el.hidden && el.getClientRects().length > 0)
      .map((el) => {
        const entry = document.getElementById(el.getAttribute('aria-describedby') ?? '');
        return {
          key: el.dataset.metric,
          name: el.textContent,
          title: el.title,
          tabIndex: el.tabIndex,
          entryKey: entry?.dataset.metric ?? null,
          entryText: entry?.textContent ?? '',
          inCard: Boolean(entry?.closest('.metrics-glossary')),
        };
      }),
  );
}

function checkTerms(terms, en, where) {
  assert.ok(terms.length > 0, `${where}: metric names found`);
  for (const term of terms) {
    const label = `${where} ${term.name} (${term.key})`;
    assert.ok(METRIC_KEYS.includes(term.key), `${label}: an explained key`);
    assert.equal(term.title, hover(en, term.key), `${label}: the hover is its definition and unit`);
    assert.ok(term.title.includes('Unit: ') && en[`metric.unit.${term.key}`].length > 0, `${label}: hover has a unit`);
    assert.equal(term.tabIndex, 0, `${label}: reachable with Tab`);
    assert.equal(term.entryKey, term.key, `${label}: described by its card entry`);
    assert.ok(term.inCard, `${label}: the entry is in the card`);
    assert.ok(term.entryText.includes(en[`metric.def.${term.key}`]), `${label}: card has the definition`);
    assert.ok(term.entryText.includes(en[`metric.unit.${term.key}`]), `${label}: card has the unit`);
  }
}

/** What the focused element is: `summary`, `close`, `term:<key>` or its tag. */
const focused = (page) =>
  page.evaluate(() => {
    const el = document.activeElement;
    if (!el) return null;
    if (el.matches('.metrics-glossary summary')) return 'summary';
    if (el.matches('.metrics-glossary button')) return 'close';
    if (el.matches('.metric-term')) return `term:${el.dataset.metric}`;
    return el.tagName.toLowerCase();
  });

const cardOpen = (page) => page.$eval('#metrics-title', (h) => h.closest('section').querySelector('.metrics-glossary').open);

for (const viewport of [
  { width: 1280, height: 900, name: 'desktop' },
  { width: 390, height: 844, name: 'phone' },
]) {
  test(`playground at ${viewport.width}×${viewport.height}: each metric has a definition with a unit; the card opens and closes by keyboard`, async () => {
    const en = await strings('en');
    const { page, errors, close } = await openPage({ viewport: { width: viewport.width, height: viewport.height } });
    try {
      await page.selectOption('#preset', 'two-groups-swap');
      await page.evaluate(async () => {
        await window.flockpath.pause();
        await window.flockpath.reset();
        await window.flockpath.step(120);
      });
      await frames(page, 3);
      const overall = await shownTerms(page, '#metrics');
      const perGroup = await shownTerms(page, '#metrics-groups');
      checkTerms(overall, en, 'overall');
      checkTerms(perGroup, en, 'per group');
      // Every shown value has its name explained: as many visible names as visible values, and
      // every heading of the per-group table but the group's own.
      const counts = await page.evaluate(() => ({
        values: [...document.querySelectorAll('#metrics dd')].filter((d) => !d.hidden).length,
        headings: document.querySelectorAll('#metrics-groups thead th').length,
      }));
      assert.equal(overall.length, counts.values, 'a name with a definition per value');
      assert.equal(perGroup.length, counts.headings - 1, 'a definition per column');
      for (const key of ['steps', 'agents', 'arrived_share', 'collisions_agent_agent', 'mean_speed', 'stuck_agents']) {
        assert.ok(overall.some((t) => t.key === key), `overall shows ${key}`);
      }
      for (const key of ['arrived_share', 'queue_order', 'fitness']) assert.ok(perGroup.some((t) => t.key === key), `groups show ${key}`);
      // The waiting count shows when the core reports it, and is hidden (not a dash) when not.
      const metrics = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.metrics()));
      assert.equal(overall.some((t) => t.key === 'waiting_agents'), typeof metrics.waiting_agents === 'number');

      // Keyboard: Tab from the first metric name through the names to the card's summary.
      await page.focus('#metrics .metric-term');
      await page.keyboard.press('Shift+Tab');
      const seen = [];
      for (let i = 0; i < 40 && (await focused(page)) !== 'summary'; i += 1) {
        await page.keyboard.press('Tab');
        const now = await focused(page);
        seen.push(now);
        if (now.startsWith('term:')) {
          // A name focused with Tab shows its definition (a title shows only under the mouse).
          const tip = await page.evaluate(() => {
            const el = document.getElementById('metric-tip');
            return el && !el.hidden ? { text: el.textContent, box: el.getBoundingClientRect().toJSON() } : null;
          });
          const key = now.slice(5);
          assert.ok(tip, `the focused ${key} shows its words`);
          assert.equal(tip.text, hover(en, key));
          assert.ok(tip.box.left >= 0 && tip.box.right <= viewport.width + 1, `the tip fits the width: ${JSON.stringify(tip.box)}`);
        }
      }
      assert.equal(await focused(page), 'summary', `Tab reaches the card: ${seen.join(' ')}`);
      for (const t of [...overall, ...perGroup]) assert.ok(seen.includes(`term:${t.key}`), `Tab visits ${t.key}`);
      assert.equal(await cardOpen(page), false, 'the card starts closed');
      await page.keyboard.press('Enter');
      assert.equal(await cardOpen(page), true, 'Enter opens the card');
      const entries = await page.$$eval('#metrics-title ~ * .metrics-glossary dd, .metrics-glossary dd', (dds) =>
        dds.filter((d) => d.getClientRects().length > 0).map((d) => d.dataset.metric));
      for (const t of [...overall, ...perGroup]) assert.ok(entries.includes(t.key), `the open card lists ${t.key}`);
      for (const key of ['waiting_agents', 'waiting_share']) assert.ok(entries.includes(key), `the card explains ${key}`);
      const card = await page.$('.metrics-glossary');
      await card.scrollIntoViewIfNeeded();
      const shot = await card.screenshot({ path: path.join(ROOT, 'test-artifacts', `metrics-card-${viewport.name}.png`) });
      assert.ok(shot.length > 1000);
      await screenshot(page, `metrics-card-page-${viewport.name}`);
      await page.keyboard.press('Escape');
      assert.equal(await cardOpen(page), false, 'Escape closes the card');
      assert.equal(await focused(page), 'summary', 'focus stays on the summary');
      await page.keyboard.press('Space');
      assert.equal(await cardOpen(page), true, 'Space opens it');
      await page.keyboard.press('Tab');
      assert.equal(await focused(page), 'close', 'Tab reaches the Close button');
      await page.keyboard.press('Enter');
      assert.equal(await cardOpen(page), false, 'Close closes the card');
      assert.equal(await focused(page), 'summary', 'focus goes back to the summary');
      assertNoUnexpectedErrors(errors);
    } finally {
      await close();
    }
  });
}

test('the compare page’s table explains each row with a definition and unit, and has the card', async () => {
  const en = await strings('en');
  const scene = encodeURIComponent(JSON.stringify(simpleScene()));
  const { page, errors, close } = await openPath(`compare.html#s=${scene}&c=1.scene~pso`, {
    ready: () => window.flockpathCompare !== undefined,
  });
  try {
    await page.waitForFunction(() => document.querySelectorAll('#metrics-table tbody th.metric-term').length > 5, null, { timeout: 20_000 });
    const terms = await shownTerms(page, '#metrics-table');
    checkTerms(terms, en, 'compare');
    const rows = await page.$$eval('#metrics-table tbody tr', (trs) => trs.length);
    assert.equal(terms.length, rows, 'every row is explained');
    for (const key of ['mean_time_to_goal_s', 'mean_path_length', 'mean_turn_deg', 'max_turn_deg']) {
      assert.ok(terms.some((t) => t.key === key), `compare explains ${key}`);
    }
    // A focused row name keeps its focus while the table updates.
    await page.focus('#metrics-table tbody th.metric-term');
    await page.evaluate(() => document.getElementById('step').click());
    await frames(page, 3);
    assert.equal(await page.evaluate(() => document.activeElement?.classList.contains('metric-term')), true);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('the validation page plots speed and flow against density with legends, axis labels and units, and says how each test is measured', async () => {
  const { page, errors, close } = await openPath('validation.html', { ready: () => window.flockpathValidation !== undefined, viewport: { width: 1280, height: 1000 } });
  try {
    const figures = ['speed', 'flow', 'sweep'];
    const labels = await page.evaluate((ids) =>
      ids.map((id) => ({
        id,
        y: document.getElementById(`val-${id}-y`)?.textContent ?? '',
        x: document.getElementById(`val-${id}-x`)?.textContent ?? '',
        visible: ['y', 'x'].every((a) => document.getElementById(`val-${id}-${a}`)?.getClientRects().length > 0),
      })), figures);
    const byId = Object.fromEntries(labels.map((l) => [l.id, l]));
    for (const l of labels) assert.ok(l.visible && l.x && l.y, `${l.id} has both axis labels: ${JSON.stringify(l)}`);
    assert.match(byId.speed.y, /\(m\/s\)/);
    assert.match(byId.speed.x, /\(1\/m²\)/);
    assert.match(byId.flow.y, /J_s = ρ·v \(1\/\(m·s\)\)/);
    assert.match(byId.flow.x, /\(1\/m²\)/);
    assert.match(byId.sweep.y, /\(s\)/);
    assert.match(byId.sweep.x, /\(m\/s\)/);
    // The two diagrams sit side by side at this width.
    const [speedBox, flowBox] = await Promise.all(['#val-speed-figure', '#val-flow-figure'].map((s) => page.$eval(s, (e) => e.getBoundingClientRect().toJSON())));
    assert.ok(Math.abs(speedBox.top - flowBox.top) < 2 && flowBox.left >= speedBox.right, 'flow–density beside speed–density');

    // One paragraph per test, in the docs' words (the core's TestSpec; tests/validation_words.rs).
    const module = await page.evaluate(() => import('./pkg/flockpath.js').then(async (m) => {
      await m.default();
      return JSON.parse(m.validation_options_json()).tests;
    }));
    const methods = await page.$$eval('#val-methods p', (ps) => ps.map((p) => ({ test: p.dataset.test, text: p.textContent })));
    assert.equal(methods.length, module.length);
    for (const spec of module) {
      const p = methods.find((m) => m.test === spec.id);
      assert.ok(p, spec.id);
      assert.ok(p.text.includes(spec.setup) && p.text.includes(spec.measurement) && p.text.includes(spec.criterion), `${spec.id}: ${p.text}`);
    }

    // Run T4 with Boids: both diagrams get its points and a legend entry beside Weidmann's.
    await page.evaluate(() => {
      for (const input of document.querySelectorAll('#val-planners input')) input.checked = input.value === 'boids';
      for (const input of document.querySelectorAll('#val-tests input')) input.checked = input.value === 't4-fundamental-diagram';
    });
    await page.click('#val-run');
    await page.waitForFunction(() => document.querySelector('#val-summary').textContent !== '', null, { timeout: 300_000 });
    for (const legend of ['#val-legend', '#val-flow-legend']) {
      const entries = await page.$$eval(`${legend} .entry`, (es) => es.map((e) => e.textContent));
      assert.deepEqual(entries, ['Weidmann (1993)', 'boids'], legend);
    }
    // The planner's colour is drawn on both canvases (its dots), besides Weidmann's black.
    const colored = await page.evaluate(() =>
      ['val-plot', 'val-flow'].map((id) => {
        const c = document.getElementById(id);
        const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
        let blue = 0;
        let black = 0;
        for (let i = 0; i < d.length; i += 4) {
          if (d[i] < 90 && d[i + 1] > 80 && d[i + 1] < 140 && d[i + 2] > 190) blue += 1;
          if (d[i] < 40 && d[i + 1] < 40 && d[i + 2] < 40) black += 1;
        }
        return { blue, black };
      }));
    for (const [i, c] of colored.entries()) assert.ok(c.blue > 40 && c.black > 100, `plot ${i}: ${JSON.stringify(c)}`);
    await page.$eval('.validation-plots', (e) => e.scrollIntoView());
    await screenshot(page, 'validation-plots');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
