// 简体中文. Same keys as en.js (tests/e2e/i18n.test.mjs fails on a missing one).
export default {
  // — language menu —
  'lang.label': '语言',
};
