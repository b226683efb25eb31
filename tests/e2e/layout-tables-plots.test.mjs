// Tables and plots stay inside their cards: the playground's per-group table and the compare
// page's metrics table either fit or scroll inside their card (every column reachable), and the
// compare page's "Over time" plots neither overlap each other nor spill out of their card.
// At 1280×800 and 390×844.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, frames, openPage, openPath, screenshot, simpleScene } from './helpers.mjs';

const VIEWPORTS = [{ width: 1280, height: 800 }, { width: 390, height: 844 }];

/** Four groups with long names and different planners: a wide per-group table. */
function wideScene() {
  const base = simpleScene();
  const group = base.groups[0];
  const planners = ['boids', 'pso', 'firefly', 'forces'];
  return simpleScene({
    name: 'wide table',
    groups: planners.map((kind, i) => ({
      ...group,
      name: `the ${kind} group with a long name`,
      color: ['#2f6fdf', '#df4f2f', '#2f9f5f', '#9f4fdf'][i],
      count: 60,
      spawn: { min: [40, 40 + 110 * i], max: [140, 120 + 110 * i] },
      planner: { kind, params: {} },
    })),
  });
}

/**
 * Whether the table inside `selector`'s scroll box is readable to its last column: either it fits,
 * or the box scrolls horizontally and, scrolled to the end, shows the last column inside the box;
 * and the box lies inside its card. Returns the measured boxes for the message.
 */
const tableReach = (page, selector) =>
  page.evaluate((sel) => {
    const table = document.querySelector(sel);
    const scroller = table.parentElement;
    const card = table.closest('.card');
    const box = (el) => {
      const r = el.getBoundingClientRect();
      return { left: r.left, top: r.top, right: r.right, bottom: r.bottom };
    };
    const overflowX = getComputedStyle(scroller).overflowX;
    const fits = scroller.scrollWidth <= scroller.clientWidth + 1;
    scroller.scrollLeft = scroller.scrollWidth;
    const lastHeading = [...table.rows[0].cells].at(-1);
    const seen = { scroller: box(scroller), last: box(lastHeading), card: box(card) };
    scroller.scrollLeft = 0;
    return {
      fits,
      scrolls: ['auto', 'scroll'].includes(overflowX),
      lastVisible: seen.last.right <= seen.scroller.right + 1 && seen.last.left >= seen.scroller.left - 1,
      inCard: seen.scroller.left >= seen.card.left && seen.scroller.right <= seen.card.right + 0.5,
      seen,
    };
  }, selector);

function assertReachable(reach, what) {
  const detail = JSON.stringify(reach);
  assert.ok(reach.inCard, `${what} stays inside its card: ${detail}`);
  assert.ok(reach.fits || reach.scrolls, `${what} fits or scrolls: ${detail}`);
  assert.ok(reach.lastVisible, `${what}'s last column can be brought into view: ${detail}`);
}

for (const viewport of VIEWPORTS) {
  test(`at ${viewport.width}×${viewport.height} the per-group table is not clipped`, async () => {
    const { page, errors, close } = await openPage({ viewport });
    try {
      await page.evaluate(async (scene) => {
        await window.flockpath.pause();
        await window.flockpath.load(scene);
        await window.flockpath.step(400);
      }, wideScene());
      await page.waitForFunction(() => document.querySelectorAll('#metrics-groups tbody tr').length === 4);
      await frames(page, 2);
      assertReachable(await tableReach(page, '#metrics-groups'), 'the per-group table');
      await page.locator('#metrics-groups').scrollIntoViewIfNeeded();
      await screenshot(page, `layout-group-table-${viewport.width}`);
      assert.ok(await page.evaluate(() => document.scrollingElement.scrollWidth <= innerWidth), 'no horizontal page overflow');
      assertNoUnexpectedErrors(errors);
    } finally {
      await close();
    }
  });

  test(`at ${viewport.width}×${viewport.height} the compare page's plots and table stay in their cards`, async () => {
    const scene = encodeURIComponent(JSON.stringify(simpleScene()));
    const { page, errors, close } = await openPath(`compare.html#s=${scene}&c=1.scene~pso~firefly~forces`, {
      viewport,
      ready: () => window.flockpathCompare !== undefined,
    });
    try {
      assert.equal(await page.$$eval('.pane', (p) => p.length), 4);
      await page.waitForFunction(() => window.flockpathCompare.steps()[0] > 60);
      await frames(page, 2);
      const layout = await page.evaluate(() => {
        const box = (el) => {
          const r = el.getBoundingClientRect();
          return { left: r.left, top: r.top, right: r.right, bottom: r.bottom };
        };
        const card = document.getElementById('plots').closest('.card');
        return {
          card: box(card),
          canvases: [...document.querySelectorAll('#plots canvas')].map(box),
          figures: [...document.querySelectorAll('#plots figure')].map(box),
          pageWidth: document.scrollingElement.scrollWidth,
        };
      });
      assert.equal(layout.canvases.length, 5, 'five plots');
      const inside = (b, c) => b.left >= c.left - 0.5 && b.right <= c.right + 0.5 && b.top >= c.top - 0.5 && b.bottom <= c.bottom + 0.5;
      const overlap = (a, b) => a.left < b.right - 0.5 && b.left < a.right - 0.5 && a.top < b.bottom - 0.5 && b.top < a.bottom - 0.5;
      for (const [i, b] of layout.figures.entries()) {
        assert.ok(inside(b, layout.card), `plot ${i + 1} lies inside the "Over time" card: ${JSON.stringify({ b, card: layout.card })}`);
        assert.ok(inside(layout.canvases[i], b), `plot ${i + 1}'s canvas lies inside its figure`);
        assert.ok(layout.canvases[i].bottom - layout.canvases[i].top >= 40, `plot ${i + 1} is tall enough to read`);
      }
      for (let i = 0; i < layout.figures.length; i += 1) {
        for (let j = i + 1; j < layout.figures.length; j += 1) {
          assert.ok(!overlap(layout.figures[i], layout.figures[j]), `plots ${i + 1} and ${j + 1} do not overlap`);
          assert.ok(!overlap(layout.canvases[i], layout.canvases[j]), `plot canvases ${i + 1} and ${j + 1} do not overlap`);
        }
      }
      assert.ok(layout.pageWidth <= viewport.width, `no horizontal page overflow (${layout.pageWidth} px)`);
      const table = await tableReach(page, '#metrics-table');
      assertReachable(table, 'the compare metrics table');
      assert.ok(table.fits, `four panes' columns fit the card without scrolling: ${JSON.stringify(table.seen)}`);
      await page.locator('#plots').scrollIntoViewIfNeeded();
      await screenshot(page, `layout-compare-plots-${viewport.width}`);
      assertNoUnexpectedErrors(errors);
    } finally {
      await close();
    }
  });
}
