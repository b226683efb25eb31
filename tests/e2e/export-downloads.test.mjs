// The export and share dialogs produce real files: paths CSV with one row per agent per recorded
// step, a Blender script Python compiles, a PNG, a WebM recorded with the REC indicator showing,
// the scene JSON; a scene file loads by file picker and by dropping it on the canvas; the
// recording's budget is stated and its thinning announced.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { readFile } from 'node:fs/promises';
import { assertNoUnexpectedErrors, openPage, screenshot, settled, simpleScene } from './helpers.mjs';

/** Clicks `selector` and returns the downloaded file's name and bytes. */
async function downloadVia(page, selector) {
  const [download] = await Promise.all([page.waitForEvent('download'), page.click(selector)]);
  const file = await download.path();
  return { name: download.suggestedFilename(), bytes: await readFile(file), file };
}

/**
 * The Segment Info's Duration of a WebM in seconds (null: none): EBML elements are an ID and a size
 * (variable-length integers, the size's marker bit removed) then the payload.
 */
function webmDurationSeconds(bytes) {
  const vint = (at, keepMarker) => {
    let length = 1;
    while (length <= 8 && !(bytes[at] & (0x80 >> (length - 1)))) length += 1;
    let value = keepMarker ? bytes[at] : bytes[at] & (0xff >> length);
    for (let i = 1; i < length; i += 1) value = value * 256 + bytes[at + i];
    return { value, length };
  };
  const children = (from, to, visit) => {
    for (let at = from; at < to; ) {
      const id = vint(at, true);
      const size = vint(at + id.length, false);
      const start = at + id.length + size.length;
      const known = size.value !== 2 ** (7 * size.length) - 1;
      if (visit(id.value, start, known ? size.value : to - start) === false) return;
      if (!known) return;
      at = start + size.value;
    }
  };
  let scale = 1_000_000;
  let duration = null;
  children(0, bytes.length, (id, start, size) => {
    if (id !== 0x18538067) return true; // Segment
    children(start, start + size, (childId, childStart, childSize) => {
      if (childId !== 0x1549a966) return true; // Info
      children(childStart, childStart + childSize, (infoId, infoStart, infoSize) => {
        if (infoId === 0x2ad7b1) scale = bytes.readUIntBE(infoStart, infoSize);
        if (infoId === 0x4489) duration = infoSize === 8 ? bytes.readDoubleBE(infoStart) : bytes.readFloatBE(infoStart);
      });
      return false;
    });
    return false;
  });
  return duration === null ? null : (duration * scale) / 1e9;
}

test('exports download real files and scenes load from files', async () => {
  const { page, errors, close } = await openPage();
  try {
    await page.evaluate(async (scene) => {
      await window.flockpath.pause();
      await window.flockpath.load(scene);
      await window.flockpath.reset();
      await window.flockpath.step(30);
    }, simpleScene({ name: 'export me' }));
    assert.match(await page.textContent('#recording-info'), /31 frames up to step 30 of 30 agents \(budget 32 MiB/);

    await page.click('#export');
    const csv = await downloadVia(page, '[data-export="csv"]');
    assert.equal(csv.name, 'export-me.csv');
    const rows = csv.bytes.toString('utf8').trim().split('\n');
    assert.equal(rows[0], 'agent,group,step,time,x,y,vx,vy');
    assert.equal(rows.length - 1, 30 * 31, 'one row per agent per recorded step (0..=30)');
    const last = rows.at(-1).split(',').map(Number);
    const positions = await page.evaluate(() => window.flockpath.positions());
    // The CSV holds the shortest text of each f32: it parses back to the same f32.
    assert.deepEqual(
      [last[0], last[2], Math.fround(last[4]), Math.fround(last[5])],
      [29, 30, Math.fround(positions[29][0]), Math.fround(positions[29][1])],
    );

    await page.fill('#export-fps', '30');
    const py = await downloadVia(page, '[data-export="py"]');
    assert.match(py.bytes.toString('utf8'), /scene\.render\.fps = 30/);
    execFileSync('python3', ['-m', 'py_compile', py.file]);
    const mel = await downloadVia(page, '[data-export="mel"]');
    assert.equal((mel.bytes.toString('utf8').match(/spaceLocator/g) ?? []).length, 30);
    await page.fill('#export-fps', '0');
    await page.click('[data-export="mel"]');
    await settled(page);
    assert.match(await page.textContent('#export-status'), /frame rate must be 1…240/);
    await page.fill('#export-fps', '24');
    const svg = await downloadVia(page, '[data-export="svg"]');
    assert.equal((svg.bytes.toString('utf8').match(/<polyline/g) ?? []).length, 30);
    const png = await downloadVia(page, '[data-export="png"]');
    assert.deepEqual([...png.bytes.subarray(0, 4)], [0x89, 0x50, 0x4e, 0x47], 'PNG signature');
    // The world only (issue #27 §5): the image has the world's shape, not the canvas' letterbox.
    const [pngWidth, pngHeight] = [png.bytes.readUInt32BE(16), png.bytes.readUInt32BE(20)];
    const { scale } = await page.evaluate(() => window.flockpath.view());
    const canvasSize = await page.$eval('#scene-canvas', (c) => [c.width, c.height]);
    assert.ok(Math.abs(pngWidth - 800 * scale) <= 1 && Math.abs(pngHeight - 500 * scale) <= 1,
      `PNG ${pngWidth}×${pngHeight} = the 800×500 world at scale ${scale} (canvas ${canvasSize.join('×')})`);
    assert.notDeepEqual([pngWidth, pngHeight], canvasSize, 'the letterboxed canvas is not the image');

    // WebM: the indicator shows while recording; stopping downloads the video.
    await page.click('#record-webm');
    await page.waitForSelector('#recording-indicator:not([hidden])');
    await page.waitForTimeout(1200);
    await screenshot(page, 'export-recording');
    const webm = await downloadVia(page, '#recording-indicator');
    assert.equal(webm.name, 'export-me.webm');
    assert.deepEqual([...webm.bytes.subarray(0, 4)], [0x1a, 0x45, 0xdf, 0xa3], 'WebM (EBML) header');
    // Its length is in the file (issue #27 §5: MediaRecorder leaves Duration out), read here by a
    // walk of the EBML tree independent of the page's writer: ~1.2 s recorded.
    const seconds = webmDurationSeconds(webm.bytes);
    assert.ok(seconds !== null, 'the WebM has a Duration');
    assert.ok(seconds > 0.8 && seconds < 5, `duration ${seconds} s for a ~1.2 s recording`);
    assert.ok(await page.isHidden('#recording-indicator'), 'the indicator goes away');

    // Share dialog: the scene JSON downloads, and loads back by picker and by drop.
    await page.click('#share');
    const json = await downloadVia(page, '#download-scene');
    assert.equal(JSON.parse(json.bytes.toString('utf8')).name, 'export me');
    const other = JSON.stringify(simpleScene({ name: 'picked from a file', seed: 3 }));
    await page.setInputFiles('#scene-file', { name: 'picked.json', mimeType: 'application/json', buffer: Buffer.from(other) });
    await page.waitForFunction(() => window.flockpath.scene().name === 'picked from a file');
    assert.equal(await page.isVisible('#share-dialog'), false, 'the dialog closes after loading');

    const dropped = JSON.stringify(simpleScene({ name: 'dropped on the canvas' }));
    const transfer = await page.evaluateHandle((text) => {
      const dt = new DataTransfer();
      dt.items.add(new File([text], 'dropped.json', { type: 'application/json' }));
      return dt;
    }, dropped);
    await page.dispatchEvent('#stage', 'dragover', { dataTransfer: transfer });
    assert.equal(await page.isVisible('#drop-hint'), true, 'the drop hint shows');
    await page.dispatchEvent('#stage', 'drop', { dataTransfer: transfer });
    await page.waitForFunction(() => window.flockpath.scene().name === 'dropped on the canvas');
    assert.equal(await page.isVisible('#drop-hint'), false);

    // A file that is not a scene: a message, and the scene stays.
    const bad = await page.evaluateHandle(() => {
      const dt = new DataTransfer();
      dt.items.add(new File(['{"width": "wide"}'], 'broken.json', { type: 'application/json' }));
      return dt;
    });
    await page.dispatchEvent('#stage', 'drop', { dataTransfer: bad });
    // The banner may still say the refused export above: wait for this file's message (the
    // worker answers the load a moment later).
    await page.waitForFunction(
      () => !document.getElementById('banner').hidden && document.getElementById('banner-text').textContent.includes('broken.json'),
    );
    assert.match(await page.textContent('#banner-text'), /The file broken\.json was not loaded: width is "wide"; allowed: a number in 10…20000 px/);
    assert.equal((await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene()))).name, 'dropped on the canvas');

    // Thinning is announced: 20,000 agents fill the 32 MiB budget in about 100 steps.
    await page.evaluate(async (scene) => {
      await window.flockpath.pause();
      await window.flockpath.load(scene);
      await window.flockpath.step(220);
    }, simpleScene({ name: 'crowd', width: 4000, height: 4000, goals: [], groups: [{ ...simpleScene().groups[0], count: 20000, goal: null, spawn: { min: [0, 0], max: [4000, 4000] } }] }));
    await page.waitForSelector('#recording-thinned:not([hidden])');
    assert.match(await page.textContent('#recording-thinned'), /reached its 32 MiB budget and now keeps every 4th step/);
    await screenshot(page, 'export-thinned');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
