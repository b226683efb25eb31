// The scene in the address bar: `index.html#s=<fragment>`. Reading happens at boot and on
// `hashchange`; writing uses replaceState so sharing does not add history entries.

import { messageOf, showMessage } from './errors.js';

/** The `s=` value of the current location's fragment, or null when there is none. */
export function sceneFromLocation(hash = location.hash) {
  const fragment = hash.startsWith('#') ? hash.slice(1) : hash;
  for (const part of fragment.split('&')) {
    if (part.startsWith('s=')) {
      const value = part.slice(2);
      try {
        return decodeURIComponent(value);
      } catch {
        return value;
      }
    }
  }
  return null;
}

/** Puts a scene string in the address bar; returns the full URL to share. */
export function writeSceneToLocation(sceneString) {
  const url = new URL(location.href);
  url.hash = `s=${sceneString}`;
  history.replaceState(null, '', url);
  return url.href;
}

/** Loads the scene from the link whenever the fragment changes (pasted links, back button). */
export function watchLocation(app) {
  addEventListener('hashchange', () => {
    const value = sceneFromLocation();
    if (value === null || app.crashed) return;
    if (value === app.guard((sim) => sim.scene_string()).value) return;
    try {
      app.load(value, { rethrow: true });
    } catch (error) {
      if (!app.crashed) {
        showMessage(`The scene in the link could not be loaded: ${messageOf(error)}. The previous scene keeps running.`);
      }
    }
  });
}
