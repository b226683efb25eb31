// Servers for the cross-origin tests: scripts/static-server.mjs (the documented server, what
// scripts/serve.sh runs) on a free port, and
// a course site on another origin that serves pages made in the test.

import { spawn } from 'node:child_process';
import { createServer } from 'node:http';
import path from 'node:path';
import { createInterface } from 'node:readline';
import { ROOT, WWW } from './helpers.mjs';

/** Starts `node scripts/static-server.mjs --port 0` on www/ (as serve.sh does); resolves to { url, firstLine, close }. */
export async function startDocumentedServer() {
  const child = spawn(process.execPath, [path.join(ROOT, 'scripts', 'static-server.mjs'), '--port', '0', '--directory', WWW], {
    stdio: ['ignore', 'pipe', 'pipe'],
  });
  let stderr = '';
  child.stderr.on('data', (chunk) => (stderr += chunk));
  const lines = createInterface({ input: child.stdout });
  const firstLine = await new Promise((resolve, reject) => {
    lines.once('line', resolve);
    child.once('exit', (code) => reject(new Error(`static-server.mjs exited (${code}) before printing its address: ${stderr}`)));
  });
  const url = /at (http:\/\/\S+\/)$/.exec(firstLine)?.[1];
  if (!url) {
    child.kill();
    throw new Error(`static-server.mjs printed no address: ${firstLine}`);
  }
  const close = () =>
    new Promise((resolve) => {
      if (child.exitCode !== null) resolve();
      else {
        child.once('exit', resolve);
        child.kill();
      }
    });
  return { url, firstLine, close };
}

/**
 * A course site on its own origin (127.0.0.1, another port). `pages` maps a path to { html,
 * headers } or to a script's text (served as text/javascript); it may change between requests.
 */
export async function startHost(pages = new Map()) {
  const server = createServer((req, res) => {
    const page = pages.get(new URL(req.url, 'http://x').pathname);
    if (page === undefined) {
      res.writeHead(404).end('not found');
    } else if (typeof page === 'string') {
      res.writeHead(200, { 'content-type': 'text/javascript; charset=utf-8', 'cache-control': 'no-store' }).end(page);
    } else {
      res.writeHead(200, { 'content-type': 'text/html; charset=utf-8', 'cache-control': 'no-store', ...page.headers });
      res.end(page.html);
    }
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  return {
    origin: `http://127.0.0.1:${server.address().port}`,
    pages,
    close: () => new Promise((resolve) => server.close(resolve)),
  };
}
