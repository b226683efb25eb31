// The scene check's notice that a goal is too small for the groups heading for it (issue 23):
// "Goal 1 holds about 13 bodies of radius 4 px; group “flock” has 60: 47 will wait outside."
// A polite status line in the Metrics card, not an error banner: the scene runs as it is, and
// the reader knows before the run why some agents end outside the goal. The core decides
// (`capacity_notices_json()`, typed fields); this only words the fields in the page's language.

import { formatNumber, onLanguageChange, t } from '../core/i18n.js';

/** A group in the reader's words: `group “flock”`, or `group 2` for an unnamed one. */
function groupWords(group) {
  return group.name
    ? t('capacity.group_named', { name: group.name })
    : t('capacity.group_n', { n: formatNumber(group.group + 1) });
}

/** One notice as a sentence. Goals are counted from 1, as the group panel's goal picker does. */
export function noticeText(notice) {
  const common = {
    goal: formatNumber(notice.goal + 1),
    capacity: formatNumber(notice.capacity),
    radius: formatNumber(notice.body_radius),
    agents: formatNumber(notice.agents),
    waiting: formatNumber(notice.waiting),
  };
  if (notice.groups.length === 1) {
    return t('capacity.one_group', { ...common, group: groupWords(notice.groups[0]) });
  }
  const groups = notice.groups
    .map((g) => t('capacity.group_count', { group: groupWords(g), count: formatNumber(g.count) }))
    .join(t('capacity.list_join'));
  return t('capacity.groups', { ...common, groups });
}

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
