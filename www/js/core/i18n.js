// The pages' words: one table per language (strings/en.js, strings/zh.js), chosen by `?lang=`
// (also read from the fragment's options), else the language picked earlier in the language menu
// (localStorage), else the browser's languages; English when none names a shipped language.
// Every user-visible string of the pages comes from `t`.
//
//   t('play.pause')                       → "Pause"
//   t('limit.agents', { count: 5, max: 4 }) → "… 5 … 4 …" (`{name}` is replaced, text only)
//   translatePage(document)               → fills [data-i18n], [data-i18n-html], [data-i18n-title],
//                                           [data-i18n-aria-label], [data-i18n-placeholder], [data-i18n-alt],
//                                           [data-i18n-content] (the meta description)
//   setText(el, key, vars)                → el's text now, and again after every language switch
//
// Keys are dotted: `<page or concern>.<thing>`. A key missing from a shipped table fails
// tests/e2e/i18n.test.mjs; at run time it falls back to English, then to the key itself.
//
// A page downloads only the tables it speaks (issue 29 §1): English, the fallback, always; another
// language's table when the page starts in it (this module waits for it: top-level await) or when
// the language menu switches to it (`setLanguage` resolves once it is loaded).

import en from './strings/en.js';

/** The shipped languages, each with its name in its own language (for the language menu). */
export const LANGUAGES = Object.freeze({ en: 'English', zh: '简体中文' });

/** How each shipped language's table is fetched (English is always loaded). */
const LOADERS = {
  en: async () => en,
  zh: async () => (await import('./strings/zh.js')).default,
};

/** The tables loaded so far. */
const TABLES = { en };

/** Loads `code`'s table once (a shipped code); resolves when `t` can use it. */
async function loadTable(code) {
  TABLES[code] ??= await LOADERS[code]();
}

/** Where the language picked in the menu is remembered. */
export const STORAGE_KEY = 'flockpath-lang';

/** A shipped language code for a BCP 47 tag (`zh-CN`, `zh-Hans` → `zh`), or null. */
export function shippedLanguage(tag) {
  if (typeof tag !== 'string') return null;
  const primary = tag.trim().toLowerCase().split(/[-_]/)[0];
  return Object.hasOwn(LOADERS, primary) ? primary : null;
}

/** The `lang=` option of a location: the query's, else the fragment's (`#s=…&lang=zh`). */
export function languageFromLocation(loc = typeof location === 'undefined' ? null : location) {
  if (!loc) return null;
  const fromQuery = new URLSearchParams(loc.search).get('lang');
  if (shippedLanguage(fromQuery)) return shippedLanguage(fromQuery);
  const part = loc.hash.replace(/^#/, '').split('&').find((p) => p.startsWith('lang='));
  return part ? shippedLanguage(decodeURIComponent(part.slice('lang='.length))) : null;
}

function storedLanguage() {
  try {
    return shippedLanguage(globalThis.localStorage?.getItem(STORAGE_KEY) ?? null);
  } catch {
    return null; // storage refused (sandboxed iframe, privacy settings)
  }
}

function chooseLanguage() {
  const linked = languageFromLocation();
  if (linked) return linked;
  const stored = storedLanguage();
  if (stored) return stored;
  const preferred = typeof navigator === 'undefined' ? [] : navigator.languages ?? [navigator.language];
  for (const tag of preferred) {
    const code = shippedLanguage(tag);
    if (code) return code;
  }
  return 'en';
}

let current = chooseLanguage();
const starting = loadTable(current);
// A page waits for its words. A worker must not: a module worker awaiting at its top misses the
// messages posted to it meanwhile; its few words (most cross as codes) are English until then.
if (typeof document !== 'undefined') await starting;
const listeners = new Set();

/** The language the page speaks now (`en` or `zh`). */
export function language() {
  return current;
}

/** The BCP 47 tag of a shipped language for `<html lang>` (`zh` → `zh-Hans`). */
export function htmlLang(code = current) {
  return code === 'zh' ? 'zh-Hans' : code;
}

/**
 * Switches language (an unknown code is ignored) once its table is loaded, re-translates `root`
 * and tells every listener (`onLanguageChange`) and the window (`flockpath-language` event).
 * Resolves to the language now.
 */
export async function setLanguage(code, root = typeof document === 'undefined' ? null : document) {
  const shipped = shippedLanguage(code);
  if (!shipped) return current;
  await loadTable(shipped);
  const changed = shipped !== current;
  current = shipped;
  if (root) translatePage(root);
  if (changed) {
    for (const fn of [...listeners]) {
      try {
        fn(current);
      } catch (error) {
        console.error(error);
      }
    }
    if (typeof window !== 'undefined') window.dispatchEvent(new CustomEvent('flockpath-language', { detail: current }));
  }
  return current;
}

/** Runs `fn(code)` after every language switch (to redraw words drawn in code); returns an off switch. */
export function onLanguageChange(fn) {
  listeners.add(fn);
  return () => listeners.delete(fn);
}

/** Whether the current (or English) table has `key`. */
export function hasKey(key) {
  return Object.hasOwn(TABLES[current] ?? en, key) || Object.hasOwn(en, key);
}

const fill = (text, vars) =>
  vars ? text.replace(/\{(\w+)\}/g, (whole, name) => (Object.hasOwn(vars, name) ? String(vars[name]) : whole)) : text;

/** The text for `key` in the current language, with `{name}` replaced by `vars.name`. */
export function t(key, vars = undefined) {
  return fill((TABLES[current] ?? en)[key] ?? en[key] ?? key, vars);
}

/**
 * The text for `key`, or `fallback` when no table has it: for words that come from the core
 * (a planner's label, a parameter's help, a preset's description) keyed by their stable name.
 */
export function tOr(key, fallback, vars = undefined) {
  const text = (TABLES[current] ?? en)[key] ?? en[key];
  return text === undefined ? fill(String(fallback ?? ''), vars) : fill(text, vars);
}

/** Number formatters by language and options: `toLocaleString` builds one per call (slow). */
const formatters = new Map();

/** A number in the page's language (digit grouping). */
export function formatNumber(value, options = undefined) {
  const locale = current === 'zh' ? 'zh-CN' : 'en-US';
  const key = `${locale}|${options === undefined ? '' : JSON.stringify(options)}`;
  let format = formatters.get(key);
  if (!format) {
    format = new Intl.NumberFormat(locale, options);
    formatters.set(key, format);
  }
  return format.format(Number(value));
}

/**
 * Sets `el`'s text to `t(key, vars)` and marks it, so `translatePage` (a language switch) writes
 * it again in the new language. Returns `el`.
 */
export function setText(el, key, vars = undefined) {
  el.dataset.i18n = key;
  if (vars) el.dataset.i18nVars = JSON.stringify(vars);
  else delete el.dataset.i18nVars;
  const text = t(key, vars);
  if (el.textContent !== text) el.textContent = text;
  return el;
}

/** Sets attribute `name` (`title`, `aria-label`, `placeholder`, `alt`) to `t(key, vars)`, marked likewise. */
export function setAttr(el, name, key, vars = undefined) {
  el.setAttribute(`data-i18n-${name}`, key);
  if (vars) el.setAttribute(`data-i18n-${name}-vars`, JSON.stringify(vars));
  else el.removeAttribute(`data-i18n-${name}-vars`);
  el.setAttribute(name, t(key, vars));
  return el;
}

const ATTRIBUTES = ['title', 'aria-label', 'placeholder', 'alt', 'content'];

/** Elements a `data-i18n-html` text may hold; any other markup is shown as its text. */
const INLINE = new Set(['KBD', 'CODE', 'STRONG', 'EM', 'B', 'I', 'SPAN']);

function varsOf(el, attribute) {
  const json = el.getAttribute(attribute);
  if (!json) return undefined;
  try {
    return JSON.parse(json);
  } catch {
    return undefined;
  }
}

/** Puts a table's text with inline markup (`<kbd>`, `<code>`, …; no attributes) into `el`. */
function setInlineHtml(el, text) {
  const template = el.ownerDocument.createElement('template');
  template.innerHTML = text;
  const clean = (node) => {
    for (const child of [...node.childNodes]) {
      if (child.nodeType === 1) {
        if (!INLINE.has(child.tagName)) {
          child.replaceWith(el.ownerDocument.createTextNode(child.textContent));
          continue;
        }
        for (const a of [...child.attributes]) child.removeAttribute(a.name);
        clean(child);
      } else if (child.nodeType !== 3) {
        child.remove();
      }
    }
  };
  clean(template.content);
  el.replaceChildren(template.content);
}

/**
 * Fills every marked element under `root` in the current language: `data-i18n="key"` sets the
 * text (the element must hold text only), `data-i18n-html="key"` text with inline markup,
 * `data-i18n-title="key"` etc. set that attribute (`data-i18n-content` a meta description's);
 * `data-i18n-vars` (JSON) fills `{name}`s. On a document it also sets `<html lang>` (unless it
 * carries `data-i18n-keep-lang`) and points the manifest link at the language's manifest.
 */
export function translatePage(root = document) {
  // A page whose content is written in one language (course notes) keeps its own `lang`.
  const html = root.documentElement;
  if (html && !html.hasAttribute('data-i18n-keep-lang')) html.lang = htmlLang();
  // The web app manifest (name and description an installed app shows): one per language,
  // `manifest.webmanifest` in English, `manifest.<code>.webmanifest` for the others.
  const manifest = root.querySelector?.('link[rel="manifest"]');
  if (manifest) {
    const href = manifest.getAttribute('href') ?? '';
    const wanted = href.replace(/manifest(?:\.\w+)?\.webmanifest$/, current === 'en' ? 'manifest.webmanifest' : `manifest.${current}.webmanifest`);
    if (wanted !== href) manifest.setAttribute('href', wanted);
  }
  for (const el of root.querySelectorAll('[data-i18n]')) {
    const text = t(el.dataset.i18n, varsOf(el, 'data-i18n-vars'));
    if (el.textContent !== text) el.textContent = text;
  }
  for (const el of root.querySelectorAll('[data-i18n-html]')) setInlineHtml(el, t(el.dataset.i18nHtml));
  for (const attribute of ATTRIBUTES) {
    for (const el of root.querySelectorAll(`[data-i18n-${attribute}]`)) {
      el.setAttribute(attribute, t(el.getAttribute(`data-i18n-${attribute}`), varsOf(el, `data-i18n-${attribute}-vars`)));
    }
  }
}

/** The English table (the reference). */
export { en };

/** Every shipped table, for the missing-key test. */
export const TABLES_FOR_TESTS = TABLES;
