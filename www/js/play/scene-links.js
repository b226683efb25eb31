// The playground's header links to the other pages that take a scene ("Compare planners",
// "Tune…"): each `a[data-scene-link]` opens its page with the current scene in the fragment
// (`<page>#s=<scene>`), kept up to date as the scene changes.

export function setupSceneLinks(app) {
  const links = [...document.querySelectorAll('a[data-scene-link]')];
  if (links.length === 0) return;
  const update = () => {
    const result = app.guard((sim) => sim.scene_string());
    if (!result.ok) return;
    for (const link of links) link.href = `${link.dataset.sceneLink}#s=${result.value}`;
  };
  app.addEventListener('scene', update);
  update();
}
