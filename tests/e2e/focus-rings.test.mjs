// Issue #27 §5: the header links' focus rings were the browser's 1 px default on the dark top bar.
// Every page's header links (and buttons) now show a ring at least 2 px wide whose colour, or
// its halo's, has at least 3:1 contrast with the bar behind it (WCAG 1.4.11), measured from the
// computed styles of the focused element, not eyeballed.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { openPath } from './helpers.mjs';

const PAGES = ['index.html', 'compare.html', 'lab.html', 'tune.html', 'validation.html', 'activities.html'];

/** In the page: each header link or button focused by keyboard, its ring and the bar's colour. */
function ringsOfHeader() {
  const rgb = (text) => (text.match(/[\d.]+/g) ?? []).map(Number);
  const luminance = ([r, g, b]) => {
    const lin = (c) => ((c /= 255) <= 0.03928 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4);
    return 0.2126 * lin(r) + 0.7152 * lin(g) + 0.0722 * lin(b);
  };
  const contrast = (a, b) => {
    const [hi, lo] = [luminance(a), luminance(b)].sort((x, y) => y - x);
    return (hi + 0.05) / (lo + 0.05);
  };
  const backgroundOf = (el) => {
    for (let node = el.parentElement; node; node = node.parentElement) {
      const colour = rgb(getComputedStyle(node).backgroundColor);
      if (colour.length === 3 || colour[3] > 0) return colour.slice(0, 3);
    }
    return [255, 255, 255];
  };
  const items = [...document.querySelectorAll('header a[href], header button')].filter((el) => el.offsetParent !== null);
  return items.map((el) => {
    el.focus();
    const style = getComputedStyle(el);
    const bar = backgroundOf(el);
    const ring = rgb(style.outlineColor).slice(0, 3);
    const halo = rgb(style.boxShadow).slice(0, 3);
    const width = parseFloat(style.outlineWidth);
    return {
      name: el.id || el.textContent.trim(),
      visible: el.matches(':focus-visible') && style.outlineStyle !== 'none',
      width,
      best: Math.max(contrast(ring, bar), halo.length === 3 ? contrast(halo, bar) : 0),
    };
  });
}

test('every header link and button shows a focus ring ≥ 2 px with ≥ 3:1 contrast, on every page', async () => {
  for (const path of PAGES) {
    const { page, close } = await openPath(path, { ready: () => document.readyState === 'complete' });
    try {
      await page.keyboard.press('Tab');
      const rings = await page.evaluate(ringsOfHeader);
      assert.ok(rings.length >= 1, `${path}: the header has links`);
      for (const ring of rings) {
        assert.ok(ring.visible, `${path} ${ring.name}: a visible ring on keyboard focus`);
        assert.ok(ring.width >= 2, `${path} ${ring.name}: ring ${ring.width} px`);
        assert.ok(ring.best >= 3, `${path} ${ring.name}: contrast ${ring.best.toFixed(2)}:1`);
      }
    } finally {
      await close();
    }
  }
});
