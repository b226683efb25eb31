// Starting a module worker from any page: a worker's script must come from the page's own origin,
// so a module served from another site (a <flock-path> pasted into a course page) cannot start
// `new Worker(itsOwnUrl)`. There the worker starts from a same-origin blob whose only line imports
// the real module by its absolute URL: the blob's origin is the page's, the import is a CORS
// request like the element's own module (README, "Hosting"), and the imported module resolves its
// relative URLs (the wasm, its own imports: `import.meta.url`) against where it really lives.
// A host page with a Content-Security-Policy must then allow `blob:` and the module's origin in
// `worker-src` (Chromium checks a module worker's static imports against `worker-src` too).

/** The blob URL made for each cross-origin worker module (one per module, kept for restarts). */
const blobs = new Map();

/** The blob URL whose module imports `absolute` (made once). */
function importerOf(absolute) {
  let url = blobs.get(absolute);
  if (!url) {
    const source = `import ${JSON.stringify(absolute)};\n`;
    url = URL.createObjectURL(new Blob([source], { type: 'text/javascript' }));
    blobs.set(absolute, url);
  }
  return url;
}

/**
 * A module Worker running the module at `url` (a URL or string, absolute or relative to the page):
 * directly when it is on the page's origin, else through a same-origin blob that imports it.
 * Throws what `new Worker` throws (a Content-Security-Policy may refuse it).
 */
export function startModuleWorker(url) {
  const absolute = new URL(url, location.href);
  if (absolute.origin === location.origin) return new Worker(absolute, { type: 'module' });
  return new Worker(importerOf(absolute.href), { type: 'module' });
}

/** Whether workers for `url` start from a blob (the module lives on another origin). */
export function startsFromBlob(url) {
  return new URL(url, location.href).origin !== location.origin;
}
