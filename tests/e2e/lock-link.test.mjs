// A teacher-locked link (`index.html#s=…&controls=…&lock=…&hide=…`): only the controls named are
// shown and their keys work, the editor cannot add, move or delete a locked obstacle or goal with
// the pointer or keys (an unlocked part still can), the page API still can, the address bar keeps
// the options, a typo is refused by name, and an old link still shows everything.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, bannerText, frames, openPage, sceneToClient, screenshot, simpleScene } from './helpers.mjs';

const OBSTACLE = { shape: 'circle', center: [400, 250], radius: 40 };
const SCENE = simpleScene({ name: 'locked', obstacles: [OBSTACLE] });

/** Whether each selector's element is visible. */
const visible = (page, selectors) =>
  page.evaluate((list) => Object.fromEntries(list.map((s) => {
    const el = document.querySelector(s);
    return [s, Boolean(el && el.getClientRects().length > 0 && getComputedStyle(el).visibility !== 'hidden')];
  })), selectors);

/** Drags with the mouse from scene point a to scene point b. */
async function drag(page, [ax, ay], [bx, by]) {
  const a = await sceneToClient(page, ax, ay);
  const b = await sceneToClient(page, bx, by);
  await page.mouse.move(a.x, a.y);
  await page.mouse.down();
  await page.mouse.move((a.x + b.x) / 2, (a.y + b.y) / 2, { steps: 4 });
  await page.mouse.move(b.x, b.y, { steps: 4 });
  await page.mouse.up();
}

/** Opens `hash` on the already open page as a fresh load (not a same-document jump). */
async function reopen(page, base, hash, { newTab = false } = {}) {
  // Leaving while a request is in flight (the manifest's icon) would report it as failed.
  await page.waitForLoadState('networkidle');
  // A new tab starts with its own session storage, where a tab keeps its lock (lock.js).
  if (newTab) await page.evaluate(() => sessionStorage.clear());
  await page.goto('about:blank');
  await page.goto(base + hash);
  await page.waitForFunction(() => window.flockpath !== undefined);
  await page.evaluate(() => window.flockpath.ready);
}

/**
 * Opens the page, loads SCENE and opens it again as a fresh load of `#s=<SCENE>` followed by
 * `options` (`&controls=…&lock=…&hide=…`); runs `body` with `{ page, server, fragment }` (the
 * scene's part of the address) and fails on any console or page error; closes the browser either way.
 */
async function withLink(options, body) {
  const { page, server, errors, close } = await openPage();
  try {
    const fragment = await page.evaluate(async (scene) => {
      await window.flockpath.load(scene);
      return window.flockpath.sceneString();
    }, SCENE);
    await reopen(page, server.url, `#s=${fragment}${options}`);
    await body({ page, server, fragment });
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
}

test('a locked link shows only its controls; locked obstacles and goals resist the pointer, not the API', () =>
  withLink('&controls=play,step,reset,planner&lock=obstacles,goals&hide=metrics,plots,timeline', async ({ page, server }) => {
    await page.evaluate(() => window.flockpath.pause());

    const classroom = await page.evaluate(() => window.flockpath.classroom());
    assert.deepEqual(classroom.controls, ['play', 'step', 'reset', 'planner']);
    assert.deepEqual(classroom.lock, ['obstacles', 'goals']);
    assert.equal(classroom.can_load, false);

    const shown = await visible(page, [
      '#play', '#step', '#reset', '#planner', '#spf', '#undo', '#share', '#export', '#seed', '#trails', '#preset',
      'nav.pages', '#params-defaults', '#metrics', '#plots', '.timeline', '#diagnose',
      '[data-tool="select"]', '[data-tool="circle"]', '[data-tool="rect"]', '[data-tool="polygon"]',
      '[data-tool="goal"]', '[data-tool="group"]', '[data-tool="path"]',
    ]);
    for (const s of ['#play', '#step', '#reset', '#planner', '#diagnose', '[data-tool="select"]', '[data-tool="group"]', '[data-tool="path"]']) {
      assert.equal(shown[s], true, `${s} is shown`);
    }
    for (const s of ['#spf', '#undo', '#share', '#export', '#seed', '#trails', '#preset', 'nav.pages', '#params-defaults',
      '#metrics', '#plots', '.timeline', '[data-tool="circle"]', '[data-tool="rect"]', '[data-tool="polygon"]', '[data-tool="goal"]']) {
      assert.equal(shown[s], false, `${s} is hidden`);
    }

    // The pointer: dragging the obstacle or the goal does nothing; keys cannot pick their tools;
    // Delete on a selected locked item does nothing.
    const before = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene()));
    await page.keyboard.press('1');
    await drag(page, OBSTACLE.center, [OBSTACLE.center[0] + 120, OBSTACLE.center[1] + 80]);
    assert.match(await page.textContent('#hint'), /Obstacles are locked/, 'the hint says why');
    await page.keyboard.press('Delete');
    await drag(page, before.goals[0].position, [600, 100]);
    await page.keyboard.press('Delete');
    for (const key of ['2', '3', '5']) await page.keyboard.press(key);
    assert.equal(await page.getAttribute('[data-tool="select"]', 'aria-checked'), 'true', 'locked tools cannot be picked by key');
    const goalPoint = await sceneToClient(page, 200, 100);
    await page.mouse.click(goalPoint.x, goalPoint.y);
    await frames(page);
    const after = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene()));
    assert.deepEqual(after.obstacles, before.obstacles, 'the locked obstacle did not move');
    assert.deepEqual(after.goals, before.goals, 'the locked goal did not move');

    // An unlocked part (a group) is still drawn with the pointer, and the address bar keeps the options.
    await page.keyboard.press('6');
    await drag(page, [100, 380], [180, 460]);
    const groups = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene().groups.length));
    assert.equal(groups, before.groups.length + 1, 'a new group was drawn');
    await page.waitForFunction(() => location.hash.startsWith(`#s=${window.flockpath.sceneString()}&`), null, { timeout: 5_000 });
    const rewritten = await page.evaluate(() => location.hash);
    assert.ok(rewritten.endsWith('&controls=play,step,reset,planner&lock=obstacles,goals&hide=metrics,plots,timeline'), rewritten);

    // The page API stays open: a script moves the obstacle and the goal.
    const moved = structuredClone(after);
    moved.obstacles[0].center = [420, 300];
    moved.goals[0].position = [650, 120];
    const loaded = await page.evaluate((scene) => window.flockpath.load(scene), moved);
    assert.deepEqual(loaded.obstacles[0].center, [420, 300]);
    assert.deepEqual(loaded.goals[0].position, [650, 120]);

    // The rewritten address reopens locked the same way.
    await reopen(page, server.url, rewritten);
    assert.deepEqual((await page.evaluate(() => window.flockpath.classroom())).lock, ['obstacles', 'goals']);
    assert.equal((await visible(page, ['[data-tool="circle"]']))['[data-tool="circle"]'], false);
    await screenshot(page, 'lock-link');
  }));

test('keys of controls not given do nothing; those given still work', () =>
  withLink('&controls=step', async ({ page, server, fragment }) => {
    await page.evaluate(() => window.flockpath.pause());
    await page.evaluate(() => document.activeElement?.blur());
    const steps = () => page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.metrics().steps));
    const start = await steps();
    await page.keyboard.press(' ');
    await page.keyboard.press('r');
    await frames(page, 4);
    assert.equal(await page.evaluate(() => window.flockpath.isPlaying()), false, 'Space does not play');
    await page.keyboard.press('s');
    await page.keyboard.press('s');
    assert.equal(await steps(), start + 2, 'S steps');
    await page.keyboard.press('r');
    assert.equal(await steps(), start + 2, 'R does not reset');

    // The Keys card lists only the shortcuts that work: S (step), the tools, Esc; not Space, R
    // or Ctrl+Z, whose controls the link does not give.
    const listed = () => page.$$eval('#keys-list > span', (spans) => spans.filter((s) => s.getClientRects().length > 0).map((s) => s.textContent.trim()));
    // Present and zoom change no scene and no run: no lock takes them.
    assert.deepEqual(await listed(), ['S step', '1–7 tools', 'Del delete', 'Esc cancel', 'P present', '+ − 0 zoom']);
    const dots = await page.$$eval('#keys-list > span', (spans) => spans.filter((s) => s.getClientRects().length > 0).map((s) => getComputedStyle(s, '::before').content));
    assert.deepEqual(dots, ['none', '" · "', '" · "', '" · "', '" · "', '" · "'], 'a dot between the shown ones only');
    // All controls again (an old link, in a new tab): every shortcut is listed.
    await reopen(page, server.url, `#s=${fragment}`, { newTab: true });
    assert.equal((await listed()).length, 9, 'every shortcut without a lock');
  }));

test('an unknown name is refused by field with the allowed names; an old link shows everything', () =>
  withLink('&lock=obstacles,walls&hide=plots', async ({ page, server, fragment }) => {
    const banner = await bannerText(page);
    assert.match(banner ?? '', /lock/);
    assert.match(banner ?? '', /"walls"/);
    assert.match(banner ?? '', /obstacles, goals, groups, paths/);
    const refused = await page.evaluate(() => window.flockpath.classroom());
    assert.deepEqual(refused.lock, [], 'the refused option locks nothing');
    assert.deepEqual(refused.hide, ['plots'], 'the other options still apply');

    await reopen(page, server.url, `#s=${fragment}`, { newTab: true });
    const open = await page.evaluate(() => window.flockpath.classroom());
    assert.equal(open.open, true);
    const selectors = ['#play', '#step', '#reset', '#spf', '#planner', '#undo', '#share', '#export', '#seed', '#trails',
      '#preset', 'nav.pages', '#metrics', '#plots', '.timeline', '#diagnose',
      ...['select', 'circle', 'rect', 'polygon', 'goal', 'group', 'path'].map((t) => `[data-tool="${t}"]`)];
    const shown = await visible(page, selectors);
    for (const s of selectors) assert.equal(shown[s], true, `${s} is shown for an old link`);
    // And the editor moves the obstacle there.
    await page.evaluate(() => window.flockpath.pause());
    await page.keyboard.press('1');
    await drag(page, OBSTACLE.center, [OBSTACLE.center[0] + 100, OBSTACLE.center[1]]);
    const center = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene().obstacles[0].center));
    assert.ok(center[0] > OBSTACLE.center[0] + 50, `the obstacle moved to ${center}`);
  }));

test('with groups locked the Groups panel is read-only and a new goal leaves the groups as they were', () =>
  withLink('&lock=groups', async ({ page }) => {
    await page.evaluate(() => window.flockpath.pause());
    const fields = await page.evaluate(() =>
      [...document.querySelectorAll('#group-editor input, #group-editor select, #group-editor button')].map((f) => f.disabled));
    assert.ok(fields.length >= 5 && fields.every(Boolean), `every group field is read-only: ${fields}`);
    assert.equal(await page.evaluate(() => document.querySelector('[data-tool="group"]').getClientRects().length), 0);

    const before = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene()));
    // The spawn region cannot be dragged; a goal can be placed, and the group keeps heading for its own.
    await page.keyboard.press('1');
    const spawn = before.groups[0].spawn;
    await drag(page, [(spawn.min[0] + spawn.max[0]) / 2, (spawn.min[1] + spawn.max[1]) / 2], [300, 100]);
    await page.keyboard.press('5');
    const click = await sceneToClient(page, 600, 420);
    await page.mouse.click(click.x, click.y);
    const after = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene()));
    assert.deepEqual(after.groups, before.groups, 'the groups are unchanged');
    assert.equal(after.goals.length, before.goals.length + 1, 'the goal was added');
    // An unlocked part still moves.
    await page.keyboard.press('1');
    await drag(page, OBSTACLE.center, [OBSTACLE.center[0], OBSTACLE.center[1] + 100]);
    const center = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene().obstacles[0].center));
    assert.ok(center[1] > OBSTACLE.center[1] + 50, `the obstacle moved to ${center}`);
  }));

// Issue #27 §4: a lock is honoured in the tab it was opened in. Deleting `&lock=…` from the address
// bar and reloading, or pasting a link without options, keeps the lock (with a message that says a
// lock keeps a class focused and is not security); the select hint on a locked page says what is
// fixed instead of "Delete removes it"; a new tab opens the unlocked link unlocked.
test('a locked tab keeps its lock for links without options, and says a lock is not security', () =>
  withLink('&lock=obstacles,goals', async ({ page, server, fragment }) => {
    const hint = () => page.textContent('#hint');
    assert.match(await hint(), /Obstacles, Goals are fixed by the teacher’s link/);
    assert.doesNotMatch(await hint(), /Delete removes it;?$/);

    // The options deleted from the address bar, then a reload.
    await reopen(page, server.url, `#s=${fragment}`);
    let classroom = await page.evaluate(() => window.flockpath.classroom());
    assert.deepEqual(classroom.lock, ['obstacles', 'goals'], 'the reload kept the lock');
    assert.match(await bannerText(page) ?? '', /keeps the lock of the teacher’s link.*not security/);
    assert.match(await page.evaluate(() => location.hash), /&lock=obstacles,goals/, 'the address bar holds the lock again');

    // A link without options pasted into the tab.
    await page.click('#banner-close');
    await page.evaluate((f) => {
      location.hash = `s=${f}`;
    }, fragment);
    await page.waitForFunction(() => /&lock=/.test(location.hash));
    classroom = await page.evaluate(() => window.flockpath.classroom());
    assert.deepEqual(classroom.lock, ['obstacles', 'goals'], 'the pasted link kept the lock');

    // A new tab opens it unlocked: the lock is not security, and the page says so where it is made.
    await reopen(page, server.url, `#s=${fragment}`, { newTab: true });
    classroom = await page.evaluate(() => window.flockpath.classroom());
    assert.deepEqual(classroom.lock, [], 'a new tab is not locked');
    assert.match(await hint(), /Delete removes it\.$/);
  }));
