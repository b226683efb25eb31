// Geometry checks shared by the layout tests (playground and the other pages): boxes in CSS px,
// "on screen", controls beyond the right edge, and the phone header's Menu button.

import assert from 'node:assert/strict';

/** Box of `selector` in CSS px, or null when it is not rendered. */
export const box = (page, selector) =>
  page.evaluate((sel) => {
    const el = document.querySelector(sel);
    if (!el) return null;
    const r = el.getBoundingClientRect();
    return r.width === 0 && r.height === 0 ? null : { left: r.left, top: r.top, right: r.right, bottom: r.bottom };
  }, selector);

export const screenSize = (page) => page.evaluate(() => ({ width: innerWidth, height: innerHeight }));

export function assertOnScreen(b, screen, what) {
  assert.ok(b, `${what} is rendered`);
  const eps = 0.5;
  assert.ok(
    b.left >= -eps && b.top >= -eps && b.right <= screen.width + eps && b.bottom <= screen.height + eps,
    `${what} lies within the ${screen.width}×${screen.height} screen: ${JSON.stringify(b)}`,
  );
}

/**
 * Controls whose box reaches beyond the screen's right edge (outside scrolling boxes and closed
 * dialogs), looking into open shadow roots too (the <flock-path> element's bar).
 */
export const controlsBeyondRightEdge = (page) =>
  page.evaluate(() => {
    const out = [];
    const visit = (root) => {
      for (const el of root.querySelectorAll('button, a, input, select, textarea, output, canvas, progress, iframe')) {
        if (el.closest('dialog:not([open]), .table-scroll')) continue;
        const r = el.getBoundingClientRect();
        if (r.width === 0 && r.height === 0) continue;
        if (r.left < -0.5 || r.right > innerWidth + 0.5) out.push(`${el.tagName.toLowerCase()}#${el.id} ${r.left}…${r.right}`);
      }
      for (const host of root.querySelectorAll('*')) if (host.shadowRoot) visit(host.shadowRoot);
    };
    visit(document);
    return out;
  });

/** Opens the header menu when the header is collapsed into one; returns whether it was. */
export async function openMenuIfCollapsed(page) {
  const toggle = await box(page, '#menu-toggle');
  if (toggle === null) return false;
  assert.equal(await page.getAttribute('#menu-toggle', 'aria-expanded'), 'false');
  await page.tap('#menu-toggle');
  assert.equal(await page.getAttribute('#menu-toggle', 'aria-expanded'), 'true');
  return true;
}

/**
 * The window is `viewport`, the page needs no horizontal scrolling and every control lies within
 * the screen's width; returns the screen size.
 */
export async function assertFitsWidth(page, viewport) {
  const screen = await screenSize(page);
  assert.deepEqual(screen, viewport);
  const scrollWidth = await page.evaluate(() => document.scrollingElement.scrollWidth);
  assert.ok(scrollWidth <= screen.width, `no horizontal overflow: the page is ${scrollWidth} px wide`);
  assert.deepEqual(await controlsBeyondRightEdge(page), [], 'every control within the screen width');
  return screen;
}
