// scripts/serve.py (what scripts/serve.sh runs): on port 0 it prints the real port, and it answers
// the module, its imports and the wasm with `Access-Control-Allow-Origin: *` and the MIME types a
// browser needs (text/javascript for modules, application/wasm for streaming compilation).

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { startServePy } from './cross-origin-helpers.mjs';

test('serve.py sends CORS headers and the right MIME types for the module, its imports and the wasm', async () => {
  const server = await startServePy();
  try {
    assert.match(server.firstLine, /^serve\.py: serving .*www at http:\/\/127\.0\.0\.1:\d+\/$/, 'serve.sh reads the port from this line');
    const expected = {
      'js/flock-path.js': /^text\/javascript\b/,
      'pkg/flockpath.js': /^text\/javascript\b/,
      'pkg/flockpath_bg.wasm': /^application\/wasm$/,
      'examples/course-notes.html': /^text\/html\b/,
    };
    for (const [file, type] of Object.entries(expected)) {
      const response = await fetch(server.url + file, { headers: { origin: 'http://course.example' } });
      assert.equal(response.status, 200, file);
      assert.equal(response.headers.get('access-control-allow-origin'), '*', `${file}: Access-Control-Allow-Origin`);
      assert.match(response.headers.get('content-type') ?? '', type, `${file}: Content-Type`);
      await response.arrayBuffer();
    }
    // The wasm is served whole and unchanged (a compiled module's magic number first).
    const wasm = new Uint8Array(await (await fetch(`${server.url}pkg/flockpath_bg.wasm`)).arrayBuffer());
    assert.deepEqual([...wasm.subarray(0, 4)], [0x00, 0x61, 0x73, 0x6d]);
    // A missing file is a 404 that a page on another site can still read (so it can say so).
    const missing = await fetch(`${server.url}js/no-such-file.js`);
    assert.equal(missing.status, 404);
    assert.equal(missing.headers.get('access-control-allow-origin'), '*');
    // A preflight (custom request headers) is allowed.
    const preflight = await fetch(`${server.url}pkg/flockpath_bg.wasm`, { method: 'OPTIONS' });
    assert.equal(preflight.status, 204);
    assert.match(preflight.headers.get('access-control-allow-methods') ?? '', /\bGET\b/);
  } finally {
    await server.close();
  }
});
