// The scene in the address bar: `index.html#s=<fragment>`. Reading happens at boot and on
// `hashchange`; every change the user makes is written back (debounced, with replaceState, so
// the address bar always holds a link to what is on screen and Back is not flooded).

import { messageOf, showMessage } from './errors.js';
import { fragmentValue } from './fragment.js';
import { t } from './i18n.js';

/** The `s=` value of the current location's fragment, or null when there is none. */
export function sceneFromLocation(hash = location.hash) {
  return fragmentValue('s', hash);
}

/** How long edits settle before the address bar is rewritten (ms): a slider drag writes once. */
export const WRITE_DELAY_MS = 300;

/** The page URL that opens `sceneString` (other fragment options dropped). */
export function shareUrl(sceneString, page = location.href) {
  const url = new URL(page);
  url.hash = `s=${sceneString}`;
  return url.href;
}

/** `s=<scene>` followed by the other options of `hash` (classroom options, theme, …): rewriting
 * the scene keeps them, so the address bar still holds the link the page was opened with. */
function withScene(hash, sceneString) {
  const others = hash.replace(/^#/, '').split('&').filter((part) => part && !part.startsWith('s='));
  return [`s=${sceneString}`, ...others].join('&');
}

/** Puts a scene string in the address bar (other fragment options kept); returns the URL. */
export function writeSceneToLocation(sceneString) {
  const url = new URL(location.href);
  url.hash = withScene(url.hash, sceneString);
  history.replaceState(null, '', url);
  return url.href;
}

/** Loads the scene from the link whenever the fragment changes (pasted links, back button). */
export function watchLocation(app) {
  addEventListener('hashchange', () => {
    const value = sceneFromLocation();
    if (value === null || app.crashed) return;
    if (value === app.guard((sim) => sim.scene_string()).value) return;
    Promise.resolve()
      .then(() => app.load(value, { rethrow: true }))
      .catch((error) => {
        if (app.crashed) return;
        showMessage(t('error.link_kept', { reason: messageOf(error) }));
        showSceneInLocation(app);
      });
  });
}

/**
 * Puts the link of what is on screen back in the address bar after a refused link (at boot or
 * pasted), so copying the address copies a link that works; the message names what was wrong.
 */
export function showSceneInLocation(app) {
  const result = app.guard((sim) => sim.scene_string());
  if (result.ok) writeSceneToLocation(result.value);
}

/**
 * Rewrites the fragment after every scene change (edits, parameters, seed, view options, loads),
 * at most once per WRITE_DELAY_MS.
 */
export function keepLocationInSync(app) {
  let timer = null;
  const write = () => {
    timer = null;
    if (app.crashed) return;
    const result = app.guard((sim) => sim.scene_string());
    if (result.ok && sceneFromLocation() !== result.value) writeSceneToLocation(result.value);
  };
  app.addEventListener('scene', () => {
    clearTimeout(timer);
    timer = setTimeout(write, WRITE_DELAY_MS);
  });
}
