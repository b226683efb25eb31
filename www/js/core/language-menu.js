// A page's language: translates the page's marked HTML (`data-i18n…`, js/core/i18n.js) as soon as
// the page is parsed and puts a small language picker in the top bar's menu (or the bar itself).
// Picking a language re-translates in place (the scene, the run and the panels stay as they are),
// writes `?lang=` into the address (a shared link opens in that language) and remembers the choice
// for the other pages (localStorage). Every page of the folder loads this module; <flock-path> on
// another site does not (it follows `?lang=` and the browser's languages only).

import { LANGUAGES, STORAGE_KEY, language, setLanguage, setAttr, translatePage } from './i18n.js';

/** Puts the language in the address bar's query, keeping the fragment (the scene). */
function writeToLocation(code) {
  const url = new URL(location.href);
  url.searchParams.set('lang', code);
  // A `lang=` in the fragment would win over the query on reload: drop it.
  url.hash = url.hash
    .replace(/^#/, '')
    .split('&')
    .filter((part) => part && !part.startsWith('lang='))
    .join('&');
  history.replaceState(history.state, '', url);
}

function remember(code) {
  try {
    localStorage.setItem(STORAGE_KEY, code);
  } catch {
    // storage refused: the URL still carries the choice
  }
}

/** Switches the page to `code`: re-translates, rewrites the URL, remembers it (once its words are loaded). */
export async function chooseLanguage(code) {
  const now = await setLanguage(code);
  writeToLocation(now);
  remember(now);
  const select = document.getElementById('lang-select');
  if (select) select.value = now;
  return now;
}

/** The picker: a labelled select of the shipped languages, each named in its own language. */
function addMenu() {
  if (document.getElementById('lang-select')) return;
  const place = document.getElementById('topbar-menu') ?? document.querySelector('.topbar');
  if (!place) return;
  const select = document.createElement('select');
  select.id = 'lang-select';
  select.className = 'lang-select';
  setAttr(select, 'aria-label', 'lang.label');
  setAttr(select, 'title', 'lang.title');
  for (const [code, name] of Object.entries(LANGUAGES)) {
    const option = document.createElement('option');
    option.value = code;
    option.textContent = name;
    option.lang = code === 'zh' ? 'zh-Hans' : code;
    select.append(option);
  }
  select.value = language();
  select.addEventListener('change', () => chooseLanguage(select.value));
  place.append(select);
}

function start() {
  translatePage(document);
  addMenu();
}

if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', start, { once: true });
else start();
