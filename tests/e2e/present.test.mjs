// Presentation mode (issue 27 §2) in real headless Chromium: Present (button or P) fills the
// viewport with the canvas (fullscreen, or the fixed layer where fullscreen is refused), its
// controls fade after two idle seconds and come back on movement or focus, Esc (or the browser
// leaving fullscreen) gives the page back; axe finds nothing serious in it, and it speaks
// Chinese. Screenshots at 1366×768 and on a 390×844 phone go to test-artifacts/.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, frames, loadPaused, openPage, openPath, screenshot, seriousViolations, settled, simpleScene } from './helpers.mjs';

const canvasBox = (page) =>
  page.evaluate(() => {
    const r = document.getElementById('scene-canvas').getBoundingClientRect();
    return { x: r.x, y: r.y, width: r.width, height: r.height, vw: innerWidth, vh: innerHeight };
  });

const barOpacity = (page) => page.evaluate(() => Number(getComputedStyle(document.getElementById('present-bar')).opacity));

/** Share of the viewport the canvas covers (0…1). */
const covered = (box) => (box.width * box.height) / (box.vw * box.vh);

test('Present fills the viewport, its controls fade when idle and return, Esc gives the page back', async () => {
  const { page, errors, close } = await openPage({ viewport: { width: 1366, height: 768 } });
  try {
    await loadPaused(page, simpleScene());
    const before = await canvasBox(page);
    assert.ok(covered(before) < 0.8, `the page's own layout leaves room around the canvas: ${covered(before).toFixed(2)}`);

    await page.click('#present');
    await page.waitForFunction(() => document.getElementById('scene-canvas').getBoundingClientRect().width >= innerWidth * 0.97);
    await frames(page, 3);
    const presented = await canvasBox(page);
    assert.ok(covered(presented) >= 0.95, `the canvas covers ${(covered(presented) * 100).toFixed(1)} % of the viewport`);
    assert.equal(await page.getAttribute('#present', 'aria-pressed'), 'true');
    // The backing store follows the new size: the Sim (in its worker) renders the full screen.
    await page.waitForFunction((w) => window.flockpath.view().canvasWidth >= 0.95 * w, presented.vw, { timeout: 5000 });
    const view = await page.evaluate(() => window.flockpath.view());
    assert.ok(view.canvasWidth >= 0.95 * presented.vw, `the renderer draws ${view.canvasWidth} px across`);

    // The headline: arrived share and collisions, large.
    const headline = await page.evaluate(() => ({
      arrived: document.getElementById('present-arrived').textContent,
      collisions: document.getElementById('present-collisions').textContent,
      size: parseFloat(getComputedStyle(document.getElementById('present-arrived')).fontSize),
    }));
    assert.match(headline.arrived, /^\d+ %$/);
    assert.match(headline.collisions, /^\d[\d,]*$/);
    assert.ok(headline.size >= 32, `the headline figures are ${headline.size}px`);
    await page.evaluate(() => window.flockpath.step(60));
    await page.waitForFunction(() => document.getElementById('present-arrived').textContent !== '' , null, { timeout: 5000 });

    // Large controls that work: Play from the bar plays, Pause pauses.
    const playBox = await page.locator('#present-play').boundingBox();
    assert.ok(playBox.height >= 44 && playBox.width >= 44, `Play is ${playBox.width}×${playBox.height}`);
    await page.click('#present-play');
    assert.equal(await page.evaluate(() => window.flockpath.isPlaying()), true);
    await page.click('#present-play');
    assert.equal(await page.evaluate(() => window.flockpath.isPlaying()), false);
    const steps = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.metrics().steps));
    await page.click('#present-step');
    await settled(page);
    assert.equal(await page.evaluate(() => window.flockpath.metrics().steps), steps + 1, 'Step steps once');
    // The bar's zoom: + zooms in by 1.5, Fit shows the whole scene again.
    const fitted = await page.evaluate(() => window.flockpath.view().scale);
    await page.click('#present-zoom-in');
    await page.waitForFunction((s) => Math.abs(window.flockpath.view().scale / s - 1.5) < 1e-3, fitted);
    await page.click('#present-fit');
    await page.waitForFunction((s) => window.flockpath.view().scale === s, fitted);

    // Idle: the bar fades after ~2 s without pointer movement (focus moved out of it first).
    await page.mouse.move(600, 300);
    await page.evaluate(() => document.activeElement.blur());
    assert.equal(await barOpacity(page), 1, 'shown right after movement');
    await page.waitForFunction(() => Number(getComputedStyle(document.getElementById('present-bar')).opacity) === 0, null, { timeout: 4000 });
    // Pointer movement brings it back.
    await page.mouse.move(620, 320);
    await page.waitForFunction(() => Number(getComputedStyle(document.getElementById('present-bar')).opacity) === 1, null, { timeout: 2000 });
    // Focus by keyboard brings it back too, and keeps it while focused.
    await page.waitForFunction(() => Number(getComputedStyle(document.getElementById('present-bar')).opacity) === 0, null, { timeout: 4000 });
    await page.keyboard.press('Tab');
    assert.equal(await page.evaluate(() => document.getElementById('stage').contains(document.activeElement)), true,
      'Tab goes into the presentation (the page behind is inert)');
    if (await page.evaluate(() => document.activeElement.id === 'overlay-canvas')) await page.keyboard.press('Tab');
    assert.equal(await page.evaluate(() => document.activeElement.id), 'present-play', 'after the canvas, the bar');
    await page.waitForFunction(() => Number(getComputedStyle(document.getElementById('present-bar')).opacity) === 1, null, { timeout: 2000 });
    for (let i = 0; i < 12; i += 1) {
      await page.keyboard.press('Tab');
      const inside = await page.evaluate(() => document.getElementById('stage').contains(document.activeElement));
      assert.ok(inside, `Tab ${i + 2} left the presentation`);
    }

    // Esc leaves: the layout is the page's again. Entered by a mouse click, the focus goes to the
    // page itself, so Space plays (a focused Present button would present again).
    await page.keyboard.press('Escape');
    await page.waitForFunction((w) => document.getElementById('scene-canvas').getBoundingClientRect().width === w, before.width);
    assert.deepEqual(await canvasBox(page), before);
    assert.equal(await page.getAttribute('#present', 'aria-pressed'), 'false');
    assert.equal(await page.evaluate(() => document.querySelector('.panel').inert), false, 'the page is usable again');
    await page.waitForTimeout(300);
    assert.equal(await page.evaluate(() => document.activeElement === document.body), true, 'the focus is on the page');
    await page.keyboard.press(' ');
    assert.equal(await page.evaluate(() => window.flockpath.isPlaying()), true, 'Space after Esc plays');
    assert.equal(await page.evaluate(() => document.getElementById('stage').classList.contains('presenting')), false);
    await page.evaluate(() => window.flockpath.pause());

    // Entered by keyboard (Enter on the focused button), Esc gives the focus back to Present.
    await page.focus('#present');
    await page.keyboard.press('Enter');
    await page.waitForFunction(() => document.getElementById('stage').classList.contains('presenting'));
    await page.keyboard.press('Escape');
    await page.waitForFunction(() => !document.getElementById('stage').classList.contains('presenting'));
    // Once the browser has left fullscreen, which may drop the focus a frame later.
    await page.waitForTimeout(300);
    assert.equal(await page.evaluate(() => document.activeElement?.id), 'present', 'keyboard focus back on Present');

    // P enters from the page itself (focus on the body).
    await page.evaluate(() => document.activeElement.blur());
    await page.keyboard.press('p');
    await page.waitForFunction(() => document.getElementById('stage').classList.contains('presenting'));
    // The browser leaving fullscreen (its own Esc, F11) leaves the presentation.
    const fullscreen = await page.evaluate(() => document.fullscreenElement?.id ?? null);
    if (fullscreen) {
      assert.equal(fullscreen, 'stage');
      await page.evaluate(() => document.exitFullscreen());
    } else {
      await page.keyboard.press('Escape');
    }
    await page.waitForFunction(() => !document.getElementById('stage').classList.contains('presenting'));
    assert.deepEqual(await canvasBox(page), before);

    // Fullscreen refused (an iframe without allowfullscreen, a browser policy): the fixed layer
    // over the viewport stands in, and Esc leaves it.
    await page.evaluate(() => {
      Element.prototype.requestFullscreen = () => Promise.reject(new TypeError('Permissions check failed'));
    });
    await page.evaluate(() => document.activeElement.blur());
    await page.keyboard.press('p');
    await page.waitForFunction(() => document.getElementById('scene-canvas').getBoundingClientRect().width >= innerWidth * 0.97);
    const layered = await canvasBox(page);
    assert.equal(await page.evaluate(() => document.fullscreenElement), null);
    assert.ok(covered(layered) >= 0.95, `without fullscreen the canvas covers ${(covered(layered) * 100).toFixed(1)} %`);
    await page.keyboard.press('Escape');
    await page.waitForFunction((w) => document.getElementById('scene-canvas').getBoundingClientRect().width === w, before.width);
    console.log(`fullscreen granted: ${Boolean(fullscreen)}; canvas ${before.width}×${before.height} → ${presented.width}×${presented.height} (fallback ${layered.width}×${layered.height}) in ${presented.vw}×${presented.vh}`);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('Present mode passes axe, speaks Chinese, and fits a phone (screenshots at 1366×768 and 390×844)', async () => {
  for (const [name, viewport, lang] of [['present-1366x768', { width: 1366, height: 768 }, 'en'], ['present-390x844-zh', { width: 390, height: 844 }, 'zh']]) {
    const { page, errors, close } = await openPath(`index.html?lang=${lang}#`, { ready: () => window.flockpath !== undefined, viewport });
    try {
      await page.evaluate(() => window.flockpath.step(150));
      await page.click('#present');
      await page.waitForFunction(() => document.getElementById('stage').classList.contains('presenting'));
      await frames(page, 4);
      const box = await canvasBox(page);
      assert.ok(covered(box) >= 0.95, `${name}: the canvas covers ${(covered(box) * 100).toFixed(1)} %`);
      // Every control of the bar inside the viewport.
      const outside = await page.evaluate(() =>
        [...document.querySelectorAll('#present-bar button, #present-bar input')].filter((el) => {
          const r = el.getBoundingClientRect();
          return r.left < 0 || r.top < 0 || r.right > innerWidth || r.bottom > innerHeight;
        }).map((el) => el.id));
      assert.deepEqual(outside, [], `${name}: controls outside the viewport`);
      if (lang === 'zh') {
        assert.equal((await page.textContent('#present-exit')).trim(), '退出');
        assert.equal(await page.getAttribute('#present-bar', 'aria-label'), '演示控件');
        assert.match(await page.textContent('#present-headline'), /已到达/);
      } else {
        assert.equal(await page.getAttribute('#present-bar', 'aria-label'), 'Presentation controls');
      }
      await page.mouse.move(viewport.width / 2, viewport.height / 2);
      await screenshot(page, name);
      assert.deepEqual(await seriousViolations(page), [], `${name}: axe`);
      assertNoUnexpectedErrors(errors);
    } finally {
      await close();
    }
  }
});
