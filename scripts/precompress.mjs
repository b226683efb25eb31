// Writes a brotli (`file.br`) and a gzip (`file.gz`) copy beside every compressible file of www/
// (pages, scripts, style sheets, the wasm), for static hosts that serve precompressed files (nginx
// `gzip_static`/`brotli_static`, Caddy `precompressed`, Netlify, scripts/static-server.mjs). A copy
// is rewritten only when older than its file; a copy whose file is gone is removed. The copies are
// build output (.gitignore). scripts/build-wasm.sh runs this after every build.
//
//   node scripts/precompress.mjs [--www DIR]
//
// Prints the folder's size raw, gzipped and brotli-compressed.

import { readdir, readFile, rm, stat, writeFile } from 'node:fs/promises';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { brotliCompressSync, constants, gzipSync } from 'node:zlib';
import { COMPRESSIBLE } from './static-server.mjs';

const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const args = process.argv.slice(2);
const at = args.indexOf('--www');
const WWW = path.resolve(at >= 0 && args[at + 1] ? args[at + 1] : path.join(ROOT, 'www'));
/** Folders left out: benchmark scenes (large, generated, fetched by the benchmark only). */
const SKIP_DIRS = new Set(['bench']);

async function walk(dir, top = true) {
  const out = [];
  for (const entry of await readdir(dir, { withFileTypes: true })) {
    if (entry.name.startsWith('.')) continue;
    const full = path.join(dir, entry.name);
    if (entry.isDirectory()) {
      if (!(top && SKIP_DIRS.has(entry.name))) out.push(...(await walk(full, false)));
    } else if (entry.isFile()) {
      out.push(full);
    }
  }
  return out;
}

const mtime = async (file) => {
  try {
    return (await stat(file)).mtimeMs;
  } catch {
    return -1;
  }
};

const files = await walk(WWW);
const present = new Set(files);
let raw = 0;
let gz = 0;
let br = 0;
let written = 0;
let removed = 0;
for (const file of files) {
  const ext = path.extname(file);
  if (ext === '.br' || ext === '.gz') {
    // A copy of a file that is gone (or no longer compressed) would be served for nothing.
    const source = file.slice(0, -ext.length);
    if (!present.has(source) || !COMPRESSIBLE.has(path.extname(source))) {
      await rm(file);
      removed += 1;
    }
    continue;
  }
  if (!COMPRESSIBLE.has(ext)) continue;
  const body = await readFile(file);
  const own = (await stat(file)).mtimeMs;
  raw += body.length;
  for (const [suffix, make] of [
    ['.gz', () => gzipSync(body, { level: 9 })],
    ['.br', () => brotliCompressSync(body, { params: { [constants.BROTLI_PARAM_QUALITY]: 11, [constants.BROTLI_PARAM_SIZE_HINT]: body.length } })],
  ]) {
    const copy = file + suffix;
    if ((await mtime(copy)) < own) {
      await writeFile(copy, make());
      written += 1;
    }
    const size = (await stat(copy)).size;
    if (suffix === '.gz') gz += size;
    else br += size;
  }
}
const kib = (n) => `${(n / 1024).toFixed(0)} KiB`;
console.log(`[precompress] ${path.relative(ROOT, WWW) || '.'}: ${kib(raw)} raw, ${kib(gz)} gzip, ${kib(br)} brotli (${written} copies written, ${removed} removed)`);
