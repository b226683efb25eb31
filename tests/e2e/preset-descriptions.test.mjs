// Every preset in the Scene menu shows its own one-line description beside the menu, in English
// and in Chinese (issue 23 §2). Regression: the forces presets built scenes named
// `forces-b2-e1`…, so the page found no preset for them and showed the fallback
// `Scene “forces-b2-e1”` instead of saying what to watch.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { ROOT, assertNoUnexpectedErrors, openPage, openPath } from './helpers.mjs';

const STRINGS = path.join(ROOT, 'www', 'js', 'core', 'strings');
const table = async (code) => (await import(path.join(STRINGS, `${code}.js`))).default;

/** Chooses every preset of the menu in turn; returns `[[name, description shown], …]`. */
async function shownDescriptions(page) {
  const names = await page.$$eval('#preset option', (options) => options.map((o) => o.value).filter(Boolean));
  const shown = [];
  for (const name of names) {
    await page.selectOption('#preset', name);
    await page.evaluate(() => window.flockpath.pause());
    shown.push([name, await page.textContent('#preset-description')]);
  }
  return shown;
}

for (const [code, open] of [
  ['en', () => openPage({ hash: '' })],
  ['zh', () => openPath('index.html?lang=zh', { ready: () => window.flockpath !== undefined })],
]) {
  test(`${code}: every preset in the menu shows its own description, not the scene-name fallback`, async () => {
    const words = await table(code);
    const { page, errors, close } = await open();
    try {
      const shown = await shownDescriptions(page);
      assert.ok(shown.length >= 26, `${shown.length} presets in the menu`);
      for (const [name, text] of shown) {
        assert.equal(text, words[`preset.${name}.description`], `${name}: the description shown`);
      }
      const distinct = new Set(shown.map(([, text]) => text));
      assert.equal(distinct.size, shown.length, 'each preset has a description of its own');
      assertNoUnexpectedErrors(errors);
    } finally {
      await close();
    }
  });
}
