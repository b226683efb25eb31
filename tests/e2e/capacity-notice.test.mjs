// The scene check says up front when a group cannot fit its goal (issue 23 §1): a polite notice
// in the Metrics card naming the goal, about how many bodies it holds, the group and how many
// will wait outside; not an error banner, not a refusal (the scene loads and runs). In Chromium:
// the default scene shows no notice; `open-field` with its goal shrunk to 20 px shows one whose
// numbers are the core's (`capacity_notices_json`, read through the page's wasm module only to
// cross-check the words), in English and, after switching the language menu, in Chinese; the
// notice goes when an edit makes the goal large enough again.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, bannerText, frames, loadPaused, openPage, openPath, screenshot, settled } from './helpers.mjs';

/** The notice's text, or null while it is hidden. */
async function noticeText(page) {
  return page.evaluate(() => {
    const box = document.getElementById('capacity-notice');
    return box && !box.hidden ? box.textContent : null;
  });
}

test('a goal too small for its group is named in a notice that goes when the goal fits', async () => {
  const { page, errors, close } = await openPage({ hash: '' });
  try {
    const first = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene().name));
    assert.equal(first, 'pillars', 'the default scene');
    assert.equal(await noticeText(page), null, 'the default scene fits its goal: no notice');

    await page.selectOption('#preset', 'open-field');
    const openField = await page.evaluate(async () => {
      await window.flockpath.pause();
      return window.flockpath.scene();
    });
    assert.equal(openField.name, 'open-field');
    assert.equal(await noticeText(page), null, 'open-field as shipped fits its goal');
    const flock = openField.groups[0];
    assert.equal(openField.goals.length, 1);

    const small = structuredClone(openField);
    small.goals[0].radius = 20;
    await loadPaused(page, JSON.stringify(small));
    await frames(page, 2);
    const text = await noticeText(page);
    assert.ok(text, 'a notice is shown for a 20 px goal');
    // Exactly the core's words for a 20 px goal and 4 px bodies: the lattice of places holds
    // 13 (checked natively in src/sim/capacity_notice.rs), so 60 − 13 = 47 wait.
    assert.equal(flock.agent_radius ?? 4, 4);
    assert.equal(
      text,
      `Goal 1 holds about 13 bodies of radius 4 px; group “${flock.name}” has ${flock.count}: ${flock.count - 13} will wait outside.`,
    );
    assert.equal(await bannerText(page), null, 'a notice, not an error banner');
    const role = await page.getAttribute('#capacity-notice', 'role');
    assert.equal(role, 'status');
    // Not a refusal: the scene is loaded and runs.
    const loaded = await page.evaluate(async () => {
      await window.flockpath.step(30);
      return { goal: window.flockpath.scene().goals[0].radius, steps: window.flockpath.metrics().steps };
    });
    assert.deepEqual(loaded, { goal: 20, steps: 30 });
    await screenshot(page, 'capacity-notice-en');

    await page.selectOption('#lang-select', 'zh');
    await page.waitForFunction(() => document.documentElement.lang.startsWith('zh'));
    const zh = await noticeText(page);
    assert.equal(zh, `目标 1 约可容纳 13 个半径 4 px 的个体；群组“${flock.name}”有 ${flock.count} 个：${flock.count - 13} 个将在目标外等待。`);
    await screenshot(page, 'capacity-notice-zh');
    await page.selectOption('#lang-select', 'en');
    await page.waitForFunction(() => document.documentElement.lang === 'en');

    // Two groups sharing the small goal: both named with their counts, counted together.
    const shared = structuredClone(small);
    shared.groups.push({ ...structuredClone(flock), name: '', count: 10, spawn: { min: [40, 380], max: [160, 460] } });
    await loadPaused(page, JSON.stringify(shared));
    assert.equal(
      await noticeText(page),
      `Goal 1 holds about 13 bodies of radius 4 px; group “${flock.name}” (${flock.count}), group 2 (10) have ${flock.count + 10} together: ${flock.count + 10 - 13} will wait outside.`,
    );

    // Edits in the group panel: 13 agents fit exactly (no notice), a 14th waits.
    await loadPaused(page, JSON.stringify(small));
    assert.ok(await noticeText(page));
    const setCount = async (n) => {
      await page.fill('input[name="count"]', String(n));
      await page.dispatchEvent('input[name="count"]', 'change');
      await settled(page);
    };
    await setCount(13);
    assert.equal(await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene().groups[0].count)), 13, 'the edit applied');
    assert.equal(await noticeText(page), null, 'a goal that holds its group exactly: no notice');
    await setCount(14);
    assert.equal(
      await noticeText(page),
      `Goal 1 holds about 13 bodies of radius 4 px; group “${flock.name}” has 14: 1 will wait outside.`,
    );

    // A larger goal loaded again: the notice goes.
    const roomy = structuredClone(small);
    roomy.goals[0].radius = 60;
    await loadPaused(page, JSON.stringify(roomy));
    assert.equal(await noticeText(page), null, 'a goal that holds its group: no notice');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('the <flock-path> element of course notes says the same notice under its canvas', async () => {
  const ready = () => { const el = document.getElementById('pillars'); return Boolean(el?.sim) && el.steps > 0; };
  const { page, errors, close } = await openPath('examples/course-notes.html', { ready, viewport: { width: 1000, height: 900 } });
  const notice = (id) =>
    page.evaluate((id) => {
      const box = document.getElementById(id).shadowRoot.querySelector('.notice');
      return box && !box.hidden ? box.textContent : null;
    }, id);
  try {
    assert.equal(await notice('pillars'), null, 'pillars fits its goal: no notice in the element');
    // A second element whose goal holds about 13 of its 60 bodies.
    const expected = await page.evaluate(async () => {
      const scene = document.getElementById('pillars').scene();
      scene.goals[0].radius = 20;
      const el = document.createElement('flock-path');
      el.id = 'small';
      el.setAttribute('scene', JSON.stringify(scene));
      document.body.append(el);
      await el.settled();
      return { count: scene.groups[0].count };
    });
    await page.waitForFunction(() => {
      const box = document.getElementById('small')?.shadowRoot?.querySelector('.notice');
      return box && !box.hidden;
    });
    const text = await notice('small');
    assert.match(text, /^Goal 1 holds about \d+ bodies of radius \d+ px; group .+ has (\d+): (\d+) will wait outside\.$/, text);
    const [, has, wait] = text.match(/has (\d+): (\d+) will wait/);
    assert.equal(Number(has), expected.count, "the group's size");
    assert.ok(Number(wait) > 0 && Number(wait) < expected.count, text);
    // The same words as the playground's notice for the same scene (one wording, core/capacity-words.js).
    const held = Number(text.match(/about (\d+) bodies/)[1]);
    assert.equal(Number(wait), expected.count - held, text);
    await page.evaluate(() => document.getElementById('small').scrollIntoView({ block: 'end' }));
    await screenshot(page, 'capacity-notice-element');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
