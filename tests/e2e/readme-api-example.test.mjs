// The README's page-API example for course-note scripts (the synchronous API became Promises when
// the simulation moved into a Web Worker, issue 24) is run as written: the "now" block is read
// from README.md and evaluated in the playground with `scene` bound to a preset's JSON; its
// `share` and `where` must be the state after its `step(300)`, the same as the page's own reads.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import { assertNoUnexpectedErrors, openPage, ROOT } from './helpers.mjs';

/** The README's code block that starts with `// now:`. */
async function nowBlock() {
  const readme = await readFile(path.join(ROOT, 'README.md'), 'utf8');
  const blocks = [...readme.matchAll(/```js\n([\s\S]*?)```/g)].map((m) => m[1]);
  const now = blocks.find((b) => b.startsWith('// now:'));
  assert.ok(now, 'README.md has the "// now:" page-API example');
  return now;
}

test('the README page-API example runs as written and reads the state after its step(300)', async () => {
  const code = await nowBlock();
  const { page, errors, close } = await openPage({ hash: '' });
  try {
    const got = await page.evaluate(async (code) => {
      const flockpath = window.flockpath;
      await flockpath.settled();
      const scene = JSON.stringify(flockpath.scene());
      // The example's own lines, then what it computed.
      const run = new Function('flockpath', 'scene', `return (async () => { ${code}\n return { share, where }; })();`);
      const { share, where } = await run(flockpath, scene);
      return { share, count: where.length, steps: flockpath.metrics().steps, again: flockpath.metrics().arrived_share, agents: flockpath.scene().groups.reduce((n, g) => n + g.count, 0) };
    }, code);
    assert.equal(got.steps, 300, 'the reads after the awaited step(300) are of step 300');
    assert.equal(got.share, got.again, 'share is the metrics of step 300');
    assert.equal(got.count, got.agents, 'positions() gives every agent');
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});
