// The playground's "Compare planners" link: opens the current scene in the compare page
// (`compare.html#s=<scene>`), where it runs side by side with other planners.

const STYLE = `
a.button { display: inline-flex; align-items: center; padding: 0.45rem 0.8rem; border: 1px solid #4a5a70;
  border-radius: 8px; min-height: 2.4rem; color: #fff; text-decoration: none; white-space: nowrap; }
a.button:hover { border-color: #7fb0ff; }
`;

export function setupCompareLink(app) {
  const link = document.getElementById('compare-link');
  if (!link) return;
  const style = document.createElement('style');
  style.textContent = STYLE;
  document.head.append(style);
  const update = () => {
    const result = app.guard((sim) => sim.scene_string());
    if (result.ok) link.href = `compare.html#s=${result.value}`;
  };
  app.addEventListener('scene', update);
  update();
}
