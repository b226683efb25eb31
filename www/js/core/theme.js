// The page theme: "standard" or "projector" (a white field, thick dark trails, large agents,
// larger text, darker ink; for a projector or the back of a classroom). Chosen by the URL
// (`?theme=projector`, or `theme=projector` among the fragment's options: `#s=…&theme=projector`)
// and by a toggle button this module adds to the top bar's menu. The choice is a page option, not
// part of the scene: the canvas is drawn in it by the Rust renderer (`Sim.set_theme`, through
// `flockpath.theme()` on the playground, directly on each <flock-path> element), the rest of the
// page by style.css (`:root[data-theme="projector"]`). Toggling writes `?theme=` into the address
// bar (replaceState; the fragment, which holds the scene and is rewritten by url.js, is left
// alone), so a shared link keeps the theme.

import { setAttr, setText } from './i18n.js';

export const THEMES = ['standard', 'projector'];

/** The theme a location asks for: the fragment's `theme=` option, else the query's, else standard. */
export function themeFromLocation(loc = location) {
  const fragment = loc.hash
    .replace(/^#/, '')
    .split('&')
    .find((part) => part.startsWith('theme='));
  const asked = fragment ? fragment.slice('theme='.length) : new URLSearchParams(loc.search).get('theme');
  return THEMES.includes(asked) ? asked : 'standard';
}

let current = 'standard';

/** Draws every simulation of the page in `current` (the playground and <flock-path> elements). */
function paintCanvases() {
  try {
    // The playground's simulation runs in a worker: the theme is set there (a Promise).
    if (window.flockpath?.theme) Promise.resolve(window.flockpath.theme(current)).catch(() => {});
  } catch {
    // Still booting or crashed: boot applies it (below) or nothing can.
  }
  for (const el of document.querySelectorAll('flock-path')) {
    try {
      if (el.host?.sim && !el.host.crashed) {
        // A Promise when the element's simulation runs in a worker.
        Promise.resolve(el.host.sim.set_theme(current)).catch(() => {});
        el.host.dirty = true;
      }
    } catch {
      // A freed or crashed element keeps its look.
    }
  }
}

/** Applies `name` to the page and its canvases; returns the theme applied. */
export function setTheme(name) {
  current = THEMES.includes(name) ? name : 'standard';
  document.documentElement.dataset.theme = current;
  const toggle = document.getElementById('theme-toggle');
  if (toggle) toggle.setAttribute('aria-pressed', String(current === 'projector'));
  paintCanvases();
  return current;
}

/** Puts the theme in the address bar's query (standard: no option). */
function writeToLocation(name) {
  const url = new URL(location.href);
  if (name === 'standard') url.searchParams.delete('theme');
  else url.searchParams.set('theme', name);
  // A fragment option would win over the query: drop it.
  url.hash = url.hash
    .replace(/^#/, '')
    .split('&')
    .filter((part) => part && !part.startsWith('theme='))
    .join('&');
  history.replaceState(history.state, '', url);
}

/** The "Projector" toggle in the top bar's menu (where the page has one). */
function addToggle() {
  const menu = document.getElementById('topbar-menu');
  if (!menu || document.getElementById('theme-toggle')) return;
  const button = document.createElement('button');
  button.type = 'button';
  button.id = 'theme-toggle';
  button.className = 'ghost';
  setText(button, 'theme.projector');
  setAttr(button, 'title', 'theme.projector_title');
  button.setAttribute('aria-pressed', String(current === 'projector'));
  button.addEventListener('click', () => {
    writeToLocation(setTheme(current === 'projector' ? 'standard' : 'projector'));
  });
  // Last in the menu: opening it still focuses the first view link.
  menu.append(button);
}

setTheme(themeFromLocation());
if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', addToggle, { once: true });
else addToggle();
// The playground's API and the elements appear after boot.
addEventListener('flockpath-ready', paintCanvases);
addEventListener('hashchange', () => {
  if (location.hash.includes('theme=')) setTheme(themeFromLocation());
});
