// The planner parameter form, built from the core's parameter table (`planners_json`): shared by
// the playground's panel and the compare page's panes. Imports nothing from page folders.

/** Shows a number the way its slider step suggests (0.05 → two decimals). */
export function formatValue(value, step) {
  if (typeof value !== 'number') return String(value);
  const decimals = step > 0 && step < 1 ? Math.min(4, Math.ceil(-Math.log10(step) - 1e-9)) : 0;
  return value.toFixed(decimals);
}
