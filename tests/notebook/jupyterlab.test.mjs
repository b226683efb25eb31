// The notebook widget in a real JupyterLab (issue 28): a notebook's cells show two FlockPath
// widgets, step them from Python, and print what the browser wrote back; each digest equals the
// CLI's (`flockpath run`) for the same scene and steps, so the widget runs the same simulation,
// each its own. Needs the venv and package of scripts/test-notebooks.sh (which runs this file).

import assert from 'node:assert/strict';
import { mkdir, readFile, writeFile } from 'node:fs/promises';
import path from 'node:path';
import { after, before, test } from 'node:test';
import { ARTIFACTS, ROOT } from '../e2e/helpers.mjs';
import { cliDigest, notebook, startJupyterLab } from './jupyter-helpers.mjs';

// The cells are docs/notebooks.md's example ("In a notebook"), as a course author copies them; the
// test adds a cell that prints what the kernel heard back.
const DOC = await readFile(path.join(ROOT, 'docs', 'notebooks.md'), 'utf8');
const section = DOC.slice(DOC.indexOf('## In a notebook'), DOC.indexOf('## Options and state'));
const DOC_CELLS = [...section.matchAll(/```python\n([\s\S]*?)```/g)].map((m) => m[1].trimEnd());
/** name → { scene, steps } as the example's cells make and step them. */
const RUNS = {};
for (const [, name, scene] of DOC_CELLS.join('\n').matchAll(/^(\w+) = FlockPath\("([\w-]+)"/gm)) RUNS[name] = { scene };
for (const [, name, steps] of DOC_CELLS.join('\n').matchAll(/^(\w+)\.step\((\d+)\)$/gm)) RUNS[name].steps = Number(steps);
const NAMES = Object.keys(RUNS);
// The doc's last cell only reads (its answer is quoted in the text below it); this one prints.
const CELLS = [
  ...DOC_CELLS.slice(0, -1),
  `print(${NAMES.map((n) => `"${n}", ${n}.steps, ${n}.digest`).join(', ')}, "errors", repr(${NAMES.map((n) => `${n}.error`).join(' + ')}))`,
];

let lab;

before(async () => {
  lab = await startJupyterLab({ 'widgets.ipynb': notebook(CELLS) });
});

after(async () => {
  await lab?.close();
});

/**
 * Runs the notebook's cell `index` in place (Ctrl+Enter in its editor, as a reader would), and
 * waits until JupyterLab has taken it (its prompt shows `[*]` or a number): a key pressed while
 * the page is still wiring its shortcuts is lost, so it is pressed again then.
 */
async function runCell(index) {
  const cell = lab.page.locator('.jp-Notebook .jp-CodeCell').nth(index);
  const prompt = cell.locator('.jp-InputPrompt');
  const before = (await prompt.innerText()).trim();
  for (let attempt = 0; attempt < 5; attempt += 1) {
    await cell.locator('.cm-content').click();
    await lab.page.keyboard.press('Control+Enter');
    const taken = await lab.page
      .waitForFunction(
        ([el, was]) => {
          const now = el.textContent.trim();
          return now !== was || now.includes('*');
        },
        [await prompt.elementHandle(), before],
        { timeout: 10_000 },
      )
      .then(() => true)
      .catch(() => false);
    if (taken) return cell;
  }
  throw new Error(`cell ${index} was not run (its prompt stayed "${before}")`);
}

test('two widgets in JupyterLab step from Python and report the CLI digest', { timeout: 360_000 }, async () => {
  try {
    await runNotebook();
  } catch (error) {
    // What JupyterLab and the page said, for the failure's reader.
    await mkdir(ARTIFACTS, { recursive: true });
    await lab.page.screenshot({ path: path.join(ARTIFACTS, 'notebook-jupyterlab-failed.png') }).catch(() => {});
    await writeFile(path.join(ARTIFACTS, 'notebook-jupyterlab.log'), lab.log());
    error.message += `\npage errors: ${lab.errors.join(' | ') || 'none'}; JupyterLab's log: test-artifacts/notebook-jupyterlab.log`;
    throw error;
  }
});

async function runNotebook() {
  const { page } = lab;
  await page.goto(lab.url('lab/tree/widgets.ipynb'));
  await page.locator('.jp-Notebook .jp-CodeCell').nth(CELLS.length - 1).waitFor({ timeout: 60_000 });
  // The kernel is up (the status bar says Idle) before the first cell runs.
  await page.locator('.jp-StatusBar-TextItem', { hasText: /\|\s*Idle/ }).first().waitFor({ timeout: 150_000 });

  // Cells 1 and 2 show the widgets: each loads its own simulation (the wasm from the kernel's server).
  for (const index of [0, 1]) {
    const cell = await runCell(index);
    // The first cell waits for the kernel to start: up to a minute or two on a busy machine.
    await cell.locator('flock-path canvas').waitFor({ timeout: 150_000 });
    await cell.locator('flock-path .loading').waitFor({ state: 'hidden', timeout: 60_000 });
  }
  const shown = await page.evaluate(() =>
    [...document.querySelectorAll('flock-path')].map((el) => ({ name: el.scene().name, steps: el.steps, bar: !el.shadowRoot.querySelector('.bar').hidden })),
  );
  assert.deepEqual(shown.map((s) => s.name), NAMES.map((n) => RUNS[n].scene));
  assert.deepEqual(shown.map((s) => s.steps), [0, 0], 'playing=False by default: they wait at step 0');
  assert.ok(shown.every((s) => s.bar), 'controls shown');
  const secondButtons = await page.evaluate(() =>
    [...document.querySelectorAll('flock-path')[1].shadowRoot.querySelectorAll('.bar button')].filter((b) => !b.hidden).map((b) => b.className),
  );
  assert.deepEqual(secondButtons, ['play', 'step'], 'controls="play,step" shows only those');

  // Cell 3 asks the browser to step; each element gets there on its own.
  assert.deepEqual(NAMES, ['first', 'second'], `the example's widgets: ${JSON.stringify(RUNS)}`);
  assert.ok(NAMES.every((n) => RUNS[n].steps > 0), 'the example steps each widget');
  await runCell(2);
  await page.waitForFunction(
    (want) => {
      const els = [...document.querySelectorAll('flock-path')];
      return els.length === 2 && els[0].steps === want[0] && els[1].steps === want[1];
    },
    [RUNS.first.steps, RUNS.second.steps],
    { timeout: 60_000 },
  );
  await mkdir(ARTIFACTS, { recursive: true });
  await page.screenshot({ path: path.join(ARTIFACTS, 'notebook-jupyterlab.png') });
  const widgets = page.locator('flock-path');
  await widgets.nth(0).screenshot({ path: path.join(ARTIFACTS, 'notebook-widget-pillars.png') });
  await widgets.nth(1).screenshot({ path: path.join(ARTIFACTS, 'notebook-widget-corridor.png') });

  // Cell 4 prints what the kernel heard back (the widget's answer arrives after cell 3 ended).
  let printed = '';
  for (let attempt = 0; attempt < 20; attempt += 1) {
    const cell = await runCell(CELLS.length - 1);
    const output = cell.locator('.jp-OutputArea-output');
    await page.waitForTimeout(300);
    await output.first().waitFor({ timeout: 30_000 });
    printed = (await output.first().innerText()).trim();
    if (printed.includes(`first ${RUNS.first.steps} `) && printed.includes(`second ${RUNS.second.steps} `)) break;
    await page.waitForTimeout(500);
  }
  const match = /^first (\d+) ([0-9a-f]{16}) second (\d+) ([0-9a-f]{16}) errors '(.*)'$/.exec(printed);
  assert.ok(match, `the kernel printed the widgets' state: ${printed}`);
  const [, firstSteps, firstDigest, secondSteps, secondDigest, errors] = match;
  assert.equal(Number(firstSteps), RUNS.first.steps);
  assert.equal(Number(secondSteps), RUNS.second.steps);
  assert.equal(errors, '', 'no widget error');
  assert.equal(firstDigest, cliDigest(RUNS.first.scene, RUNS.first.steps), 'pillars: the CLI digest');
  assert.equal(secondDigest, cliDigest(RUNS.second.scene, RUNS.second.steps), 'corridor: the CLI digest');
  assert.notEqual(firstDigest, secondDigest);
  // The answer the doc quotes under its last cell is the one the widget gave.
  assert.ok(section.includes(`(${RUNS.first.steps}, '${firstDigest}', `), 'docs/notebooks.md quotes the digest the widget gives');
  assert.deepEqual(lab.errors, [], 'no console or page errors');
}
