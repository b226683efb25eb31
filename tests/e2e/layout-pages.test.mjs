// The other pages on phones and tablets (touch, 390×844 and 768×1024): the optimizer lab, Tune,
// Compare, the embed view, the Activities page and the course-notes example fit the screen's width (no horizontal
// scrolling, every control — also inside <flock-path>'s shadow bar — within the width), the
// header's controls are on screen (Compare folds them behind the playground's Menu on a phone),
// and where a page is about a canvas, that canvas is wholly on the first screen and stays put
// when a message comes and goes, or (the lab's map) while its status line changes.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPath, screenshot } from './helpers.mjs';
import { assertFitsWidth, assertOnScreen, box, openMenuIfCollapsed } from './layout-helpers.mjs';

const PAGES = [
  {
    path: 'lab.html',
    ready: () => window.flockpathLab !== undefined,
    canvas: '#lab-canvas',
    header: ['#to-playground'],
    banner: true,
  },
  {
    path: 'tune.html',
    ready: () => window.flocktune !== undefined,
    canvas: '#preview-canvas',
    header: ['#playground-link'],
    banner: true,
  },
  {
    path: 'compare.html',
    ready: () => window.flockpathCompare !== undefined && document.querySelectorAll('.pane canvas').length === 2,
    canvas: '.pane:nth-child(1) canvas',
    // On tablets the two panes sit side by side, so both are on the first screen.
    tabletCanvas: '.pane:nth-child(2) canvas',
    header: ['#preset', '#copy-link', '#playground-link'],
    menu: true,
    banner: true,
  },
  {
    path: 'embed.html',
    ready: () => window.flockpathEmbed !== undefined,
    canvas: '#embedded',
    header: ['#open-full'],
  },
  {
    // The activity library: a page of tables, only the widths and the header are checked.
    path: 'activities.html',
    ready: () => window.flockpathActivities !== undefined,
    canvas: null,
    header: ['#print-guide', '#to-playground'],
  },
  {
    // A page of text with simulations in it: only the widths are checked.
    path: 'examples/course-notes.html',
    ready: () => {
      const els = [...document.querySelectorAll('flock-path')];
      return els.length === 2 && els.every((el) => el.sim && el.steps > 0);
    },
    canvas: null,
    header: [],
  },
];

for (const viewport of [{ width: 390, height: 844 }, { width: 768, height: 1024 }]) {
  for (const spec of PAGES) {
    test(`${spec.path} at ${viewport.width}×${viewport.height} (touch) fits the screen`, async () => {
      const { page, context, errors, close } = await openPath(spec.path, { ready: spec.ready, viewport, hasTouch: true });
      try {
        const screen = await assertFitsWidth(page, viewport);
        const name = spec.path.replace(/\W+/g, '-');
        await screenshot(page, `layout-pages-${name}-${screen.width}`);

        if (spec.canvas) {
          const canvas = await box(page, spec.canvas);
          assertOnScreen(canvas, screen, `${spec.canvas} (on the first screen)`);
          assert.ok(canvas.bottom - canvas.top >= 200, `${spec.canvas} is a usable size (${canvas.bottom - canvas.top} px high)`);
          if (spec.tabletCanvas && screen.width > 640) assertOnScreen(await box(page, spec.tabletCanvas), screen, spec.tabletCanvas);
        }

        if (spec.banner) {
          // A message (the page's own showMessage) floats over the page: the canvas stays put and
          // Dismiss is on screen.
          const before = await box(page, spec.canvas);
          await page.evaluate(() =>
            import(new URL('js/core/errors.js', location.href).href).then((m) =>
              m.showMessage('the scene could not be loaded: a message long enough to wrap onto a second line on a phone')));
          assert.deepEqual(await box(page, spec.canvas), before, 'the canvas with the message shown');
          assertOnScreen(await box(page, '#banner-close'), screen, 'the message\'s Dismiss button');
          await screenshot(page, `layout-pages-${name}-message-${screen.width}`);
          await page.tap('#banner-close');
          assert.equal(await box(page, '#banner'), null, 'Dismiss hides the message');
          assert.deepEqual(await box(page, spec.canvas), before, 'the canvas after Dismiss');
        }

        const collapsed = await openMenuIfCollapsed(page);
        assert.equal(collapsed, Boolean(spec.menu) && screen.width < 640, 'the header collapses into a menu on a phone only');
        for (const selector of spec.header) assertOnScreen(await box(page, selector), screen, selector);
        if (collapsed) {
          await screenshot(page, `layout-pages-${name}-menu-${screen.width}`);
          // Copy link answers in place, so the menu stays open to show "Link copied".
          await context.grantPermissions(['clipboard-read', 'clipboard-write']);
          await page.tap('#copy-link');
          await page.waitForFunction(() => document.getElementById('copy-link').textContent === 'Link copied');
          assert.equal(await page.getAttribute('#menu-toggle', 'aria-expanded'), 'true');
          await page.keyboard.press('Escape');
          assert.equal(await page.getAttribute('#menu-toggle', 'aria-expanded'), 'false');
          assert.equal(await box(page, '#playground-link'), null, 'the closed menu hides its items');
        }
        assertNoUnexpectedErrors(errors);
      } finally {
        await close();
      }
    });
  }

  test(`lab.html at ${viewport.width}×${viewport.height}: the map stays put while the status line changes`, async () => {
    const { page, errors, close } = await openPath('lab.html', { ready: PAGES[0].ready, viewport, hasTouch: true });
    try {
      const before = await box(page, '#lab-canvas');
      for (let i = 0; i < 3; i += 1) await page.tap('#lab-step');
      await page.waitForFunction(() => document.getElementById('lab-status').textContent.includes('iteration 3/'));
      assert.deepEqual(await box(page, '#lab-canvas'), before, 'after three steps');
      // The longest status the lab writes (firefly, T = 10000, a negative best, N = 500) and none.
      for (const text of ['· firefly · iteration 10000/10000 · best -1.2346e+10 · 500 particles', '']) {
        await page.evaluate((t) => (document.getElementById('lab-status').textContent = t), text);
        assert.deepEqual(await box(page, '#lab-canvas'), before, `with the status ${JSON.stringify(text)}`);
      }
      assertNoUnexpectedErrors(errors);
    } finally {
      await close();
    }
  });
}
