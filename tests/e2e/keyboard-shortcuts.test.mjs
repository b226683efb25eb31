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

// Issue #27 §4: every shortcut with every kind of control focused. Focused by keyboard, a control
// keeps its keys and no single-key shortcut acts; focused by a mouse click (a button keeps the
// focus after it is clicked, a select after a pick), the shortcuts act on every key the control
// does not use itself, so S, R and 1–7 work right after clicking Pause or picking a scene.
test('playground: every shortcut with every kind of control focused, by keyboard and by mouse', async () => {
  const { page, errors, close } = await openPage();
  try {
    const state = () =>
      page.evaluate(async () => {
        await window.flockpath.settled();
        return {
          steps: window.flockpath.metrics().steps,
          playing: window.flockpath.isPlaying(),
          tool: document.querySelector('#tools [aria-checked="true"]')?.dataset.tool,
          preset: document.getElementById('preset').value,
          obstacles: window.flockpath.scene().obstacles.length,
          presenting: document.getElementById('stage').classList.contains('presenting'),
          scale: window.flockpath.view().scale,
        };
      });
    const tool = (name) => page.evaluate((n) => document.querySelector(`#tools [data-tool="${n}"]`).click(), name);
    await page.evaluate(async (s) => {
      await window.flockpath.pause();
      await window.flockpath.load(s);
      await window.flockpath.step(5);
    }, simpleScene());
    const start = await state();
    assert.equal(start.steps, 5);

    // Focused by keyboard (Tab order, here page.focus with no pointer): no single-key shortcut acts.
    // Keys each control would take itself are left out (a select's type-ahead on letters it has).
    const kinds = [
      ['button', '#step', ['r', 's', '3', 'Delete', 'Escape', 'p', '+', '0']],
      ['checkbox', '#overlay-landscape', ['r', 's', '3', 'Delete', 'Escape', 'p', '+', '0']],
      ['tool radio', '#tools [data-tool="select"]', ['r', 's', '3', 'Delete', 'Escape', 'p', '+', '0']],
      ['slider', '#spf', ['r', 's', '3', 'Delete', 'Escape', 'Space', 'p', '+', '0']],
      ['select', '#preset', ['r', '3', '+']],
      ['number field', '#seed', ['r', 's', '3', 'Space', 'p']],
    ];
    for (const [kind, selector, keys] of kinds) {
      await page.focus(selector);
      for (const key of keys) {
        await page.keyboard.press(key);
        const now = await state();
        assert.equal(now.steps, 5, `${key} on a keyboard-focused ${kind} did not step or reset`);
        assert.equal(now.tool, 'select', `${key} on a keyboard-focused ${kind} did not pick a tool`);
        assert.equal(now.playing, false, `${key} on a keyboard-focused ${kind} did not play`);
        assert.equal(now.preset, start.preset, `${key} on a keyboard-focused ${kind} did not switch scenes`);
        assert.equal(now.presenting, false, `${key} on a keyboard-focused ${kind} did not present`);
        assert.equal(now.scale, start.scale, `${key} on a keyboard-focused ${kind} did not zoom`);
      }
    }
    await page.evaluate(() => document.activeElement?.blur());

    // Focused by a mouse click: each shortcut acts, except the keys the control uses.
    const mouse = [
      ['button', '#step', 1],
      ['checkbox', '#overlay-landscape', 0],
      ['tool radio', '#tools [data-tool="circle"]', 0],
      ['slider', '#spf', 0],
    ];
    for (const [kind, selector, stepsByClick] of mouse) {
      await tool('select');
      const before = (await state()).steps;
      await page.click(selector);
      assert.equal(await page.evaluate((sel) => document.activeElement === document.querySelector(sel), selector), true, `the click focused the ${kind}`);
      assert.equal((await state()).steps, before + stepsByClick);
      await page.keyboard.press('s');
      assert.equal((await state()).steps, before + stepsByClick + 1, `S steps after a click on the ${kind}`);
      await page.keyboard.press('3');
      assert.equal((await state()).tool, 'rect', `3 picks the rectangle after a click on the ${kind}`);
      await page.keyboard.press('Escape');
      await page.keyboard.press('r');
      assert.equal((await state()).steps, 0, `R resets after a click on the ${kind}`);
      await page.evaluate(() => window.flockpath.step(5));
    }
    // P, + and 0 act after a click too: present (Esc leaves), zoom in, fit.
    await page.click('#step');
    await page.keyboard.press('p');
    assert.equal((await state()).presenting, true, 'P presents after a click on a button');
    await page.keyboard.press('Escape');
    assert.equal((await state()).presenting, false, 'Esc leaves');
    await page.click('#step');
    await page.keyboard.press('+');
    await page.waitForFunction((s) => window.flockpath.view().scale > s * 1.4, start.scale);
    await page.keyboard.press('0');
    await page.waitForFunction((s) => window.flockpath.view().scale === s, start.scale);

    // Space and Enter stay the clicked button's own keys: Space presses Step, play stays paused.
    await page.click('#step');
    const pressed = (await state()).steps;
    await page.keyboard.press('Space');
    let now = await state();
    assert.equal(now.steps, pressed + 1, 'Space pressed the clicked Step button');
    assert.equal(now.playing, false, 'and did not toggle play');
    // The slider keeps its arrows.
    await page.click('#spf');
    const spf = await page.inputValue('#spf');
    await page.keyboard.press('ArrowLeft');
    assert.notEqual(await page.inputValue('#spf'), spf, 'ArrowLeft moved the clicked slider');

    // A scene picked from the Scene menu with the mouse (the click opens the list, the pick closes
    // it): the next S steps the new scene; before, the select's type-ahead took it and switched to
    // the first scene starting with S.
    await page.selectOption('#preset', 'pillars');
    await page.evaluate(() => document.activeElement?.blur());
    await page.click('#preset');
    await page.keyboard.press('ArrowDown');
    await page.keyboard.press('Enter');
    await page.evaluate(async () => {
      await window.flockpath.settled();
      await window.flockpath.pause();
    });
    const picked = await state();
    assert.notEqual(picked.preset, 'pillars', 'a scene was picked');
    await page.keyboard.press('s');
    now = await state();
    assert.equal(now.preset, picked.preset, 'S did not switch scenes');
    assert.equal(now.steps, picked.steps + 1, 'S stepped the picked scene');

    // A text field keeps every key even when clicked.
    await tool('select');
    await page.click('#seed');
    await page.keyboard.press('3');
    assert.match(await page.inputValue('#seed'), /3$/, 'the clicked field took the 3');
    assert.equal((await state()).tool, 'select', 'and no tool was picked');
    await page.keyboard.press('Backspace');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
