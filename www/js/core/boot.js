// Starting up: the wasm module loaded and initialised once per page or worker (every page, both
// workers and every <flock-path> element share `loadWasm`), and a page's guarded start that turns
// any failure into the banner (or the crash panel) instead of a blank page. Every URL is resolved
// against this module's own URL, so the folder works under any sub-path, offline, and from a page
// on another site (<flock-path>; the server must allow CORS, see README "Hosting").

import { capturePanicReports, isPanic, messageOf, setupBanner, showMessage, showPanic } from './errors.js';
import { t } from './i18n.js';

/** The wasm-bindgen glue and the wasm it loads (named here to say what went wrong). */
export const PKG_URL = new URL('../../pkg/flockpath.js', import.meta.url).href;
export const WASM_URL = new URL('../../pkg/flockpath_bg.wasm', import.meta.url).href;

/** Why loading `url` failed, in words a course author can act on, with the browser's detail. */
function loadError(what, url, error, hint = '') {
  // The browser's detail often repeats the URL the message already names.
  const detail = messageOf(error).replace(` fetching '${url}'`, '').replace(`: ${url}`, '');
  return new Error(t('boot.load_failed', { what, detail, hint: hint ? ` ${hint}` : '' }));
}

/** The hint for a request the browser refused: on another site, CORS or the page's CSP. */
function refusedHint() {
  if (new URL(PKG_URL).origin === location.origin) return '';
  return t('boot.hint_cors');
}

/** The hint for glue missing on flockpath's own site: the build did not run. */
function buildHint() {
  return new URL(PKG_URL).origin === location.origin ? t('boot.hint_build') : '';
}

let loaded = null;

/**
 * Loads and initialises the wasm module once; resolves to `{ module, wasm, wasmModule }` (the JS
 * bindings, the instance exports, for `memory`, and the compiled `WebAssembly.Module`, which a
 * page posts to its workers), or rejects with a readable Error naming what failed. `compiled`: a
 * module compiled elsewhere (a worker gets its page's), instead of fetching the wasm.
 */
export function loadWasm(compiled = null) {
  loaded ??= (async () => {
    let module;
    try {
      module = await import(PKG_URL);
    } catch (error) {
      throw loadError(t('boot.not_found', { url: PKG_URL }), PKG_URL, error, refusedHint() || buildHint());
    }
    let wasm;
    let wasmModule;
    try {
      wasmModule = compiled ?? (await compileWasm());
      wasm = await module.default({ module_or_path: wasmModule });
    } catch (error) {
      // fetch() rejects with a TypeError when the browser refuses it (CORS, CSP) or is offline; a
      // CompileError is the CSP refusing WebAssembly or a file that is not wasm; else an HTTP error.
      if (error instanceof TypeError) {
        throw loadError(t('boot.not_fetched', { url: WASM_URL }), WASM_URL, error, refusedHint());
      }
      const wasmApi = typeof WebAssembly !== 'undefined' ? WebAssembly : null;
      if (wasmApi && (error instanceof wasmApi.CompileError || error instanceof wasmApi.LinkError)) {
        throw loadError(t('boot.not_wasm', { url: WASM_URL }), WASM_URL, error, t('boot.hint_csp'));
      }
      throw loadError(t('boot.not_loaded', { url: WASM_URL }), WASM_URL, error);
    }
    return { module, wasm, wasmModule };
  })();
  return loaded;
}

/**
 * Fetches and compiles the wasm (while it downloads, when the server says `application/wasm`).
 * A page's workers get the compiled module from the page (`loadWasm(compiled)`): one download and
 * one compile per page, not one per worker.
 */
async function compileWasm() {
  const response = await fetch(WASM_URL);
  if (!response.ok) throw new Error(`HTTP ${response.status} ${response.statusText}`);
  const type = response.headers.get('content-type') ?? '';
  if (typeof WebAssembly.compileStreaming === 'function' && type.startsWith('application/wasm')) return WebAssembly.compileStreaming(response);
  // For the course author whose server sends another type: it works, only later.
  console.warn(`${WASM_URL} is served as "${type}", not application/wasm: compiled after the download instead of during it.`);
  return WebAssembly.compile(await response.arrayBuffer());
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
    if (!(isPanic(error) && showPanic(message))) showMessage(t('boot.could_not_start', { what, message }));
    console.error(error);
  });
}
