// The iframe postMessage API: a host page sends { flockpath: 1, id, method, args } to an
// embed.html iframe and gets { flockpath: 1, id, ok, result | error } back, for load, play,
// pause, step, reset, metrics, scene and sceneString; bad input and unknown methods are errors
// with readable messages, and the embedded scene keeps running.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPath, simpleScene } from './helpers.mjs';

test('a host page scripts the embed through postMessage', async () => {
  const { page, errors, close } = await openPath('examples/course-notes.html', {
    ready: () => document.getElementById('corridor') !== null,
  });
  try {
    // A tiny client in the host page: one promise per request id.
    await page.evaluate(() => {
      const frame = document.getElementById('corridor');
      const pending = new Map();
      let next = 1;
      window.addEventListener('message', (event) => {
        if (event.source !== frame.contentWindow || event.data?.flockpath !== 1) return;
        const waiting = pending.get(event.data.id);
        if (waiting) {
          pending.delete(event.data.id);
          waiting(event.data);
        }
      });
      window.__call = (method, ...args) =>
        new Promise((resolve) => {
          const id = next++;
          pending.set(id, resolve);
          frame.contentWindow.postMessage({ flockpath: 1, id, method, args }, '*');
        });
    });
    const call = (method, ...args) => page.evaluate(([m, a]) => window.__call(m, ...a), [method, args]);
    // Requests sent before the embed has booted wait for it (no need to catch its 'ready').
    await page.frameLocator('#corridor').locator('flock-path').waitFor();

    let reply = await call('pause');
    assert.deepEqual(reply, { flockpath: 1, id: 1, ok: true, result: null });
    reply = await call('load', simpleScene({ name: 'from the host', seed: 5 }));
    assert.equal(reply.ok, true);
    assert.equal(reply.result.name, 'from the host');
    await call('reset');
    reply = await call('step', 50);
    assert.deepEqual([reply.ok, reply.result], [true, 50]);
    const metrics = (await call('metrics')).result;
    assert.equal(metrics.steps, 50);
    assert.equal(metrics.agents, 30);
    const scene = (await call('scene')).result;
    assert.equal(scene.seed, 5);
    const sceneString = (await call('sceneString')).result;
    assert.match(sceneString, /^2\./);

    // Errors: readable, and the scene is unchanged.
    reply = await call('load', '2.garbled!');
    assert.equal(reply.ok, false);
    assert.match(reply.error, /base64|cut short|damaged/);
    reply = await call('step', -1);
    assert.equal(reply.ok, false);
    assert.match(reply.error, /whole number/);
    reply = await call('teleport');
    assert.equal(reply.ok, false);
    assert.match(reply.error, /unknown method "teleport"/);
    assert.equal((await call('sceneString')).result, sceneString, 'scene unchanged after refused calls');

    await call('play');
    assert.equal((await call('isPlaying')).result, true);
    const ids = await page.evaluate(async () => {
      const replies = await Promise.all([window.__call('metrics'), window.__call('digest')]);
      return replies.map((r) => r.id);
    });
    assert.equal(new Set(ids).size, 2, 'replies carry their own request ids');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('when the embed cannot load (its wasm missing), waiting and later requests answer ok: false with the reason', { timeout: 90_000 }, async () => {
  // Ready once the notes' own scenes have their wasm, in the page and in each simulation worker
  // (an element's `sim` exists once its worker started): a fetch still in flight when they are
  // removed below would be aborted (a "request failed" that is not the one this test makes).
  const { page, context, errors, close } = await openPath('examples/course-notes.html', {
    ready: () => {
      const loaded = (win) => win.performance.getEntriesByType('resource').some((e) => e.name.endsWith('.wasm') && e.responseEnd > 0);
      const frames = [...document.querySelectorAll('iframe')];
      return (
        document.getElementById('corridor') !== null &&
        [...document.querySelectorAll('flock-path')].every((el) => el.sim) &&
        frames.every((f) => f.contentWindow && loaded(f.contentWindow) && f.contentWindow.flockpathEmbed?.sim)
      );
    },
  });
  try {
    // A host page with one fresh iframe, whose wasm request is held until requests are waiting.
    let release;
    const held = new Promise((resolve) => (release = resolve));
    let requested;
    const wasmRequested = new Promise((resolve) => (requested = resolve));
    await context.route('**/pkg/flockpath_bg.wasm', async (route) => {
      requested();
      await held;
      await route.fulfill({ status: 404, body: 'not found' });
    });
    await page.evaluate(() => {
      for (const el of document.querySelectorAll('flock-path, iframe')) el.remove();
      const frame = Object.assign(document.createElement('iframe'), { src: '../embed.html' });
      document.body.append(frame);
      window.__replies = new Map();
      window.__events = [];
      window.addEventListener('message', (event) => {
        if (event.source !== frame.contentWindow || event.data?.flockpath !== 1) return;
        if (event.data.event) window.__events.push(event.data);
        else window.__replies.set(event.data.id, event.data);
      });
      window.__send = (id, method, ...args) => frame.contentWindow.postMessage({ flockpath: 1, id, method, args }, '*');
      window.__reply = (id) =>
        new Promise((resolve) => {
          const poll = () => (window.__replies.has(id) ? resolve(window.__replies.get(id)) : setTimeout(poll, 20));
          poll();
        });
    });
    await wasmRequested;
    // The embed's scripts listen once they have run (the wasm download starts earlier, from the
    // page's preload): a message sent before that would reach no listener, in any browser.
    await page.waitForFunction(() => Boolean(document.querySelector('iframe')?.contentWindow?.customElements?.get('flock-path')));
    await page.evaluate(() => {
      window.__send(1, 'step', 10);
      window.__send(2, 'metrics');
    });
    await page.waitForTimeout(300);
    assert.equal(await page.evaluate(() => window.__replies.size), 0, 'requests wait while the embed loads');

    release();
    const reason = /^The flockpath simulation could not be loaded: .*flockpath_bg\.wasm could not be loaded \([^)]*404/;
    const waiting = await page.evaluate(() => Promise.all([window.__reply(1), window.__reply(2)]));
    for (const [i, reply] of waiting.entries()) {
      assert.deepEqual(Object.keys(reply).sort(), ['error', 'flockpath', 'id', 'ok']);
      assert.deepEqual([reply.flockpath, reply.id, reply.ok], [1, i + 1, false]);
      assert.match(reply.error, reason);
    }
    // A request sent after the failure is answered at once with the same reason; an unknown
    // method still says so.
    const later = await page.evaluate(() => {
      window.__send(3, 'digest');
      window.__send(4, 'teleport');
      return Promise.all([window.__reply(3), window.__reply(4)]);
    });
    assert.deepEqual([later[0].ok, later[0].error], [false, waiting[0].error]);
    assert.match(later[1].error, /unknown method "teleport"/);
    // The parent hears of the failure instead of a 'ready' that never comes.
    assert.deepEqual(await page.evaluate(() => window.__events), [{ flockpath: 1, event: 'error', error: waiting[0].error }]);
    assertNoUnexpectedErrors(errors, [/404/, /could not be loaded/]);
  } finally {
    await close();
  }
});
