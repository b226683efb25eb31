// <flock-path> runs on the shell's core (issue #13): its module graph reaches core/boot.js (the
// wasm loader), core/sim-host.js (the guarded door), core/sim-proxy.js (the simulation worker's
// stand-in), core/remote-loop.js (the frame loop drawing the worker's frames, with its hidden-tab
// pause) and core/view.js (the backing-store sizing, one pixel cap), and flock-path.js keeps no
// copy of them; nothing in its module graph steps a simulation on the page's thread. In Chromium: the element renders pixels into a backing
// store of its CSS box × devicePixelRatio, the core modules load next to it, and a hidden tab
// does not step while it stays "playing".

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import { assertNoUnexpectedErrors, openPath, ROOT } from './helpers.mjs';

const JS = path.join(ROOT, 'www', 'js');
const ELEMENT = path.join(JS, 'flock-path.js');

/** The files `file` imports statically, relative ones resolved. */
async function staticImports(file) {
  const text = await readFile(file, 'utf8');
  const specs = [...text.matchAll(/^\s*import\s(?:[^'"]*?from\s*)?['"](\.[^'"]+)['"]/gm)].map((m) => m[1]);
  return specs.map((spec) => path.resolve(path.dirname(file), spec));
}

/** Every file reachable from `file` through static imports. */
async function graph(file, seen = new Set()) {
  for (const next of await staticImports(file)) {
    if (seen.has(next)) continue;
    seen.add(next);
    await graph(next, seen);
  }
  return seen;
}

test('flock-path.js imports the core modules and keeps no copy of them', async () => {
  const direct = (await staticImports(ELEMENT)).map((f) => path.relative(JS, f));
  for (const core of ['core/boot.js', 'core/sim-host.js', 'core/sim-proxy.js', 'core/remote-loop.js', 'core/view.js']) {
    assert.ok(direct.includes(core), `flock-path.js imports ${core}: ${direct.join(', ')}`);
  }
  const reached = [...(await graph(ELEMENT))].map((f) => path.relative(JS, f));
  // The simulation worker and its imports are started by core/sim-proxy.js, not imported.
  assert.ok(!reached.includes('core/sim-worker.js'), `the worker is not imported into the page: ${reached.join(', ')}`);
  assert.ok(reached.every((f) => f.startsWith('core/')), `only core/ is imported: ${reached.join(', ')}`);
  const text = await readFile(ELEMENT, 'utf8');
  // What the core does, flock-path.js no longer does itself.
  for (const [own, core] of [
    [/putImageData|Uint8ClampedArray/, 'the drawing of frames (core/remote-loop.js)'],
    [/requestAnimationFrame/, 'the frame loop (core/remote-loop.js)'],
    [/module\.Sim\(|sim\.step\(/, 'the stepping (core/sim-worker.js)'],
    [/devicePixelRatio|MAX_PIXELS|new ResizeObserver/, 'the backing-store sizing (core/view.js)'],
    [/pkg\/flockpath|module_or_path|WebAssembly\./, 'the wasm loading (core/boot.js)'],
    [/instanceof WebAssembly\.RuntimeError|isPanic/, 'the guarded call (core/sim-host.js)'],
  ]) {
    assert.doesNotMatch(text, own, `flock-path.js repeats ${core}`);
  }
});

const ready = () => {
  const els = [...document.querySelectorAll('flock-path')];
  return els.length === 2 && els.every((el) => el.sim && el.steps > 5);
};

test('the element draws through the core, sizes by it, and pauses in a hidden tab', async () => {
  const { page, errors, close } = await openPath('examples/course-notes.html', { ready, viewport: { width: 1000, height: 900 } });
  try {
    // The core's modules were loaded next to the element (relative to its own URL).
    const modules = await page.evaluate(() =>
      performance.getEntriesByType('resource').map((e) => new URL(e.name).pathname).filter((p) => p.includes('/js/')),
    );
    for (const core of ['boot', 'sim-host', 'sim-proxy', 'remote-loop', 'view']) {
      assert.ok(modules.some((p) => p.endsWith(`/js/core/${core}.js`)), `js/core/${core}.js loaded: ${modules.join(', ')}`);
    }

    // Pixels: the scene is painted (many colours, not a blank store) at CSS size × devicePixelRatio.
    const drawn = await page.evaluate(() => {
      const canvas = document.getElementById('pillars').shadowRoot.querySelector('canvas');
      const rect = canvas.getBoundingClientRect();
      const data = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
      const colours = new Set();
      for (let i = 0; i < data.length; i += 4 * 97) colours.add((data[i] << 16) | (data[i + 1] << 8) | data[i + 2]);
      return { colours: colours.size, width: canvas.width, height: canvas.height, css: [rect.width, rect.height], ratio: devicePixelRatio };
    });
    assert.ok(drawn.colours >= 3, `the canvas shows a scene: ${JSON.stringify(drawn)}`);
    assert.ok(Math.abs(drawn.width - drawn.css[0] * drawn.ratio) <= 1, `backing width follows the box: ${JSON.stringify(drawn)}`);
    assert.ok(Math.abs(drawn.height - drawn.css[1] * drawn.ratio) <= 1, `backing height follows the box: ${JSON.stringify(drawn)}`);

    // A hidden tab: the loop stops stepping (Page Visibility), the element still says it plays.
    const steps = () => page.evaluate(() => document.getElementById('swap').steps);
    await page.evaluate(() => {
      Object.defineProperty(document, 'hidden', { configurable: true, get: () => true });
      Object.defineProperty(document, 'visibilityState', { configurable: true, get: () => 'hidden' });
      document.dispatchEvent(new Event('visibilitychange'));
    });
    await page.waitForTimeout(100);
    const hiddenAt = await steps();
    await page.waitForTimeout(600);
    assert.equal(await steps(), hiddenAt, 'no step while hidden');
    assert.equal(await page.evaluate(() => document.getElementById('swap').playing), true, 'still playing');
    await page.evaluate(() => {
      delete document.hidden;
      delete document.visibilityState;
      document.dispatchEvent(new Event('visibilitychange'));
    });
    await page.waitForFunction((n) => document.getElementById('swap').steps > n + 10, hiddenAt);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

// Issue #27 §5: the element's `ready` Promise (documented in the README) resolves with the element
// once it runs — also after a refused scene attribute, when it runs the first preset and says why
// by flockpath-error — and rejects with the reason when it cannot run at all (no wasm).
test('<flock-path>.ready resolves when the element runs and rejects with the reason when it cannot', async () => {
  const ready = () => customElements.get('flock-path') !== undefined;
  const { page, context, server, errors, close } = await openPath('examples/course-notes.html', { ready });
  try {
    const outcome = await page.evaluate(async () => {
      const make = (scene) => {
        const el = document.createElement('flock-path');
        el.setAttribute('scene', scene);
        document.body.append(el);
        return el;
      };
      const good = make('pillars');
      const bad = make('no-such-preset');
      const said = new Promise((resolve) => bad.addEventListener('flockpath-error', (e) => resolve(e.detail), { once: true }));
      const resolved = await good.ready;
      await good.step(3);
      const runs = await bad.ready;
      return { same: resolved === good, steps: good.steps, badRuns: runs === bad, badScene: bad.scene().name, said: await said };
    });
    assert.equal(outcome.same, true, 'ready resolves with the element');
    assert.equal(outcome.steps, 3, 'and its methods work then');
    assert.equal(outcome.badRuns, true, 'a refused scene attribute: the element still runs');
    assert.match(outcome.said, /unknown preset 'no-such-preset'/, 'and says why');
    assertNoUnexpectedErrors(errors, [/no-such-preset/]);

    // No wasm (blocked): the element cannot run, ready rejects with the reason in its box.
    const blocked = await context.newPage();
    await blocked.route('**/*.wasm', (route) => route.abort());
    await blocked.goto(`${server.url}examples/course-notes.html`);
    const rejected = await blocked.evaluate(async () => {
      await customElements.whenDefined('flock-path');
      const el = document.querySelector('flock-path');
      try {
        await el.ready;
        return null;
      } catch (error) {
        const box = el.shadowRoot.querySelector('.message');
        return { isError: error instanceof Error, message: error.message, box: box.textContent, shown: !box.hidden };
      }
    });
    assert.ok(rejected?.isError, `ready rejects with an Error: ${JSON.stringify(rejected)}`);
    assert.ok(rejected.message.length > 10 && rejected.shown, JSON.stringify(rejected));
    assert.equal(rejected.message, rejected.box, 'the reason the element shows');
    await blocked.close();
  } finally {
    await close();
  }
});
