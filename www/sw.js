// The service worker that lets the pages open without a network: on the first visit it caches
// every file of the folder that the pages need (the list and a version hash come from
// pkg/precache.js, written by scripts/precache.mjs at build time), and afterwards answers a
// request from that cache when the network cannot.
//
// Network first: online, every request goes to the server as if there were no service worker
// (edits to the folder show on the next reload, HTTP caching works as usual); only a request that
// fails, or gets no answer within NETWORK_TIMEOUT_MS, is answered from the cache. The cache holds
// exactly one build (network answers are not written back), so an offline page never mixes files
// of two builds. A new build changes pkg/precache.js, which the browser notices at the next visit
// (it compares this script and its imports byte for byte): the new worker caches the new files
// under a new name, takes over, and deletes the caches of older versions for its scope.
//
// Everything is relative to this script's URL and the scope is its folder, so the folder works
// under any sub-path; several copies on one origin keep separate caches (the name holds the scope).
// Only same-origin GET requests for listed files are touched: anything else (bench data, other
// sites, POSTs) goes to the network untouched.

/* global importScripts */
importScripts('pkg/precache.js');

const { version: VERSION, files: FILES } = self.FLOCKPATH_PRECACHE;
const SCOPE = self.registration.scope;
const PREFIX = `flockpath ${SCOPE} `;
const CACHE = PREFIX + VERSION;
/** How long a request may wait for the network before a cached copy answers it (ms). */
const NETWORK_TIMEOUT_MS = 10_000;
/** Listed files as absolute URLs. */
const LISTED = new Set(FILES.map((file) => new URL(file, SCOPE).href));

self.addEventListener('install', (event) => {
  event.waitUntil(
    (async () => {
      const cache = await caches.open(CACHE);
      // All or nothing: one failed file fails the install and the previous version stays.
      // 'no-cache' revalidates with the server, so an HTTP cache cannot hand back an older build.
      await cache.addAll([...LISTED].map((url) => new Request(url, { cache: 'no-cache' })));
      await self.skipWaiting();
    })(),
  );
});

self.addEventListener('activate', (event) => {
  event.waitUntil(
    (async () => {
      for (const name of await caches.keys()) {
        if (name.startsWith(PREFIX) && name !== CACHE) await caches.delete(name);
      }
      await self.clients.claim();
    })(),
  );
});

/** The listed URL a request stands for (query dropped, a folder means its index.html), or null. */
function listedKey(request) {
  if (request.method !== 'GET') return null;
  const url = new URL(request.url);
  url.search = '';
  url.hash = '';
  if (url.origin !== self.location.origin || !url.href.startsWith(SCOPE)) return null;
  if (url.pathname.endsWith('/')) url.pathname += 'index.html';
  return LISTED.has(url.href) ? url.href : null;
}

async function networkFirst(request, key) {
  const cached = caches.open(CACHE).then((cache) => cache.match(key));
  const network = fetch(request);
  let timer = 0;
  const late = new Promise((resolve) => {
    timer = setTimeout(resolve, NETWORK_TIMEOUT_MS);
  });
  try {
    const winner = await Promise.race([network, late]);
    if (winner) return winner;
    // The network is slow: a cached copy answers, else keep waiting for the network.
    return (await cached) ?? (await network);
  } catch (error) {
    const copy = await cached;
    if (copy) return copy;
    throw error;
  } finally {
    clearTimeout(timer);
  }
}

self.addEventListener('fetch', (event) => {
  const key = listedKey(event.request);
  if (key) event.respondWith(networkFirst(event.request, key));
});

self.addEventListener('message', (event) => {
  // Lets a page (and the tests) ask which build this worker serves.
  if (event.data === 'flockpath-version') event.source?.postMessage({ flockpathVersion: VERSION, cache: CACHE });
});
