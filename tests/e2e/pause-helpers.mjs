// Shared by the tests that time a Pause click while a heavy scene steps in the worker (issue 24):
// the click's timing, measured in the page, and the heavy obstacle field of worker-pause.test.mjs.

/**
 * Clicks Pause with a real pointer (and the page's own listeners) and measures, in the page, from
 * the moment the browser took the button's release (the pointerup event's `timeStamp`: a click
 * that waits behind a busy main thread counts its wait) until the button says "not pressed", the
 * page API `window[api]` says paused, and a requestAnimationFrame callback ran after that.
 * `api`: `flockpath` (playground), `flockpathCompare` (compare page), or `flockpathLab` (the lab,
 * its button `#lab-play`); `element`: instead, the CSS selector of a `<flock-path>` whose own Play
 * button is clicked (its `playing` property says paused). The pointer goes to the button's
 * centre, found beforehand, without Playwright's actionability checks (they wait for the page's
 * main thread, which would hide a blocked page from the measure).
 */
export async function timedPause(page, api = 'flockpath', { element = null } = {}) {
  const box = await page.evaluate(
    ({ name, selector }) => {
      const el = selector ? document.querySelector(selector).shadowRoot.querySelector('.play') : document.getElementById(name === 'flockpathLab' ? 'lab-play' : 'play');
      const rect = el.getBoundingClientRect();
      return { x: rect.x, y: rect.y, width: rect.width, height: rect.height };
    },
    { name: api, selector: element },
  );
  await page.evaluate(
    ({ name, selector }) => {
      const host = selector ? document.querySelector(selector) : null;
      const button = host ? host.shadowRoot.querySelector('.play') : document.getElementById(name === 'flockpathLab' ? 'lab-play' : 'play');
      const playing = host ? () => host.playing : () => window[name].isPlaying();
      const pressed = () => button.getAttribute('aria-pressed') === 'true';
      window.__pause = null;
      let down = null;
      const watch = () => {
        if (!pressed() && !playing()) {
          requestAnimationFrame(() => {
            window.__pause = performance.now() - down;
          });
          return;
        }
        requestAnimationFrame(watch);
      };
      button.addEventListener(
        'pointerup',
        (event) => {
          down = event.timeStamp;
          requestAnimationFrame(watch);
        },
        { once: true },
      );
    },
    { name: api, selector: element },
  );
  await page.mouse.click(box.x + box.width / 2, box.y + box.height / 2);
  await page.waitForFunction(() => window.__pause !== null, null, { timeout: 10_000 });
  return page.evaluate(() => window.__pause);
}

/** A seeded uniform generator in [0, 1) (LCG), so the scenes are the same every run. */
export function seeded(seed) {
  let state = seed >>> 0;
  return () => {
    state = (Math.imul(state, 1664525) + 1013904223) >>> 0;
    return (state >>> 8) / (1 << 24);
  };
}

/**
 * `count` circles centred beyond the top-left corner of a `world`-px square world, each reaching
 * past its bottom and right edges (its bounding box covers the world: every obstacle is a
 * candidate for every agent) while the bottom-right part stays free.
 */
export function coveringCircles(count, world) {
  const unit = seeded(2024);
  return Array.from({ length: count }, () => {
    const a = 2000 + Math.round(unit() * 1000);
    return { shape: 'circle', center: [-a, -a], radius: world + a + 1 };
  });
}
