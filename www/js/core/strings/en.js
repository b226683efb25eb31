// English: the reference table. Every key here must exist in every other shipped table
// (tests/e2e/i18n.test.mjs). Keys: `<page or concern>.<thing>`; `{name}` is filled by t().
// Sections are grouped by concern so parallel work appends to its own block.
export default {
  // — language menu —
  'lang.label': 'Language',
};
