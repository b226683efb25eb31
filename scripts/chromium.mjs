// Headless Chromium for the benchmark scripts: Debian's /usr/bin/chromium driven by playwright-core
// (nothing is downloaded), with the flags a root user without network needs (docs: TOOLCHAIN.md).

import { mkdtemp, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { chromium } from 'playwright-core';

export const CHROMIUM_ARGS = [
  '--no-sandbox', '--disable-dev-shm-usage', '--disable-gpu', '--disable-quic', '--no-first-run',
  '--disable-background-networking', '--disable-component-update', '--disable-sync',
];

/**
 * Launches Chromium with a fresh profile in a temporary folder named `prefix…` and the page of
 * `viewport`. Resolves to `{ context, page, close }`; `close()` ends the browser (whatever state
 * it is in) and removes the profile.
 */
export async function launchChromium(prefix, viewport) {
  const profile = await mkdtemp(path.join(tmpdir(), prefix));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: '/usr/bin/chromium',
    headless: true,
    args: CHROMIUM_ARGS,
    viewport,
  });
  const page = context.pages()[0] ?? (await context.newPage());
  const close = async () => {
    await context.close().catch(() => {});
    await rm(profile, { recursive: true, force: true });
  };
  return { context, page, close };
}
