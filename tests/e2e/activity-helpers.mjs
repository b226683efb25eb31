// Shared by the activity tests: a scene link with an activity, made through the page API.

/** The link (fragment value) of preset `preset` with `activity` added, made by the page's API. */
export async function linkWithActivity(page, activity, preset = 'pillars') {
  return page.evaluate(
    async ([a, name]) => {
      await window.flockpath.load(name);
      await window.flockpath.load({ ...window.flockpath.scene(), activity: a });
      return window.flockpath.sceneString();
    },
    [activity, preset],
  );
}
