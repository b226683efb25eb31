// The capacity notice in the reader's words (issue 23): "Goal 1 holds about 13 bodies of radius
// 4 px; group “flock” has 60: 47 will wait outside." The core decides which goals are too small
// (`capacity_notices_json()`, typed fields); this words the fields in the page's language, for
// the playground's Metrics card and the <flock-path> element alike.

import { formatNumber, t } from './i18n.js';

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
