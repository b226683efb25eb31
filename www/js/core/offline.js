// Registers the service worker (www/sw.js) that keeps the pages working without a network. Each
// page includes this module with a <script type="module"> tag; nothing imports it. The worker's
// URL is resolved against this module's own URL (so the folder works under any sub-path), its
// scope is the folder it sits in, and it is registered only from pages of its own origin (a page
// of another site embedding <flock-path> never is: flock-path.js does not load this module).
// Registration waits for the page's `load` event, so caching the folder never competes with the
// first start. Where service workers are unavailable (file://, plain http on another host, a
// browser that blocks them) the pages simply work online only.
//
// `window.flockpathOffline` is a promise of the registration (null when there is none).

/** The folder of the pages (two up from js/core/); the worker sits at its top, so its scope is
 * the whole folder. (Registered by URL, not imported: the worker is no module of the page.) */
const FOLDER = new URL('../../', import.meta.url);
const SW_URL = new URL('sw.js', FOLDER);

/** Registers the worker once the page has loaded; resolves to the registration or null. */
export function registerOffline() {
  const container = navigator.serviceWorker;
  if (!container || SW_URL.origin !== location.origin) return Promise.resolve(null);
  const loaded =
    document.readyState === 'complete' ? Promise.resolve() : new Promise((resolve) => addEventListener('load', resolve, { once: true }));
  return loaded
    .then(() => container.register(SW_URL.href, { scope: FOLDER.href, updateViaCache: 'none' }))
    .catch(() => null);
}

window.flockpathOffline ??= registerOffline();
