// scripts/static-server.mjs (what scripts/serve.sh runs): on port 0 it prints the real port, and it
// answers the module, its imports and the wasm with `Access-Control-Allow-Origin: *` and the MIME
// types a browser needs (text/javascript for modules, application/wasm for streaming
// compilation), compressed for clients that accept it (issue 29: a first visit under 1 MB), with
// validators so a revalidation is a 304, and never a stale precompressed copy.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { copyFile, mkdtemp, rm, utimes, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { brotliDecompressSync, gunzipSync } from 'node:zlib';
import { WWW } from './helpers.mjs';
import { startDocumentedServer } from './cross-origin-helpers.mjs';
import { serveStatic } from '../../scripts/static-server.mjs';

test('the documented server sends CORS headers and the right MIME types for the module, its imports and the wasm', async () => {
  const server = await startDocumentedServer();
  try {
    assert.match(server.firstLine, /^static-server: serving .*www at http:\/\/127\.0\.0\.1:\d+\/$/, 'serve.sh reads the port from this line');
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
    // The wasm arrives whole and unchanged once decoded (a compiled module's magic number first).
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
    // Outside the folder is not served.
    const outside = await fetch(`${server.url}..%2f..%2fCargo.toml`);
    assert.equal(outside.status, 404);
  } finally {
    await server.close();
  }
});

/** GET `url` with `encoding` accepted (node's fetch would decode: read the raw body with http). */
async function raw(url, headers) {
  const { request } = await import('node:http');
  return new Promise((resolve, reject) => {
    request(url, { headers }, (res) => {
      const chunks = [];
      res.on('data', (c) => chunks.push(c));
      res.on('end', () => resolve({ status: res.statusCode, headers: res.headers, body: Buffer.concat(chunks) }));
    }).on('error', reject).end();
  });
}

test('compressed answers: a fresh brotli copy, gzip on the fly for a stale one, identity when not accepted, 304 on revalidation', async () => {
  const dir = await mkdtemp(path.join(tmpdir(), 'flockpath-serve-'));
  const server = await serveStatic({ '/': dir });
  try {
    const text = `${'const agents = [];\n'.repeat(400)}// end\n`;
    const file = path.join(dir, 'app.js');
    await writeFile(file, text);
    const { brotliCompressSync } = await import('node:zlib');
    await writeFile(`${file}.br`, brotliCompressSync(Buffer.from(text)));
    const url = `${server.origin}/app.js`;

    const br = await raw(url, { 'accept-encoding': 'gzip, deflate, br' });
    assert.equal(br.headers['content-encoding'], 'br');
    assert.equal(br.headers.vary, 'Accept-Encoding');
    assert.equal(brotliDecompressSync(br.body).toString(), text);
    assert.ok(br.body.length < text.length / 10, `brotli ${br.body.length} of ${text.length} bytes`);

    const gz = await raw(url, { 'accept-encoding': 'gzip' });
    assert.equal(gz.headers['content-encoding'], 'gzip');
    assert.equal(gunzipSync(gz.body).toString(), text);

    const plain = await raw(url, { 'accept-encoding': 'identity' });
    assert.equal(plain.headers['content-encoding'], undefined);
    assert.equal(plain.body.toString(), text);
    const refused = await raw(url, { 'accept-encoding': 'br;q=0, gzip;q=0' });
    assert.equal(refused.headers['content-encoding'], undefined);

    // The file changed after its copy was written: the copy is stale and never served.
    const edited = text.replace('// end', '// edited');
    await writeFile(file, edited);
    const later = new Date(Date.now() + 5_000);
    await utimes(file, later, later);
    const fresh = await raw(url, { 'accept-encoding': 'br, gzip' });
    assert.equal(fresh.headers['content-encoding'], 'gzip', 'gzip made on the fly, not the stale brotli copy');
    assert.equal(gunzipSync(fresh.body).toString(), edited);

    // Revalidation with the validator it gave: 304 and no body.
    const again = await raw(url, { 'accept-encoding': 'br, gzip', 'if-none-match': fresh.headers.etag });
    assert.equal(again.status, 304);
    assert.equal(again.body.length, 0);

    // Images are not compressed again.
    await copyFile(path.join(WWW, 'icon.svg'), path.join(dir, 'icon.svg'));
    await writeFile(path.join(dir, 'tiny.png'), Buffer.alloc(4096, 7));
    const png = await raw(`${server.origin}/tiny.png`, { 'accept-encoding': 'br, gzip' });
    assert.equal(png.headers['content-encoding'], undefined);
  } finally {
    await server.close();
    await rm(dir, { recursive: true, force: true });
  }
});
