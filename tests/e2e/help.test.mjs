// Issue #27 §1: the page explains itself. A first visit shows a welcome card (what this is, three
// things to try, Help…) that "Got it" dismisses for good (a reload does not bring it back); the
// header's "?" opens Help: each planner in a paragraph with its paper, what each number means
// with its unit, the keys, sharing and embedding — in English and in Chinese.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPage, screenshot } from './helpers.mjs';

test('a first visit is welcomed once; Help explains the planners, the numbers and the keys in both languages', async () => {
  const { page, errors, close } = await openPage({ hash: '' });
  try {
    await page.waitForSelector('#welcome');
    assert.match(await page.textContent('#welcome'), /draws crowds that find their way/);
    assert.equal(await page.locator('#welcome li').count(), 3, 'three things to try');
    await screenshot(page, 'help-welcome');

    await page.click('#welcome-help');
    await page.waitForSelector('#help-dialog[open]');
    const planners = await page.evaluate(() => [...document.querySelectorAll('#help-dialog .help-planners dd')].map((dd) => dd.textContent));
    const count = await page.$$eval('#planner option', (options) => options.length);
    assert.equal(planners.length, count, 'a paragraph per planner in the menu');
    for (const text of planners) assert.ok(text.length > 80 && /\(\d{4}|paper/.test(text), `a paragraph that names its paper: ${text}`);
    const metrics = await page.$$eval('#help-dialog .help-metrics dd', (dds) => dds.map((dd) => dd.textContent));
    assert.ok(metrics.length >= 10, `${metrics.length} metrics explained`);
    for (const text of metrics) assert.match(text, /Unit: /, text);
    assert.ok(await page.locator('#help-dialog .help-keys kbd').count() >= 8, 'the keys');
    assert.match(await page.textContent('#help-dialog'), /Share… gives a link/);
    await screenshot(page, 'help-dialog');
    await page.keyboard.press('Escape');

    // "Got it": gone, and not back after a reload (the browser remembers it).
    await page.click('#welcome-close');
    assert.equal(await page.locator('#welcome').count(), 0);
    await page.reload();
    await page.waitForFunction(() => window.flockpath !== undefined);
    assert.equal(await page.locator('#welcome').count(), 0, 'welcomed once');

    // In Chinese: the same dialog in its words.
    await page.selectOption('#lang-select', 'zh');
    await page.waitForFunction(() => document.documentElement.lang.startsWith('zh'));
    await page.click('#help');
    await page.waitForSelector('#help-dialog[open]');
    const zh = await page.textContent('#help-dialog');
    assert.match(zh, /关于 flockpath/);
    assert.match(zh, /数字的含义/);
    assert.match(zh, /Reynolds/);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
