// The iframe (`embed.html#s=…&controls=…&lock=…&hide=…`) and `<flock-path controls="…" lock="…">`
// honour the teacher's options: only the controls named are in the bar, the "Open in flockpath"
// link carries the options to the playground (which is then locked the same way), a refused
// attribute is said in the element's box and by `flockpath-error`, and an old embed link (or a
// bare `controls`) still shows every control.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPath, simpleScene } from './helpers.mjs';

const ready = () => window.flockpathEmbed !== undefined;
const BUTTONS = ['.play', '.step', '.reset', '.planner'];

/** Which of the element's bar parts are shown (its bar included). */
const bar = (page, selector = '#embedded') =>
  page.evaluate(([sel, parts]) => {
    const root = document.querySelector(sel).shadowRoot;
    const shown = (el) => Boolean(el && !el.hidden && el.getClientRects().length > 0);
    return { bar: shown(root.querySelector('.bar')), ...Object.fromEntries(parts.map((p) => [p, shown(root.querySelector(p))])) };
  }, [selector, BUTTONS]);

test('the iframe shows only the controls named and carries the options to the playground', async () => {
  const first = await openPath('embed.html', { ready });
  const fragment = await first.page.evaluate(async (scene) => {
    await window.flockpathEmbed.load(scene);
    return window.flockpathEmbed.sceneString();
  }, simpleScene({ name: 'embedded-lock' }));
  assert.deepEqual(await bar(first.page), { bar: true, '.play': true, '.step': true, '.reset': true, '.planner': true },
    'an embed link without options shows every control');
  await first.close();

  const { page, errors, close } = await openPath(`embed.html#s=${fragment}&controls=play,reset&lock=obstacles&hide=metrics`, { ready });
  try {
    await page.evaluate(() => window.flockpathEmbed.ready);
    assert.deepEqual(await bar(page), { bar: true, '.play': true, '.step': false, '.reset': true, '.planner': false });
    const classroom = await page.evaluate(() => window.flockpathEmbed.classroom());
    assert.deepEqual([classroom.controls, classroom.lock, classroom.hide], [['play', 'reset'], ['obstacles'], ['metrics']]);

    const link = page.locator('#open-full');
    await link.hover();
    const href = await link.getAttribute('href');
    assert.equal(new URL(href).hash, `#s=${fragment}&controls=play,reset&lock=obstacles&hide=metrics`);

    // The playground it opens is locked the same way.
    await page.waitForLoadState('networkidle');
    await page.goto(href);
    await page.waitForFunction(() => window.flockpath !== undefined);
    await page.evaluate(() => window.flockpath.ready);
    const applied = await page.evaluate(() => ({
      classroom: window.flockpath.classroom(),
      circle: document.querySelector('[data-tool="circle"]').getClientRects().length > 0,
      step: document.getElementById('step').getClientRects().length > 0,
      metrics: document.getElementById('metrics').getClientRects().length > 0,
    }));
    assert.deepEqual(applied.classroom.lock, ['obstacles']);
    assert.deepEqual([applied.circle, applied.step, applied.metrics], [false, false, false]);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('<flock-path> shows the controls its attribute names and refuses unknown names by field', async () => {
  const { page, errors, close } = await openPath('embed.html', { ready });
  try {
    await page.evaluate(() => window.flockpathEmbed.ready);
    await page.evaluate(async () => {
      const add = (id, attributes) => {
        const el = document.createElement('flock-path');
        el.id = id;
        for (const [k, v] of Object.entries(attributes)) el.setAttribute(k, v);
        el.style.height = '200px';
        document.body.append(el);
        return el.ready;
      };
      window.refusals = [];
      document.addEventListener('flockpath-error', (e) => window.refusals.push(String(e.detail)));
      await add('only-step', { scene: 'pillars', controls: 'step, reset', lock: 'goals' });
      await add('bare', { scene: 'pillars', controls: '' });
      await add('typo', { scene: 'pillars', controls: 'play', hide: 'metrics,charts' });
    });
    assert.deepEqual(await bar(page, '#only-step'), { bar: true, '.play': false, '.step': true, '.reset': true, '.planner': false });
    assert.deepEqual(await page.evaluate(() => document.getElementById('only-step').classroom().lock), ['goals']);
    assert.deepEqual(await bar(page, '#bare'), { bar: true, '.play': true, '.step': true, '.reset': true, '.planner': true });

    // The refused attribute: said in the box and by the event; the others apply.
    const refusals = await page.evaluate(() => window.refusals);
    assert.equal(refusals.length, 1, refusals.join('\n'));
    assert.match(refusals[0], /hide/);
    assert.match(refusals[0], /"charts"/);
    assert.match(refusals[0], /metrics, plots, diagnose, timeline, groups, keys/);
    const box = await page.evaluate(() => document.getElementById('typo').shadowRoot.querySelector('.message').textContent);
    assert.equal(box, refusals[0]);
    assert.deepEqual(await bar(page, '#typo'), { bar: true, '.play': true, '.step': false, '.reset': false, '.planner': false });

    // Changing the attribute later applies at once.
    await page.evaluate(() => document.getElementById('only-step').setAttribute('controls', 'play,planner'));
    assert.deepEqual(await bar(page, '#only-step'), { bar: true, '.play': true, '.step': false, '.reset': false, '.planner': true });
    await page.evaluate(() => document.getElementById('only-step').setAttribute('controls', 'none'));
    assert.equal((await bar(page, '#only-step')).bar, false, 'no controls: no bar');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

// Issue 27 §4: the host page sets the teacher's options by postMessage, so they never appear in a
// URL a student can edit; `openLink: false` also hides the way out to the full page.
test('a host page sets the locks by postMessage: nothing in the iframe URL, the Open link hidden', async () => {
  const { page, errors, close } = await openPath('examples/course-notes.html', { ready: () => document.getElementById('corridor') !== null });
  try {
    await page.evaluate(() => {
      const frame = document.getElementById('corridor');
      let next = 1;
      const pending = new Map();
      window.addEventListener('message', (event) => {
        if (event.source === frame.contentWindow && event.data?.flockpath === 1) pending.get(event.data.id)?.(event.data);
      });
      window.__call = (method, ...args) => new Promise((resolve) => {
        const id = next++;
        pending.set(id, resolve);
        frame.contentWindow.postMessage({ flockpath: 1, id, method, args }, '*');
      });
    });
    const call = (method, ...args) => page.evaluate(([m, a]) => window.__call(m, ...a), [method, args]);
    const frame = page.frameLocator('#corridor');
    await frame.locator('flock-path').waitFor();
    const src = await page.getAttribute('#corridor', 'src');
    assert.doesNotMatch(src, /lock=|controls=/, 'the options are not in the iframe URL');

    let reply = await call('setClassroom', { controls: ['play', 'reset'], lock: 'obstacles,goals', openLink: false });
    assert.equal(reply.ok, true, reply.error);
    assert.deepEqual([reply.result.controls, reply.result.lock], [['play', 'reset'], ['obstacles', 'goals']]);
    const shown = () => frame.locator('flock-path').evaluate((el) => {
      const visible = (node) => Boolean(node && !node.hidden && node.getClientRects().length > 0);
      return { play: visible(el.shadowRoot.querySelector('.play')), step: visible(el.shadowRoot.querySelector('.step')), open: visible(document.getElementById('open-full')) };
    });
    assert.deepEqual(await shown(), { play: true, step: false, open: false });

    // A refused name: an error naming the option and the allowed names; the other options apply.
    reply = await call('setClassroom', { lock: 'walls', controls: 'step' });
    assert.equal(reply.ok, false);
    assert.match(reply.error, /lock/);
    assert.match(reply.error, /"walls"/);
    assert.match(reply.error, /obstacles, goals, groups, paths/);
    assert.deepEqual((await shown()).step, true);
    reply = await call('setClassroom', { locks: 'goals' });
    assert.equal(reply.ok, false);
    assert.match(reply.error, /unknown option "locks"; known: controls, lock, hide, openLink/);

    // Back to everything allowed.
    reply = await call('setClassroom', { controls: null, lock: null, openLink: true });
    assert.equal(reply.ok, true, reply.error);
    assert.equal(reply.result.open, true);
    assert.deepEqual(await shown(), { play: true, step: true, open: true });
    assertNoUnexpectedErrors(errors, [/walls/]);
  } finally {
    await close();
  }
});
