// Phones and tablets (touch): the playground fits the screen's width, every header control is on
// screen (behind the Menu button on a phone, which is a real button with aria-expanded that the
// keyboard opens and Escape closes), the Share and Export dialogs are fully on screen, and the
// canvas starts within the first screen.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPage, screenshot } from './helpers.mjs';
import { assertFitsWidth, assertOnScreen, box, openMenuIfCollapsed } from './layout-helpers.mjs';

/** Header controls that must be reachable at every size. */
const HEADER_CONTROLS = ['#preset', '#help', '#new-scene', '#compare-link', '#tune-link', '#to-lab', '#share', '#export'];

/** Opens a dialog from the header (through the menu when collapsed) and checks it fits. */
async function checkDialog(page, button, dialog, screen, name) {
  await openMenuIfCollapsed(page);
  await page.tap(button);
  await page.waitForSelector(`${dialog}[open]`);
  assertOnScreen(await box(page, dialog), screen, `the ${name} dialog`);
  const inner = await page.evaluate((sel) => {
    const d = document.querySelector(sel);
    return { scroll: d.scrollWidth, client: d.clientWidth };
  }, dialog);
  assert.ok(inner.scroll <= inner.client + 1, `nothing in the ${name} dialog needs horizontal scrolling: ${JSON.stringify(inner)}`);
  await screenshot(page, `layout-${name.toLowerCase()}-${screen.width}`);
  // Its last button (Close) is on screen, so it can be closed with a tap.
  const close = `${dialog} .row-buttons.end button`;
  assertOnScreen(await box(page, close), screen, `the ${name} dialog's Close button`);
  await page.tap(close);
  await page.waitForSelector(`${dialog}:not([open])`, { state: 'attached' });
}

for (const viewport of [{ width: 390, height: 844 }, { width: 768, height: 1024 }]) {
  test(`at ${viewport.width}×${viewport.height} (touch) everything fits the screen`, async () => {
    const { page, errors, close } = await openPage({ viewport, hasTouch: true });
    try {
      const screen = await assertFitsWidth(page, viewport);

      const canvas = await box(page, '#scene-canvas');
      assert.ok(canvas.top < screen.height / 2, `the canvas starts in the upper half of the first screen (top ${canvas.top})`);
      assert.ok(canvas.bottom - canvas.top >= 200, `the canvas is a usable size (${canvas.bottom - canvas.top} px high)`);
      await screenshot(page, `layout-first-screen-${screen.width}`);

      const collapsed = await openMenuIfCollapsed(page);
      assert.equal(collapsed, screen.width < 640, 'the header collapses into a menu on a phone only');
      for (const selector of [...HEADER_CONTROLS, ...(collapsed ? ['#menu-toggle'] : [])]) {
        assertOnScreen(await box(page, selector), screen, selector);
      }
      if (collapsed) {
        await screenshot(page, `layout-menu-${screen.width}`);
        // The open menu overlays the page: the canvas has not moved.
        assert.deepEqual(await box(page, '#scene-canvas'), canvas);
        // Keyboard: Escape closes it and gives focus back to the button; Enter opens it again
        // with focus on its first item.
        await page.keyboard.press('Escape');
        assert.equal(await page.getAttribute('#menu-toggle', 'aria-expanded'), 'false');
        assert.equal(await box(page, '#share'), null, 'the closed menu hides its items');
        assert.equal(await page.evaluate(() => document.activeElement.id), 'menu-toggle');
        await page.keyboard.press('Enter');
        assert.equal(await page.getAttribute('#menu-toggle', 'aria-expanded'), 'true');
        assert.equal(await page.evaluate(() => document.activeElement.id), 'help');
        await page.keyboard.press('Escape');
      }

      await checkDialog(page, '#share', '#share-dialog', screen, 'Share');
      await checkDialog(page, '#export', '#export-dialog', screen, 'Export');
      await checkDialog(page, '#new-scene', '#new-scene-dialog', screen, 'New scene');
      assert.equal(await page.evaluate(() => document.scrollingElement.scrollWidth) <= screen.width, true);
      assertNoUnexpectedErrors(errors);
    } finally {
      await close();
    }
  });
}
