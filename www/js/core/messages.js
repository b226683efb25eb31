// The core's messages in the reader's language. Every error the core refuses with crosses the
// wasm boundary in one shape: an `Error` whose `message` is the English text and whose `code` and
// `args` (src/model/refusal.rs) say what happened as data. The page words it from the code's
// template in messages/<language>.js: no English sentence is read to make another one.
//
// An argument is a string (shown as it is), a number, a list (joined as the template says), a
// `{term, english}` word of the strings table (a planner's or parameter's label, a unit) or a
// nested `{code, args}` message (the reason a scene could not be read).

import { language, t, tOr } from './i18n.js';
import en from './messages/en.js';
import zh from './messages/zh.js';
import { allowedText, reasonText } from './refusals.js';

const TEMPLATES = { en, zh };

/** The template of `code` in the page's language (English when it has none), or undefined. */
function template(code, lang) {
  return TEMPLATES[lang]?.[code] ?? en[code];
}

/**
 * Text arguments whose words still come from the core's English (what a scene field allows, the
 * JSON reader's reason): worded through refusals.js until the core sends them as messages too.
 */
const ENGLISH_ARGS = { allowed: allowedText, reason: reasonText, problem: reasonText };

/** One argument as text, in `lang`, formatted as the placeholder's `spec` says. */
function argText(name, value, spec, lang) {
  if (value === null || value === undefined) return '';
  if (Array.isArray(value)) {
    // A list of names, or of any arguments (figures beside worded figures, messages).
    const item = (v) => (v !== null && typeof v === 'object' ? argText(name, v, '', lang) : String(v));
    const items = spec === '?' ? value.map((v) => JSON.stringify(String(v))) : value.map(item);
    if ((spec === 'and' || spec === 'or') && items.length > 1) {
      const last = items.pop();
      return `${items.join(', ')} ${lang === 'en' ? spec : t(`list.${spec}`)} ${last}`;
    }
    return items.join(', ');
  }
  if (typeof value === 'object') {
    if (typeof value.code === 'string') return messageText(value.code, value.args ?? {}, lang) ?? String(value.message ?? '');
    if (typeof value.term === 'string') return lang === 'en' ? String(value.english) : tOr(value.term, value.english);
    return JSON.stringify(value);
  }
  if (typeof value === 'number') return String(value);
  const text = String(value);
  if (spec === '?') return JSON.stringify(text);
  if (lang !== 'en' && Object.hasOwn(ENGLISH_ARGS, name)) return ENGLISH_ARGS[name](text);
  return text;
}

/** `{name}`, `{name:spec}`: the template syntax of src/model/refusal.rs. */
const PLACEHOLDER = /\{([a-z_]+)(?::([a-z?]+))?\}/g;

/** The message `code` with `args` in `lang` (the page's language by default); null for an unknown code. */
export function messageText(code, args, lang = language()) {
  const text = template(code, lang);
  if (typeof text !== 'string') return null;
  return text.replace(PLACEHOLDER, (whole, name, spec) => (Object.hasOwn(args ?? {}, name) ? argText(name, args[name], spec ?? '', lang) : whole));
}

/** The argument names of a template, in order of first use (for the template tests). */
export function templateArgs(text) {
  return [...new Set([...text.matchAll(PLACEHOLDER)].map((m) => m[1]))];
}

/** Every code with a template in `lang`. */
export function templateCodes(lang) {
  return Object.keys(TEMPLATES[lang] ?? {});
}

/**
 * The refusal `error` (an `Error` with `code` and `args` from the core) in the page's language;
 * null for an error without a known code (its message is shown as it is).
 */
export function errorText(error) {
  const code = error?.code;
  const args = error?.args;
  if (typeof code !== 'string' || !args || typeof args !== 'object') return null;
  return messageText(code, args);
}
