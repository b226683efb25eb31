// The activity library (issue #27 §3), in one browser: every activity's link, opened from the
// Activities page as a teacher hands it out, shows its prompt and question, takes the prediction,
// and its check decides as the teacher guide says (the status, step and values written to
// www/js/activities/measured.js by scripts/activity-links.mjs); the Chinese link carries the same
// scene in Chinese; the Activities page lists every activity, passes axe and prints the teacher
// guide one A4 page per activity; the playground prints a student handout of at most two pages
// with no buttons or sliders.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdir, writeFile } from 'node:fs/promises';
import path from 'node:path';
import { ARTIFACTS, ROOT, assertNoUnexpectedErrors, frames, launchBrowser } from './helpers.mjs';
import { ACTIVITIES } from '../../www/js/activities/library.js';
import { MEASURED } from '../../www/js/activities/measured.js';

const AXE = path.join(ROOT, 'node_modules', 'axe-core', 'axe.min.js');
const card = '#activity .fp-activity';

/** Pages of a PDF made by Chromium: its page objects (`/Type /Page`, not `/Pages`). */
const pdfPages = (pdf) => (pdf.toString('latin1').match(/\/Type\s*\/Page(?![a-z])/g) ?? []).length;

/** The activity a link of `activity` carries in language `lang`, as the library words it. */
function linkedActivity(activity, lang) {
  const w = activity[lang];
  const prediction = { question: w.question, choices: w.choices };
  if (activity.expected !== undefined) prediction.expected = activity.expected;
  return { prompt: w.prompt, prediction, check: activity.check };
}

test('every library activity runs to the verdict its teacher notes give; the page lists and prints them', { timeout: 600_000 }, async () => {
  const { page, server, errors, close } = await launchBrowser({ viewport: { width: 1366, height: 768 }, serviceWorkers: 'block' });
  const openActivities = async () => {
    await page.goto(`${server.url}activities.html`);
    await page.waitForFunction(() => window.flockpathActivities !== undefined);
  };
  try {
    assert.ok(ACTIVITIES.length >= 8, `${ACTIVITIES.length} activities`);

    // The page lists every activity once, each linking to its scene.
    await openActivities();
    const listed = await page.locator('a.activity-open').evaluateAll((links) => links.map((a) => [a.dataset.activity, a.getAttribute('href')]));
    assert.deepEqual(listed.map(([id]) => id).sort(), ACTIVITIES.map((a) => a.id).sort());
    for (const [id, href] of listed) assert.equal(href, `index.html#s=${MEASURED[id].links.en}`, id);
    for (const a of ACTIVITIES) {
      const row = await page.locator(`#activity-${a.id}`).innerText();
      assert.ok(row.includes(a.en.title) && row.includes(`${a.minutes} min`), row);
    }
    await page.addScriptTag({ path: AXE });
    const violations = await page.evaluate(async () => (await window.axe.run(document)).violations.map((v) => `${v.id} (${v.impact}): ${v.nodes.map((n) => n.target.join(' ')).join(', ')}`));
    assert.deepEqual(violations, [], 'axe finds nothing on the Activities page');
    await mkdir(ARTIFACTS, { recursive: true });
    await page.screenshot({ path: path.join(ARTIFACTS, 'activities-page.png'), fullPage: true });

    // "Print teacher guide" prints the page, whose print is the guide: one A4 page per activity.
    await page.evaluate(() => {
      window.printed = 0;
      window.print = () => (window.printed += 1);
    });
    await page.click('#print-guide');
    assert.equal(await page.evaluate(() => window.printed), 1);
    const guide = await page.pdf({ format: 'A4' });
    await writeFile(path.join(ARTIFACTS, 'teacher-guide.pdf'), guide);
    assert.equal(pdfPages(guide), ACTIVITIES.length, 'one page per activity');
    // The guide in Chinese: the same pages, in Chinese words.
    await page.goto(`${server.url}activities.html?lang=zh`);
    await page.waitForFunction(() => window.flockpathActivities !== undefined);
    assert.equal(pdfPages(await page.pdf({ format: 'A4' })), ACTIVITIES.length, 'one page per activity in Chinese too');
    assert.equal(await page.locator(`#guide-${ACTIVITIES[0].id} h3`).textContent(), ACTIVITIES[0].zh.title);
    await openActivities();

    await page.emulateMedia({ media: 'print' });
    for (const a of ACTIVITIES) {
      const text = await page.locator(`#guide-${a.id}`).innerText();
      assert.ok(text.includes(a.en.expect) && text.includes(a.en.next), `${a.id}: notes printed`);
      assert.match(text, a.check === undefined ? /$/ : new RegExp(`${MEASURED[a.id].check.status === 'met' ? 'Met' : 'Missed'}[^\\n]*${MEASURED[a.id].check.step.toLocaleString('en-US')}`), `${a.id}: the measured verdict printed`);
    }
    await page.emulateMedia({ media: null }); // back to the page's own (page.pdf prints with an emulated media)

    for (const a of ACTIVITIES) {
      const expected = MEASURED[a.id].check;
      // Opened from the Activities page, as a student would.
      await openActivities();
      await page.click(`a.activity-open[data-activity="${a.id}"]`);
      await page.waitForFunction(() => window.flockpath !== undefined);
      await page.evaluate(() => window.flockpath.ready);
      await page.locator(`${card} .fp-prompt`).waitFor();
      assert.equal(await page.locator(`${card} .fp-prompt`).textContent(), a.en.prompt, a.id);
      assert.deepEqual(await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene().activity)), linkedActivity(a, 'en'), a.id);

      // Play asks the question first; the expected answer locked in, the run goes.
      await page.click('#play');
      assert.equal(await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.metrics().steps)), 0, `${a.id}: no step before the prediction`);
      await page.getByRole('radio', { name: a.en.choices[a.expected], exact: true }).check();
      await page.click(`${card} .fp-lock`);
      assert.equal(await page.locator(`${card} .fp-predicted`).textContent(), `Your prediction: ${a.en.choices[a.expected]}`);
      // Then on through the page API, a frame of 100 steps at a time, until the check decides.
      const report = await page.evaluate(async () => {
        const fp = window.flockpath;
        await fp.pause();
        await fp.settled();
        while (fp.activityReport().status === 'running') {
          await fp.step(100);
          await fp.settled();
        }
        return fp.activityReport();
      });
      assert.deepEqual(
        { status: report.status, step: report.step, values: report.conditions.map((c) => c.measured[0]?.value ?? null) },
        expected,
        `${a.id}: the verdict the teacher guide prints`,
      );
      await frames(page, 3);
      assert.equal(await page.locator(`${card} .fp-status.fp-${expected.status}`).count(), 1, `${a.id}: the card shows ${expected.status}`);
      assert.match(await page.locator(`${card} .fp-result`).textContent(), new RegExp(`You predicted: ${a.en.choices[a.expected].replace(/[()]/g, '\\$&')}`));

      // The Chinese link: the same scene and check, in Chinese.
      const zh = await page.evaluate(async (value) => {
        const en = window.flockpath.scene();
        await window.flockpath.load(value);
        const s = window.flockpath.scene();
        return { activity: s.activity, sameScene: JSON.stringify({ ...s, activity: null, name: null }) === JSON.stringify({ ...en, activity: null, name: null }) };
      }, MEASURED[a.id].links.zh);
      assert.deepEqual(zh.activity, linkedActivity(a, 'zh'), `${a.id}: zh link`);
      assert.equal(zh.sameScene, true, `${a.id}: the zh link's scene is the en link's`);
    }

    // The student handout: the U-trap (four groups, the longest legend and table) printed at step 400.
    const trap = ACTIVITIES.find((a) => a.id === 'u-trap');
    const groups = await page.evaluate(async (value) => {
      await window.flockpath.load(value);
      await window.flockpath.step(400);
      await window.flockpath.settled();
      return window.flockpath.scene().groups.length;
    }, MEASURED[trap.id].links.en);
    await frames(page, 3);
    await page.evaluate(() => window.dispatchEvent(new Event('beforeprint')));
    const handout = await page.pdf({ format: 'A4', printBackground: true });
    await writeFile(path.join(ARTIFACTS, 'handout.pdf'), handout);
    const handoutPages = pdfPages(handout);
    assert.ok(handoutPages >= 1 && handoutPages <= 2, `handout on ${handoutPages} pages`);
    await page.evaluate(() => window.dispatchEvent(new Event('beforeprint'))); // as a browser's Print does
    await page.emulateMedia({ media: 'print' });
    await page.setViewportSize({ width: 794, height: 1123 });
    const printed = await page.evaluate(() => {
      const shown = (el) => el && getComputedStyle(el).display !== 'none' && el.getClientRects().length > 0;
      const still = document.querySelector('#stage img.flockpath-print-still');
      return {
        title: document.querySelector('#handout-head .handout-title')?.textContent,
        legend: [...document.querySelectorAll('#handout-head .handout-legend li')].map((li) => li.textContent),
        stillWidth: still?.getBoundingClientRect().width ?? 0,
        pageWidth: document.documentElement.clientWidth,
        controls: [...document.querySelectorAll('button, input, select, textarea, .toolbar')].filter(shown).map((el) => el.id || el.className || el.tagName),
        metrics: shown(document.getElementById('metrics')),
        question: shown(document.querySelector('#activity .fp-activity')),
      };
    });
    assert.equal(printed.title, trap.en.title);
    assert.equal(printed.legend.length, groups, printed.legend.join(' | '));
    assert.ok(printed.stillWidth >= printed.pageWidth * 0.95, `the canvas at full width (${printed.stillWidth} of ${printed.pageWidth} px)`);
    assert.deepEqual(printed.controls, [], 'no button, field or slider printed');
    assert.equal(printed.metrics, true);
    assert.equal(printed.question, true);
    await page.screenshot({ path: path.join(ARTIFACTS, 'handout-print.png'), fullPage: true });
    await page.emulateMedia({ media: null }); // back to the page's own (page.pdf prints with an emulated media)
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('the playground links the Activities page from its header menu, its welcome card and its Help dialog', { timeout: 60_000 }, async () => {
  const { page, server, errors, close } = await launchBrowser({ viewport: { width: 1366, height: 768 }, serviceWorkers: 'block' });
  try {
    await page.goto(`${server.url}index.html`);
    await page.waitForFunction(() => window.flockpath !== undefined);
    assert.equal(await page.locator('#topbar-menu a#to-activities').getAttribute('href'), 'activities.html');
    assert.equal(await page.locator('#welcome a#welcome-activities').getAttribute('href'), 'activities.html', 'the first-visit welcome says where the activities are');
    await page.click('#help');
    await page.locator('#help-dialog a#help-activities').waitFor();
    assert.equal(await page.locator('#help-dialog a#help-activities').getAttribute('href'), 'activities.html');
    await page.click('#help-dialog a#help-activities');
    await page.waitForFunction(() => window.flockpathActivities !== undefined);
    assert.equal(await page.locator('a.activity-open').count(), ACTIVITIES.length);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
