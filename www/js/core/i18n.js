// The pages' words: one table per language (strings/en.js, strings/zh.js), chosen by `?lang=`
// (also read from the fragment's query part) or else the browser's languages; English when
// neither names a shipped language. Every user-visible string of the pages comes from `t`.
//
//   t('play.pause')                       → "Pause"
//   t('limit.agents', { count: 5, max: 4 }) → "… 5 … 4 …" (`{name}` is replaced, text only)
//   translatePage(document)               → fills [data-i18n], [data-i18n-title],
//                                           [data-i18n-aria-label], [data-i18n-placeholder]
//
// Keys are dotted: `<page or concern>.<thing>`. A key missing from a shipped table fails
// tests/e2e/i18n.test.mjs; at run time it falls back to English, then to the key itself.

import en from './strings/en.js';
import zh from './strings/zh.js';

/** The shipped languages, each with its name in its own language (for the language menu). */
export const LANGUAGES = Object.freeze({ en: 'English', zh: '简体中文' });

const TABLES = { en, zh };

/** A shipped language code for a BCP 47 tag (`zh-CN`, `zh-Hans` → `zh`), or null. */
export function shippedLanguage(tag) {
  if (typeof tag !== 'string') return null;
  const primary = tag.trim().toLowerCase().split(/[-_]/)[0];
  return Object.hasOwn(TABLES, primary) ? primary : null;
}

function chooseLanguage() {
  const fromUrl = typeof location === 'undefined' ? null : new URLSearchParams(location.search).get('lang');
  if (fromUrl && shippedLanguage(fromUrl)) return shippedLanguage(fromUrl);
  const preferred = typeof navigator === 'undefined' ? [] : navigator.languages ?? [navigator.language];
  for (const tag of preferred) {
    const code = shippedLanguage(tag);
    if (code) return code;
  }
  return 'en';
}

let current = chooseLanguage();

/** The language the page speaks now (`en` or `zh`). */
export function language() {
  return current;
}

/** Switches language (an unknown code is ignored) and re-translates `root`. */
export function setLanguage(code, root = typeof document === 'undefined' ? null : document) {
  const shipped = shippedLanguage(code);
  if (!shipped) return current;
  current = shipped;
  if (root) translatePage(root);
  return current;
}

/** The text for `key` in the current language, with `{name}` replaced by `vars.name`. */
export function t(key, vars = undefined) {
  const text = TABLES[current][key] ?? en[key] ?? key;
  if (!vars) return text;
  return text.replace(/\{(\w+)\}/g, (whole, name) => (Object.hasOwn(vars, name) ? String(vars[name]) : whole));
}

const ATTRIBUTES = [
  ['data-i18n-title', 'title'],
  ['data-i18n-aria-label', 'aria-label'],
  ['data-i18n-placeholder', 'placeholder'],
  ['data-i18n-alt', 'alt'],
];

/**
 * Fills every marked element under `root` in the current language: `data-i18n="key"` sets the
 * text (the element must hold text only), `data-i18n-title="key"` etc. set that attribute.
 */
export function translatePage(root = document) {
  if (root.documentElement) root.documentElement.lang = current === 'zh' ? 'zh-Hans' : current;
  for (const el of root.querySelectorAll('[data-i18n]')) el.textContent = t(el.dataset.i18n);
  for (const [data, attribute] of ATTRIBUTES) {
    for (const el of root.querySelectorAll(`[${data}]`)) el.setAttribute(attribute, t(el.getAttribute(data)));
  }
}

/** Every shipped table, for the missing-key test. */
export const TABLES_FOR_TESTS = TABLES;
