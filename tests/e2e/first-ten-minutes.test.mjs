// A teacher's first ten minutes (issue 27, "Done means"), scripted end to end in one browser as a
// teacher meets the page: the first-visit welcome, a preset from the Scene menu, Present (the
// stage fills the projector), zoom in and back, slow motion, an activity from the Activities page
// run with a prediction, a locked link made in Share… and opened by a student, and that link on a
// phone. Each step checks what the teacher sees; screenshots go to test-artifacts/.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, frames, launchBrowser, screenshot, settled } from './helpers.mjs';

const visible = (page, selector) => page.evaluate((s) => {
  const el = document.querySelector(s);
  return Boolean(el && !el.closest('[hidden]') && el.getClientRects().length > 0);
}, selector);

test('a teacher’s first ten minutes: welcome → preset → Present → zoom → slow motion → activity → locked link → phone', async () => {
  const launched = await launchBrowser({ viewport: { width: 1366, height: 768 }, serviceWorkers: 'block' });
  const { page, context, server, errors, close } = launched;
  try {
    // 1. The welcome: what this is, three things to try, where the activities are.
    await page.goto(server.url);
    await page.waitForFunction(() => window.flockpath !== undefined);
    await page.waitForSelector('#welcome');
    assert.equal(await page.locator('#welcome li').count(), 3, 'three things to try');
    assert.equal(await page.getAttribute('#welcome a#welcome-activities', 'href'), 'activities.html');
    await screenshot(page, 'ten-minutes-1-welcome');
    await page.click('#welcome-close');

    // 2. A preset from the Scene menu: its description says what to watch.
    await page.selectOption('#preset', 'pillars');
    await page.waitForFunction(() => window.flockpath.scene().name === 'pillars');
    assert.match(await page.textContent('#preset-description'), /pillar/i);
    await page.evaluate(() => window.flockpath.pause());

    // 3. Present: the stage fills the screen, with the headline in large type.
    await page.click('#present');
    await page.waitForFunction(() => document.getElementById('scene-canvas').getBoundingClientRect().width >= innerWidth * 0.95);
    const canvas = await page.evaluate(() => {
      const r = document.getElementById('scene-canvas').getBoundingClientRect();
      return (r.width * r.height) / (innerWidth * innerHeight);
    });
    assert.ok(canvas >= 0.95, `the canvas covers ${(100 * canvas).toFixed(1)} % of the screen`);
    await page.click('#present-play');
    await page.waitForFunction(() => window.flockpath.metrics().steps > 30);
    assert.match(await page.textContent('#present-arrived'), /^\d+ %$/);

    // 4. Zoom in about the centre (+), then Fit shows the whole scene again.
    const fitted = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.view().scale));
    await page.keyboard.press('+');
    await page.waitForFunction((s) => window.flockpath.view().scale > s * 1.1, fitted);
    await page.keyboard.press('0');
    await page.waitForFunction((s) => Math.abs(window.flockpath.view().scale - s) < 1e-3 * s, fitted);

    // 5. Slow motion: a quarter speed, said on the slider.
    await page.evaluate(() => {
      const spf = document.getElementById('spf');
      spf.value = '-1';
      spf.dispatchEvent(new Event('input', { bubbles: true }));
    });
    assert.match(await page.evaluate(() => document.getElementById('spf').getAttribute('aria-valuetext')), /^0\.25×$/);
    await screenshot(page, 'ten-minutes-3-present');
    await page.keyboard.press('Escape');
    await page.waitForFunction(() => document.getElementById('scene-canvas').getBoundingClientRect().width < innerWidth * 0.9);
    await page.evaluate(() => window.flockpath.pause());

    // 6. An activity from the Activities page: the question first, a prediction, a verdict.
    await page.click('#to-activities');
    await page.waitForSelector('a.activity-open');
    await page.locator('a.activity-open').first().click();
    await page.waitForFunction(() => window.flockpath !== undefined);
    const card = '#activity .fp-activity';
    await page.locator(`${card} .fp-prompt`).waitFor();
    await page.click('#play');
    assert.equal(await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.metrics().steps)), 0, 'no step before the prediction');
    await page.locator(`${card} input[type="radio"]`).first().check();
    await page.click(`${card} .fp-lock`);
    const report = await page.evaluate(async () => {
      const fp = window.flockpath;
      await fp.pause();
      while (fp.activityReport().status === 'running') {
        await fp.step(100);
        await fp.settled();
      }
      return fp.activityReport();
    });
    assert.ok(['met', 'missed'].includes(report.status), `the check decided: ${report.status}`);
    await frames(page, 3);
    assert.equal(await page.locator(`${card} .fp-status.fp-${report.status}`).count(), 1, 'the card shows the verdict');
    await screenshot(page, 'ten-minutes-6-activity');

    // 7. Share a locked link: obstacles and goals fixed, only Play and Step for the students.
    await page.click('#share');
    await page.waitForSelector('#share-dialog[open]');
    await page.click('#share-lock-toggle');
    for (const name of ['reset', 'speed', 'planner', 'params', 'seed', 'trails', 'presets', 'undo', 'share', 'export', 'views', 'fullscreen']) {
      await page.uncheck(`input[data-classroom="controls:${name}"]`);
    }
    await page.check('input[data-classroom="lock:obstacles"]');
    await page.check('input[data-classroom="lock:goals"]');
    const link = await page.inputValue('#share-link');
    assert.match(link, /&controls=play,step&lock=obstacles,goals/);
    const student = await context.newPage();
    await student.goto(link);
    await student.waitForFunction(() => window.flockpath !== undefined);
    const classroom = await student.evaluate(async () => (await window.flockpath.settled(), window.flockpath.classroom()));
    assert.deepEqual([classroom.controls, classroom.lock], [['play', 'step'], ['obstacles', 'goals']]);
    assert.equal(await visible(student, '[data-tool="circle"]'), false, 'no obstacle tool for the student');
    assert.equal(await visible(student, '#reset'), false);
    await student.close();

    // 8. The same link on a phone: it runs, fits the width, and says what is fixed.
    const phone = await context.newPage();
    await phone.setViewportSize({ width: 390, height: 844 });
    await phone.goto(link);
    await phone.waitForFunction(() => window.flockpath !== undefined);
    await settled(phone);
    const widths = await phone.evaluate(() => [document.documentElement.scrollWidth, document.documentElement.clientWidth]);
    assert.ok(widths[0] <= widths[1], `no sideways scroll on the phone: ${widths}`);
    // The activity travels with the link: Play asks the student's prediction first, then runs.
    await phone.click('#play');
    await phone.locator(`${card} input[type="radio"]`).first().check();
    await phone.click(`${card} .fp-lock`);
    await phone.waitForFunction(() => window.flockpath.metrics().steps > 10);
    await screenshot(phone, 'ten-minutes-8-phone');
    await phone.close();
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
