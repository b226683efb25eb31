// Shared by the notebook tests: a real JupyterLab (from PyPI, in the venv scripts/setup-python.sh
// makes) started on a free port with a token in a temporary folder, Debian's Chromium driven by
// playwright-core, and the CLI's digest of a run to compare the widget's with.

import { execFileSync, spawn } from 'node:child_process';
import { randomBytes } from 'node:crypto';
import { mkdir, mkdtemp, rm, writeFile } from 'node:fs/promises';
import { createServer } from 'node:net';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { chromium } from 'playwright-core';
import { CHROMIUM_ARGS, ROOT } from '../e2e/helpers.mjs';

export const VENV = path.join(ROOT, '.venv-python');

/** A port nobody listens on now (the OS picks it). */
function freePort() {
  return new Promise((resolve, reject) => {
    const server = createServer();
    server.once('error', reject);
    server.listen(0, '127.0.0.1', () => {
      const { port } = server.address();
      server.close(() => resolve(port));
    });
  });
}

/** The digest `flockpath run` prints for `scene` after `steps` steps (16 hex digits). */
export function cliDigest(scene, steps) {
  execFileSync('cargo', ['build', '--quiet', '--bin', 'flockpath'], { cwd: ROOT, stdio: 'inherit' });
  const out = execFileSync(path.join(ROOT, 'target', 'debug', 'flockpath'), ['run', '--scene', scene, '--steps', String(steps)], {
    cwd: ROOT,
    encoding: 'utf8',
  });
  const match = /digest ([0-9a-f]{16})/.exec(out);
  if (!match) throw new Error(`no digest in the CLI's output: ${out}`);
  return match[1];
}

/** A notebook (nbformat 4) of code cells, as JupyterLab saves one. */
export function notebook(cells) {
  return JSON.stringify({
    nbformat: 4,
    nbformat_minor: 5,
    metadata: { kernelspec: { name: 'python3', display_name: 'Python 3', language: 'python' } },
    cells: cells.map((source, i) => ({ cell_type: 'code', id: `cell-${i}`, metadata: {}, execution_count: null, outputs: [], source })),
  });
}

/**
 * Starts JupyterLab in a new temporary folder holding `files` ({name: text}), with its own
 * config, data-free runtime and settings folders (nothing of the machine's Jupyter setup is read
 * or written), and Chromium; resolves to { page, url(pathInLab), errors, log, close }.
 */
export async function startJupyterLab(files) {
  const dir = await mkdtemp(path.join(tmpdir(), 'flockpath-jupyter-'));
  for (const [name, text] of Object.entries(files)) await writeFile(path.join(dir, name), text);
  // No "Would you like news?" prompt over the notebook (there is no internet to ask anyway).
  await mkdir(path.join(dir, '.config', 'labconfig'), { recursive: true });
  await writeFile(
    path.join(dir, '.config', 'labconfig', 'page_config.json'),
    JSON.stringify({ disabledExtensions: { '@jupyterlab/apputils-extension:announcements': true } }),
  );
  const port = await freePort();
  const token = randomBytes(16).toString('hex');
  const env = {
    ...process.env,
    JUPYTER_CONFIG_DIR: path.join(dir, '.config'),
    JUPYTER_RUNTIME_DIR: path.join(dir, '.runtime'),
    IPYTHONDIR: path.join(dir, '.ipython'),
    PATH: `${path.join(VENV, 'bin')}:${process.env.PATH}`,
  };
  const lab = spawn(
    path.join(VENV, 'bin', 'jupyter'),
    [
      'lab',
      '--no-browser',
      '--allow-root',
      `--port=${port}`,
      '--ip=127.0.0.1',
      `--IdentityProvider.token=${token}`,
      `--ServerApp.root_dir=${dir}`,
      `--LabApp.user_settings_dir=${path.join(dir, '.settings')}`,
      `--LabApp.workspaces_dir=${path.join(dir, '.workspaces')}`,
      // No internet here: no news or update checks.
      '--LabApp.news_url=',
      '--LabApp.check_for_updates_class=jupyterlab.NeverCheckForUpdate',
    ],
    { cwd: dir, env, stdio: ['ignore', 'pipe', 'pipe'] },
  );
  let log = '';
  lab.stdout.on('data', (chunk) => (log += chunk));
  lab.stderr.on('data', (chunk) => (log += chunk));
  const base = `http://127.0.0.1:${port}`;
  // Up once its API answers with the token.
  const deadline = Date.now() + 60_000;
  for (;;) {
    if (lab.exitCode !== null) throw new Error(`jupyter lab exited (${lab.exitCode}):\n${log}`);
    try {
      const response = await fetch(`${base}/api/status?token=${token}`);
      if (response.ok) break;
    } catch {
      // Not listening yet.
    }
    if (Date.now() > deadline) throw new Error(`jupyter lab did not answer in 60 s:\n${log}`);
    await new Promise((resolve) => setTimeout(resolve, 250));
  }
  const profile = await mkdtemp(path.join(tmpdir(), 'flockpath-jupyter-chromium-'));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: '/usr/bin/chromium',
    headless: true,
    args: CHROMIUM_ARGS,
    viewport: { width: 1280, height: 900 },
  });
  const page = context.pages()[0] ?? (await context.newPage());
  const errors = [];
  page.on('pageerror', (error) => errors.push(`pageerror: ${error.message}`));
  page.on('console', (msg) => {
    if (msg.type() === 'error') errors.push(`console: ${msg.text()}`);
  });
  return {
    page,
    errors,
    log: () => log,
    url: (where) => `${base}/${where}?token=${token}`,
    close: async () => {
      await context.close().catch(() => {});
      lab.kill('SIGTERM');
      await new Promise((resolve) => (lab.exitCode !== null ? resolve() : lab.once('exit', resolve)));
      await rm(profile, { recursive: true, force: true });
      await rm(dir, { recursive: true, force: true });
    },
  };
}
