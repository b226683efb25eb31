// Starting up: the wasm module loaded and initialised once per page or worker (every page, both
// workers and every <flock-path> element share `loadWasm`), and a page's guarded start that turns
// any failure into the banner (or the crash panel) instead of a blank page. Every URL is resolved
// against this module's own URL, so the folder works under any sub-path, offline, and from a page
// on another site (<flock-path>; the server must allow CORS, see README "Hosting").

import { capturePanicReports, isPanic, messageOf, setupBanner, showMessage, showPanic } from './errors.js';

/** The wasm-bindgen glue and the wasm it loads (named here to say what went wrong). */
export const PKG_URL = new URL('../../pkg/flockpath.js', import.meta.url).href;
export const WASM_URL = new URL('../../pkg/flockpath_bg.wasm', import.meta.url).href;

/** Why loading `url` failed, in words a course author can act on, with the browser's detail. */
function loadError(what, url, error, hint = '') {
  // The browser's detail often repeats the URL the message already names.
  const detail = messageOf(error).replace(` fetching '${url}'`, '').replace(`: ${url}`, '');
  return new Error(`The flockpath simulation could not be loaded: ${what} (${detail}).${hint}`);
}

/** The hint for a request the browser refused: on another site, CORS or the page's CSP. */
function refusedHint() {
  if (new URL(PKG_URL).origin === location.origin) return '';
  return (
    ' This page is on another site than flockpath: the flockpath server must send Access-Control-Allow-Origin, ' +
    'and a Content-Security-Policy must allow its origin (see flockpath’s README, “Hosting”).'
  );
}

/** The hint for glue missing on flockpath's own site: the build did not run. */
function buildHint() {
  return new URL(PKG_URL).origin === location.origin ? ' Build it with: bash scripts/build-wasm.sh' : '';
}

let loaded = null;

/**
 * Loads and initialises the wasm module once; resolves to `{ module, wasm }` (the JS bindings and
 * the instance exports, for `memory`), or rejects with a readable Error naming what failed.
 */
export function loadWasm() {
  loaded ??= (async () => {
    let module;
    try {
      module = await import(PKG_URL);
    } catch (error) {
      throw loadError(`the browser refused or could not find ${PKG_URL}`, PKG_URL, error, refusedHint() || buildHint());
    }
    let wasm;
    try {
      wasm = await module.default({ module_or_path: WASM_URL });
    } catch (error) {
      // fetch() rejects with a TypeError when the browser refuses it (CORS, CSP) or is offline; a
      // CompileError is the CSP refusing WebAssembly or a file that is not wasm; else an HTTP error.
      if (error instanceof TypeError) {
        throw loadError(`the browser refused or could not fetch ${WASM_URL}`, WASM_URL, error, refusedHint());
      }
      const wasmApi = typeof WebAssembly !== 'undefined' ? WebAssembly : null;
      if (wasmApi && (error instanceof wasmApi.CompileError || error instanceof wasmApi.LinkError)) {
        const hint = " A Content-Security-Policy must allow 'wasm-unsafe-eval' in script-src (see flockpath’s README, “Hosting”).";
        throw loadError(`${WASM_URL} could not be started as WebAssembly`, WASM_URL, error, hint);
      }
      throw loadError(`${WASM_URL} could not be loaded`, WASM_URL, error);
    }
    return { module, wasm };
  })();
  return loaded;
}

/**
 * A page's start: wires the banner and the panic reports, loads the wasm, then runs
 * `start({ module, wasm })`. Any failure hides `#loading` and says `${what} could not start: …`
 * in the banner (a panic: the crash panel where the page has one); it is also logged, so the
 * console and the e2e tests see it.
 */
export function bootPage(what, start) {
  setupBanner();
  capturePanicReports();
  return (async () => start(await loadWasm()))().catch((error) => {
    const message = messageOf(error);
    document.getElementById('loading')?.setAttribute('hidden', '');
    if (!(isPanic(error) && showPanic(message))) showMessage(`${what} could not start: ${message}`);
    console.error(error);
  });
}
