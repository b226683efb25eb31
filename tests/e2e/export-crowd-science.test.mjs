// The Export dialog's crowd-science entries (issue #25 §3): "PedPy trajectories" and "JuPedSim
// script" download from the real page the same text the CLI writes for the same scene and steps
// (`flockpath run --pedpy FILE --jupedsim FILE`), so the page and the command line cannot drift
// apart; the texts are also checked on their own (one line per walker and frame in metres, the
// scene's obstacle and starts in the script's set-up, a script Python compiles).

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync } from 'node:fs';
import { mkdtemp, readFile, rm, writeFile } from 'node:fs/promises';
import os from 'node:os';
import path from 'node:path';
import { assertNoUnexpectedErrors, openPage, ROOT, screenshot, simpleScene } from './helpers.mjs';

const STEPS = 30;

/** Clicks `selector` and returns the downloaded file's name, text and path. */
async function downloadVia(page, selector) {
  const [download] = await Promise.all([page.waitForEvent('download'), page.click(selector)]);
  const file = await download.path();
  return { name: download.suggestedFilename(), text: await readFile(file, 'utf8'), file };
}

/** Cargo, from PATH or rustup's default place (the e2e runner may not have ~/.cargo/bin on PATH). */
function cargo() {
  const rustup = path.join(os.homedir(), '.cargo', 'bin', 'cargo');
  return existsSync(rustup) ? rustup : 'cargo';
}

/** The CLI's PedPy text and JuPedSim script for `scene` after `steps` steps. */
async function cliExports(scene, steps) {
  const dir = await mkdtemp(path.join(os.tmpdir(), 'flockpath-export-'));
  try {
    const sceneFile = path.join(dir, 'scene.json');
    await writeFile(sceneFile, JSON.stringify(scene));
    const pedpy = path.join(dir, 'out.txt');
    const jupedsim = path.join(dir, 'out.py');
    execFileSync(cargo(), ['run', '--quiet', '--bin', 'flockpath', '--', 'run', '--scene', sceneFile,
      '--steps', String(steps), '--pedpy', pedpy, '--jupedsim', jupedsim], { cwd: ROOT, stdio: ['ignore', 'ignore', 'inherit'] });
    return { pedpy: await readFile(pedpy, 'utf8'), jupedsim: await readFile(jupedsim, 'utf8') };
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
}

test('Export → PedPy trajectories and JuPedSim script are the CLI\'s texts for the same scene', async () => {
  const scene = simpleScene({
    name: 'crowd science',
    obstacles: [{ shape: 'rect', min: [360, 150], max: [400, 350] }],
  });
  const { page, errors, close } = await openPage();
  try {
    await page.evaluate(async ({ scene, steps }) => {
      await window.flockpath.pause();
      await window.flockpath.load(scene);
      await window.flockpath.reset();
      await window.flockpath.step(steps);
    }, { scene, steps: STEPS });
    const loaded = await page.evaluate(() => window.flockpath.scene());
    const positions = await page.evaluate(() => window.flockpath.positions());

    await page.click('#export');
    await screenshot(page, 'export-crowd-science');
    const pedpy = await downloadVia(page, '[data-export="pedpy"]');
    assert.equal(pedpy.name, 'crowd-science.pedpy.txt');
    const jupedsim = await downloadVia(page, '[data-export="jupedsim"]');
    assert.equal(jupedsim.name, 'crowd-science.jupedsim.py');

    // PedPy text on its own: a frame rate of 60 (every step recorded), one line per walker and
    // frame 0…30, the last frame where the page's walkers are (px / 20 px per metre).
    assert.match(pedpy.text, /^# framerate: 60\.0000$/m);
    const rows = pedpy.text.split('\n').filter((l) => l && !l.startsWith('#')).map((l) => l.split(' '));
    assert.equal(rows.length, 30 * (STEPS + 1), 'one line per walker and frame');
    assert.equal(new Set(rows.map((r) => r[0])).size, 30, '30 walker ids');
    const last = rows.filter((r) => Number(r[1]) === STEPS);
    for (const [i, [x, y]] of positions.entries()) {
      const row = last.find((r) => Number(r[0]) === i + 1);
      assert.ok(Math.abs(Number(row[2]) - x / 20) < 1e-4 && Math.abs(Number(row[3]) - y / 20) < 1e-4,
        `walker ${i + 1}: ${row.slice(2, 4)} m vs (${x}, ${y}) px`);
    }

    // JuPedSim script on its own: the suite's translation, the set-up with this scene's obstacle
    // and 30 starts in metres, every goal an exit, the collision-free speed model; Python compiles it.
    const setupJson = jupedsim.text.slice(jupedsim.text.indexOf('r"""') + 4, jupedsim.text.lastIndexOf('""")'));
    const setup = JSON.parse(setupJson);
    assert.equal(setup.starts_m.length, 30);
    assert.deepEqual(setup.scene.obstacles.map((o) => [o.min, o.max]), [[[360, 150], [400, 350]]]);
    assert.ok(setup.scene.goals.every((g) => g.on_arrival === 'exit'), 'goals become exits');
    assert.match(jupedsim.text, /def walkable_area\(/);
    assert.match(jupedsim.text, /run\(SETUP, "cfsm"\)/);
    execFileSync('python3', ['-m', 'py_compile', jupedsim.file]);

    // The same scene and steps through the CLI give the same texts, byte for byte.
    const cli = await cliExports(loaded, STEPS);
    assert.equal(pedpy.text, cli.pedpy, 'the page\'s PedPy text is the CLI\'s');
    assert.equal(jupedsim.text, cli.jupedsim, 'the page\'s JuPedSim script is the CLI\'s');

    // Both entries are worded in Chinese too.
    await page.selectOption('#lang-select', 'zh');
    await page.waitForFunction(() => document.documentElement.lang.startsWith('zh'));
    assert.equal(await page.textContent('[data-export="pedpy"]'), 'PedPy 轨迹');
    assert.equal(await page.textContent('[data-export="jupedsim"]'), 'JuPedSim 脚本');
    await screenshot(page, 'export-crowd-science-zh');
    await page.selectOption('#lang-select', 'en');
    await page.waitForFunction(() => document.documentElement.lang === 'en');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
