// The project's one static file server: what `scripts/serve.sh` runs for the playground, what the
// benchmark scripts and the end-to-end tests serve www/ with.
//
//   node scripts/static-server.mjs [--port N] [--bind ADDR] [--directory DIR]
//
// prints `static-server: serving DIR at http://ADDR:PORT/` first (the real port when --port is 0),
// then one line per request. As a module, `serveStatic(mounts, options)`.
//
// What a page on another origin needs to load the `<flock-path>` module, its imports and the wasm:
// `Access-Control-Allow-Origin: *` (option `cors`) and fixed MIME types (`text/javascript` for
// modules, `application/wasm` so browsers compile the wasm while it downloads). Responses are
// compressed for clients that accept it: a precompressed sibling (`file.br`, `file.gz`, written by
// scripts/precompress.mjs) when it is at least as new as the file, else gzip made on the fly; a
// stale sibling is never served (an edited file must not meet its old compressed copy).

import { createReadStream } from 'node:fs';
import { readFile, stat } from 'node:fs/promises';
import { createServer } from 'node:http';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { gzipSync } from 'node:zlib';

export const MIME = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json',
  '.wasm': 'application/wasm',
  '.png': 'image/png',
  '.svg': 'image/svg+xml',
  '.ts': 'text/plain; charset=utf-8',
  '.txt': 'text/plain; charset=utf-8',
  '.webmanifest': 'application/manifest+json',
  '.xml': 'application/xml',
  '.zip': 'application/zip',
};

/** Types worth compressing (text and wasm; images and zips are compressed already). */
export const COMPRESSIBLE = new Set(['.html', '.js', '.mjs', '.css', '.json', '.wasm', '.svg', '.ts', '.txt', '.webmanifest', '.xml']);

/** Files below this size go uncompressed: the headers would outweigh the saving. */
const MIN_COMPRESS_BYTES = 1024;

/** The encodings a request accepts, of those served (`br`, `gzip`); `q=0` refuses one. */
function accepted(header = '') {
  const ok = new Set();
  for (const part of header.split(',')) {
    const [name, ...params] = part.trim().toLowerCase().split(';');
    const q = params.map((p) => p.trim()).find((p) => p.startsWith('q='));
    if (q && Number(q.slice(2)) === 0) continue;
    if (name === 'br' || name === 'gzip') ok.add(name);
  }
  return ok;
}

/** `file`'s precompressed sibling for `encoding` when it exists and is not older than the file. */
async function freshSibling(file, info, encoding) {
  const sibling = `${file}.${encoding === 'br' ? 'br' : 'gz'}`;
  try {
    const s = await stat(sibling);
    return s.isFile() && s.mtimeMs >= info.mtimeMs ? { sibling, size: s.size } : null;
  } catch {
    return null;
  }
}

/**
 * Serves folders on 127.0.0.1 (or `bind`) and a free port (or `port`). `mounts` maps a URL prefix
 * ('/', '/course/demo/') to a folder; the longest matching prefix wins, a folder's URL serves its
 * index.html. Options: `cors` (true, or a function of the path saying for which files),
 * `cacheControl` (default `no-cache`: revalidate, so a rebuilt wasm never meets a cached
 * flockpath.js), `compress` (default true), `validators` (ETag and Last-Modified, default true;
 * false serves as the project's server did before issue 29, for benchmarks), `onRequest(req, res)` (return false to leave the
 * request unanswered: the caller handled or dropped it). Resolves to `{ origin, port, close }`.
 */
export async function serveStatic(mounts, options = {}) {
  const { cors = false, cacheControl = 'no-cache', compress = true, validators = true, onRequest = null, port = 0, bind = '127.0.0.1', log = null } = options;
  const prefixes = Object.keys(mounts).sort((a, b) => b.length - a.length);
  const server = createServer(async (req, res) => {
    if (onRequest && onRequest(req, res) === false) return;
    let pathname;
    try {
      pathname = decodeURIComponent(new URL(req.url, 'http://x').pathname);
    } catch {
      res.writeHead(400).end('bad request');
      return;
    }
    const allowed = typeof cors === 'function' ? cors(pathname) : cors;
    const corsHeaders = allowed ? { 'access-control-allow-origin': '*' } : {};
    const answer = (status, text) => {
      res.writeHead(status, { 'content-type': 'text/plain; charset=utf-8', ...corsHeaders }).end(text);
      log?.(`${req.method} ${pathname} ${status}`);
    };
    if (req.method === 'OPTIONS') {
      // A preflight (only sent when a host adds custom request headers): allow reads.
      res.writeHead(204, { ...corsHeaders, 'access-control-allow-methods': 'GET, HEAD, OPTIONS', 'access-control-allow-headers': '*' }).end();
      return;
    }
    if (req.method !== 'GET' && req.method !== 'HEAD') {
      answer(405, 'only GET and HEAD');
      return;
    }
    const prefix = prefixes.find((p) => pathname.startsWith(p));
    const root = prefix === undefined ? null : path.resolve(mounts[prefix]);
    let file = root && path.join(root, pathname.slice(prefix.length));
    if (!file || (file !== root && !file.startsWith(root + path.sep))) {
      answer(404, 'not found');
      return;
    }
    let info;
    try {
      info = await stat(file);
      if (info.isDirectory()) {
        file = path.join(file, 'index.html');
        info = await stat(file);
      }
      if (!info.isFile()) throw new Error('not a file');
    } catch {
      answer(404, 'not found');
      return;
    }
    const ext = path.extname(file);
    // Validators, so a revalidation (`no-cache`, the service worker's precache) costs a 304, not
    // the file again; weak because the bytes sent depend on the encoding.
    const etag = `W/"${info.size.toString(16)}-${Math.floor(info.mtimeMs).toString(16)}"`;
    const headers = {
      'content-type': MIME[ext] ?? 'application/octet-stream',
      'cache-control': cacheControl,
      ...(validators ? { etag, 'last-modified': new Date(info.mtimeMs).toUTCString() } : {}),
      ...corsHeaders,
    };
    const match = req.headers['if-none-match'];
    if (validators && match && match.split(',').some((tag) => tag.trim() === etag || tag.trim() === '*')) {
      res.writeHead(304, headers).end();
      log?.(`${req.method} ${pathname} 304`);
      return;
    }
    const compressible = compress && COMPRESSIBLE.has(ext) && info.size >= MIN_COMPRESS_BYTES;
    if (compressible) headers.vary = 'Accept-Encoding';
    const encodings = compressible ? accepted(req.headers['accept-encoding']) : new Set();
    let body = null;
    let stream = file;
    let size = info.size;
    for (const encoding of ['br', 'gzip']) {
      if (!encodings.has(encoding)) continue;
      const found = await freshSibling(file, info, encoding);
      if (found) {
        headers['content-encoding'] = encoding;
        stream = found.sibling;
        size = found.size;
        break;
      }
    }
    if (!headers['content-encoding'] && encodings.has('gzip')) {
      // No fresh precompressed copy: gzip at a fast level (level 6 of a 2 MB wasm: ~60 ms).
      body = gzipSync(await readFile(file), { level: 6 });
      headers['content-encoding'] = 'gzip';
      size = body.length;
    }
    headers['content-length'] = String(size);
    res.writeHead(200, headers);
    log?.(`${req.method} ${pathname} 200 ${size} bytes${headers['content-encoding'] ? ` (${headers['content-encoding']})` : ''}`);
    if (req.method === 'HEAD') res.end();
    else if (body) res.end(body);
    else createReadStream(stream).pipe(res);
  });
  await new Promise((resolve, reject) => {
    server.once('error', reject);
    server.listen(port, bind, resolve);
  });
  const { port: actual } = server.address();
  return {
    origin: `http://${bind}:${actual}`,
    port: actual,
    close: () => {
      server.closeAllConnections();
      return new Promise((resolve) => server.close(resolve));
    },
  };
}

/** Command line: serve one folder at `/` with CORS on, until killed. */
async function main(argv) {
  const flag = (name, fallback) => {
    const i = argv.indexOf(name);
    return i >= 0 && i + 1 < argv.length ? argv[i + 1] : fallback;
  };
  const here = path.dirname(fileURLToPath(import.meta.url));
  const directory = path.resolve(flag('--directory', path.join(here, '..', 'www')));
  const port = Number(flag('--port', '0'));
  const bind = flag('--bind', '127.0.0.1');
  if (!Number.isInteger(port) || port < 0 || port > 65535) {
    console.error(`static-server: --port ${flag('--port')} is not a port number (0 to 65535)`);
    process.exit(2);
  }
  try {
    if (!(await stat(directory)).isDirectory()) throw new Error();
  } catch {
    console.error(`static-server: --directory ${directory} is not a folder`);
    process.exit(2);
  }
  let served;
  try {
    served = await serveStatic({ '/': directory }, { cors: true, port, bind, log: (line) => console.log(line) });
  } catch (error) {
    console.error(`static-server: cannot listen on ${bind}:${port}: ${error.message}`);
    process.exit(1);
  }
  console.log(`static-server: serving ${directory} at http://${bind}:${served.port}/`);
  const stop = () => served.close().then(() => process.exit(0));
  process.on('SIGINT', stop);
  process.on('SIGTERM', stop);
}

if (process.argv[1] && path.resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  await main(process.argv.slice(2));
}
