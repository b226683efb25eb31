// The scene check's notice that a goal is too small for the groups heading for it (issue 23):
// "Goal 1 holds about 13 bodies of radius 4 px; group “flock” has 60: 47 will wait outside."
// A polite status line in the Metrics card, not an error banner: the scene runs as it is, and
// the reader knows before the run why some agents end outside the goal. The core decides
// (`capacity_notices_json()`, typed fields); this only words the fields in the page's language.

import { noticeText } from '../core/capacity-words.js';
import { onLanguageChange } from '../core/i18n.js';

/**
 * Shows the notices of the current scene in `#capacity-notice`, refreshed when a scene is loaded
 * or edited and when the language changes; hidden while every crowd fits its goal.
 */
export function setupCapacityNotice(app) {
  const box = document.getElementById('capacity-notice');
  let notices = [];
  const show = () => {
    box.replaceChildren(...notices.map((n) => Object.assign(document.createElement('p'), { textContent: noticeText(n) })));
    box.hidden = notices.length === 0;
  };
  const refresh = () => {
    const result = app.guard((sim) => JSON.parse(sim.capacity_notices_json()));
    notices = result.ok ? result.value : [];
    show();
  };
  app.addEventListener('scene', refresh);
  onLanguageChange(show);
  refresh();
}
