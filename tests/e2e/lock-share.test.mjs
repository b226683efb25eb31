// The Share dialog's "For students" ticks: untouched, the link and snippets are what they were
// without them; ticked, the link, the iframe and the `<flock-path>` snippet carry the options,
// and the link reopens the playground with exactly those controls, locks and hidden panels.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPage, simpleScene } from './helpers.mjs';

const shown = (page, selector) => page.evaluate((s) => document.querySelector(s).getClientRects().length > 0, selector);

test('the Share dialog ticks produce a link, iframe and element that reproduce them', async () => {
  const { page, errors, close } = await openPage();
  try {
    const scene = await page.evaluate(async (s) => {
      await window.flockpath.load(s);
      return window.flockpath.sceneString();
    }, simpleScene({ name: 'shared-lock', obstacles: [{ shape: 'circle', center: [400, 250], radius: 40 }] }));
    await page.click('#share');
    await page.waitForSelector('#share-dialog[open]');
    const link = () => page.inputValue('#share-link');
    const iframe = () => page.inputValue('#share-iframe');
    const component = () => page.inputValue('#share-component');

    // No ticks changed: the snippets are the ones without classroom options.
    assert.ok((await link()).endsWith(`#s=${scene}`), await link());
    assert.match(await iframe(), new RegExp(`embed\\.html#s=${scene.replace(/[.*+?^${}()|[\]\\]/g, '\\$&')}&amp;autoplay=1"`));
    assert.match(await component(), /autoplay controls height="400px"/);

    // Tick: students get play and step only, obstacles and goals locked, metrics hidden.
    assert.equal(await shown(page, '#share-lock'), false, 'the ticks wait behind their button');
    await page.click('#share-lock-toggle');
    for (const name of ['reset', 'speed', 'planner', 'params', 'seed', 'trails', 'presets', 'undo', 'share', 'export', 'views', 'fullscreen']) {
      await page.uncheck(`input[data-classroom="controls:${name}"]`);
    }
    await page.check('input[data-classroom="lock:obstacles"]');
    await page.check('input[data-classroom="lock:goals"]');
    await page.check('input[data-classroom="hide:metrics"]');
    const options = 'controls=play,step&lock=obstacles,goals&hide=metrics';
    assert.ok((await link()).endsWith(`#s=${scene}&${options}`), await link());
    assert.ok((await iframe()).includes(`#s=${scene}&amp;autoplay=1&amp;${options.replace(/&/g, '&amp;')}"`), await iframe());
    assert.match(await component(), /<flock-path scene="[^"]+" autoplay controls="play,step" lock="obstacles,goals" hide="metrics" height="400px">/);
    assert.ok((await component()).includes(`#s=${scene}&amp;${options.replace(/&/g, '&amp;')}"`), 'the fallback link carries them too');

    // The link reproduces the ticks.
    const href = await link();
    await page.waitForLoadState('networkidle');
    await page.goto('about:blank');
    await page.goto(href);
    await page.waitForFunction(() => window.flockpath !== undefined);
    await page.evaluate(() => window.flockpath.ready);
    const classroom = await page.evaluate(() => window.flockpath.classroom());
    assert.deepEqual([classroom.controls, classroom.lock, classroom.hide], [['play', 'step'], ['obstacles', 'goals'], ['metrics']]);
    assert.equal(await shown(page, '#play'), true);
    assert.equal(await shown(page, '#step'), true);
    assert.equal(await shown(page, '#reset'), false);
    assert.equal(await shown(page, '#share'), false);
    assert.equal(await shown(page, '#metrics'), false);
    assert.equal(await shown(page, '[data-tool="circle"]'), false);
    assert.equal(await shown(page, '[data-tool="goal"]'), false);
    assert.equal(await shown(page, '[data-tool="group"]'), true);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('the ticks start from the page\'s own options', async () => {
  const { page, errors, close } = await openPage({ hash: '#s=pillars&lock=paths&hide=keys' });
  try {
    await page.evaluate(() => window.flockpath.ready);
    await page.click('#share');
    const ticks = await page.evaluate(() =>
      [...document.querySelectorAll('#share-lock input:checked')].map((b) => b.dataset.classroom).filter((n) => !n.startsWith('controls:')));
    assert.deepEqual(ticks, ['lock:paths', 'hide:keys']);
    assert.equal(await shown(page, '#share-lock'), true, 'shown at once when the page is locked');
    assert.equal(await page.getAttribute('#share-lock-toggle', 'aria-expanded'), 'true');
    assert.ok((await page.inputValue('#share-link')).endsWith('&lock=paths&hide=keys'));
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
