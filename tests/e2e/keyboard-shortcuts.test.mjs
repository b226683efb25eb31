// Shortcuts never take a focused control's keys (issue #15 item 1): on the playground Space ticks
// a focused checkbox and presses a focused button (Reset, Step) without toggling play, Enter
// presses a focused button, and a letter shortcut does nothing while a button has focus; on the
// page body and on the canvas the shortcuts work. The tool buttons are a radio group: one tab
// stop (roving tabindex), arrows move the choice and the focus, wrapping round, Home/End jump.
// The compare page and the optimizer lab follow the same rule.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPage, openPath, simpleScene } from './helpers.mjs';

const playing = (page) => page.evaluate(() => window.flockpath.isPlaying());
const steps = (page) => page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.metrics().steps));
const focused = (page) => page.evaluate(() => document.activeElement?.id || document.activeElement?.dataset.tool || document.activeElement?.tagName);

test('playground: Space and Enter act on the focused control; shortcuts on the body and the canvas', async () => {
  const { page, errors, close } = await openPage();
  try {
    await page.evaluate(async (s) => {
      await window.flockpath.pause();
      await window.flockpath.load(s);
      await window.flockpath.step(5);
    }, simpleScene());

    // A focused checkbox ticks with Space; play stays as it was.
    const before = await page.isChecked('#overlay-landscape');
    await page.focus('#overlay-landscape');
    await page.keyboard.press('Space');
    assert.equal(await page.isChecked('#overlay-landscape'), !before, 'Space ticked the focused checkbox');
    assert.equal(await playing(page), false, 'Space did not toggle play');
    // settled(): the checkbox's change reaches the worker after the key (README: reads after UI actions).
    const ticked = await page.evaluate(async () => (await window.flockpath.settled(), (await window.flockpath.overlays()).landscape));
    assert.equal(ticked, !before, 'the tick reached the page');

    // A focused Reset presses with Space (step 0), and play stays paused.
    await page.focus('#reset');
    await page.keyboard.press('Space');
    assert.equal(await steps(page), 0, 'Space pressed Reset');
    assert.equal(await playing(page), false, 'Space did not toggle play');

    // A focused Step presses with Enter and with Space: one step each.
    await page.focus('#step');
    await page.keyboard.press('Enter');
    assert.equal(await steps(page), 1, 'Enter pressed Step');
    await page.keyboard.press('Space');
    assert.equal(await steps(page), 2, 'Space pressed Step once');

    // A letter shortcut does nothing while a button has focus.
    await page.keyboard.press('r');
    assert.equal(await steps(page), 2, 'R is not a shortcut on a focused button');
    await page.keyboard.press('3');
    assert.equal(await page.getAttribute('[data-tool="rect"]', 'aria-checked'), 'false', '3 is not a shortcut there');

    // On the page body they are.
    await page.evaluate(() => document.activeElement?.blur());
    assert.equal(await focused(page), 'BODY');
    await page.keyboard.press('s');
    assert.equal(await steps(page), 3, 'S steps on the body');
    await page.keyboard.press('Space');
    assert.equal(await playing(page), true, 'Space plays on the body');
    await page.keyboard.press('Space');
    assert.equal(await playing(page), false, 'Space pauses on the body');
    // And on the canvas.
    await page.focus('#overlay-canvas');
    await page.keyboard.press('r');
    assert.equal(await steps(page), 0, 'R resets on the canvas');
    await page.keyboard.press('3');
    assert.equal(await page.getAttribute('[data-tool="rect"]', 'aria-checked'), 'true', '3 picks a tool on the canvas');
    // Ctrl shortcuts act while a button has focus (no control uses them).
    await page.keyboard.press('Shift+ArrowLeft');
    await page.keyboard.press('Enter');
    await page.keyboard.press('Shift+ArrowRight');
    await page.keyboard.press('Shift+ArrowDown');
    await page.keyboard.press('Enter');
    assert.equal((await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene()))).obstacles.length, 1, 'a rectangle by keyboard');
    await page.focus('#step');
    await page.keyboard.press('Control+z');
    assert.equal((await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene()))).obstacles.length, 0, 'Ctrl+Z undoes with a button focused');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('playground: the tool buttons are a radio group with one tab stop and arrow keys', async () => {
  const { page, errors, close } = await openPage();
  try {
    const tools = () =>
      page.$$eval('#tools [data-tool]', (buttons) =>
        buttons.map((b) => ({ tool: b.dataset.tool, role: b.getAttribute('role'), checked: b.getAttribute('aria-checked'), tab: b.tabIndex })),
      );
    assert.equal(await page.getAttribute('#tools', 'role'), 'radiogroup');
    let list = await tools();
    assert.ok(list.every((b) => b.role === 'radio'), JSON.stringify(list));
    assert.deepEqual(list.filter((b) => b.tab === 0).map((b) => b.tool), ['select'], 'only the checked tool is a tab stop');
    const names = list.map((b) => b.tool);

    await page.focus('#tools [data-tool="select"]');
    await page.keyboard.press('ArrowRight');
    list = await tools();
    assert.equal(await focused(page), names[1], 'ArrowRight moves the focus');
    assert.deepEqual(list.filter((b) => b.checked === 'true').map((b) => b.tool), [names[1]], 'and checks the tool');
    assert.deepEqual(list.filter((b) => b.tab === 0).map((b) => b.tool), [names[1]], 'and the tab stop');
    await page.keyboard.press('ArrowDown');
    assert.equal(await focused(page), names[2]);
    await page.keyboard.press('ArrowUp');
    await page.keyboard.press('ArrowLeft');
    assert.equal(await focused(page), names[0]);
    await page.keyboard.press('ArrowLeft');
    assert.equal(await focused(page), names[names.length - 1], 'ArrowLeft wraps round to the last tool');
    assert.equal(await page.getAttribute(`[data-tool="${names[names.length - 1]}"]`, 'aria-checked'), 'true');
    await page.keyboard.press('Home');
    assert.equal(await focused(page), names[0], 'Home goes to the first tool');
    await page.keyboard.press('End');
    assert.equal(await focused(page), names[names.length - 1], 'End goes to the last tool');
    await page.keyboard.press('ArrowRight');
    assert.equal(await focused(page), names[0], 'ArrowRight wraps round to the first');
    // Space on a focused tool keeps it checked (it is pressed, not play/pause).
    const wasPlaying = await playing(page);
    await page.keyboard.press('Space');
    assert.equal(await page.getAttribute(`[data-tool="${names[0]}"]`, 'aria-checked'), 'true');
    assert.equal(await playing(page), wasPlaying, 'Space on a tool does not toggle play');
    // Tab leaves the group: the next stop is not another tool.
    await page.keyboard.press('Tab');
    assert.equal(await page.evaluate(() => document.activeElement?.matches('#tools [data-tool]')), false);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('compare and lab: a focused button or checkbox keeps Space; the body gets the shortcuts', async () => {
  let opened = await openPath('compare.html', { ready: () => window.flockpathCompare !== undefined });
  try {
    const { page } = opened;
    const compare = () => page.evaluate(async () => (await window.flockpathCompare.settled(), ({ playing: window.flockpathCompare.isPlaying(), steps: window.flockpathCompare.steps()[0] })));
    await page.evaluate(async () => {
      await window.flockpathCompare.pause();
      await window.flockpathCompare.step(4);
    });
    await page.focus('#reset');
    await page.keyboard.press('Space');
    assert.deepEqual(await compare(), { playing: false, steps: 0 }, 'Space pressed Reset, play untouched');
    await page.keyboard.press('s');
    assert.equal((await compare()).steps, 0, 'S is not a shortcut on a focused button');
    await page.evaluate(() => document.activeElement?.blur());
    await page.keyboard.press('s');
    assert.equal((await compare()).steps, 1, 'S steps on the body');
    await page.keyboard.press('Space');
    assert.equal((await compare()).playing, true, 'Space plays on the body');
    assertNoUnexpectedErrors(opened.errors);
  } finally {
    await opened.close();
  }

  opened = await openPath('lab.html', { ready: () => window.flockpathLab !== undefined });
  try {
    const { page } = opened;
    const box = '#lab-compare input[type="checkbox"]';
    await page.waitForSelector(box);
    const wasPlaying = await page.evaluate(() => window.flockpathLab.isPlaying());
    const before = await page.isChecked(box);
    await page.focus(box);
    await page.keyboard.press('Space');
    assert.equal(await page.isChecked(box), !before, 'Space ticked the focused checkbox');
    assert.equal(await page.evaluate(() => window.flockpathLab.isPlaying()), wasPlaying, 'and did not toggle play');
    await page.evaluate(() => document.activeElement?.blur());
    await page.keyboard.press('Space');
    assert.equal(await page.evaluate(() => window.flockpathLab.isPlaying()), !wasPlaying, 'Space toggles play on the body');
    assertNoUnexpectedErrors(opened.errors);
  } finally {
    await opened.close();
  }
});
