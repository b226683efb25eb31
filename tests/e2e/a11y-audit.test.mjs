// Automated accessibility audit (issue #15 item 1): axe-core (npm, node_modules/axe-core) finds no
// serious or critical violation on the playground (also with the Share and Export dialogs open
// and the keyboard cursor showing), the embed page, compare, tune, the optimizer lab and the
// course-notes example. The scene canvases are in the accessibility tree with a role and a name,
// and the playground's, compare's and every <flock-path>'s live description is polite, visually
// hidden and says what the scene and the run hold (compare: each pane's planner and metrics).

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertNoUnexpectedErrors, openPath, seriousViolations } from './helpers.mjs';

const allElementsRunning = () => {
  const els = [...document.querySelectorAll('flock-path')];
  return els.length > 0 && els.every((el) => el.sim && el.steps > 0);
};

const PAGES = [
  { path: 'embed.html', ready: () => window.flockpathEmbed !== undefined },
  {
    path: 'compare.html',
    ready: () => window.flockpathCompare !== undefined && document.querySelectorAll('.pane canvas').length === 2,
  },
  { path: 'tune.html', ready: () => window.flocktune !== undefined },
  { path: 'lab.html', ready: () => window.flockpathLab !== undefined },
  { path: 'examples/course-notes.html', ready: allElementsRunning },
  { path: 'activities.html', ready: () => window.flockpathActivities !== undefined },
];

test('axe: no serious or critical violation on the playground, its dialogs and its keyboard cursor', async () => {
  const { page, errors, close } = await openPath('index.html', { ready: () => window.flockpath !== undefined });
  try {
    assert.deepEqual(await seriousViolations(page), [], 'index.html');

    // The canvas: an image with a name, and a focusable editor with a name, both described.
    assert.equal(await page.getByRole('img', { name: 'Simulated crowd' }).count(), 1);
    const editor = page.getByRole('application', { name: /Scene editor/ });
    assert.equal(await editor.count(), 1);
    assert.equal(await page.getAttribute('#overlay-canvas', 'tabindex'), '0');
    const description = await page.evaluate(() => {
      const el = document.getElementById('scene-description');
      const box = el.getBoundingClientRect();
      const scene = window.flockpath.scene();
      return { live: el.getAttribute('aria-live'), box: [box.width, box.height], text: el.textContent, obstacles: scene.obstacles.length };
    });
    assert.equal(description.live, 'polite');
    assert.ok(description.box[0] <= 1 && description.box[1] <= 1, `visually hidden: ${description.box}`);
    assert.match(description.text, new RegExp(`${description.obstacles} obstacles?`), description.text);
    assert.match(description.text, /Step [\d,]+, (playing|paused)\./, description.text);

    // Keyboard focus on the canvas (its cursor showing).
    await page.focus('#overlay-canvas');
    await page.keyboard.press('ArrowRight');
    assert.match(await page.textContent('#canvas-cursor'), /Cursor at/);
    assert.deepEqual(await seriousViolations(page), [], 'index.html with the keyboard cursor');

    // The projector theme (the top bar's toggle) passes too.
    await page.click('#theme-toggle');
    await page.waitForFunction(() => document.documentElement.dataset.theme === 'projector');
    assert.deepEqual(await seriousViolations(page), [], 'index.html in the projector theme');
    await page.click('#theme-toggle');

    for (const [button, dialog] of [['#share', '#share-dialog'], ['#export', '#export-dialog'], ['#help', '#help-dialog'], ['#new-scene', '#new-scene-dialog']]) {
      await page.click(button);
      await page.waitForSelector(`${dialog}[open]`);
      assert.deepEqual(await seriousViolations(page), [], `index.html with ${dialog} open`);
      await page.keyboard.press('Escape');
      await page.waitForSelector(`${dialog}:not([open])`, { state: 'attached' });
    }
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

for (const spec of PAGES) {
  test(`axe: no serious or critical violation on ${spec.path}`, async () => {
    const { page, errors, close } = await openPath(spec.path, { ready: spec.ready });
    try {
      assert.deepEqual(await seriousViolations(page), [], spec.path);
      assertNoUnexpectedErrors(errors);
    } finally {
      await close();
    }
  });
}

test('the description speaks the page language (?lang=zh)', async () => {
  const { page, errors, close } = await openPath('index.html?lang=zh', { ready: () => window.flockpath !== undefined });
  try {
    await page.evaluate(() => window.flockpath.pause());
    const obstacles = await page.evaluate(async () => (await window.flockpath.settled(), window.flockpath.scene().obstacles.length));
    await page.waitForFunction(() => document.getElementById('scene-description').textContent.includes('已暂停'));
    const text = await page.textContent('#scene-description');
    assert.ok(text.includes(`${obstacles} 个障碍物`), text);
    assert.match(text, /第 [\d,]+ 步，已暂停。/, text);
    assertNoUnexpectedErrors(errors);
  } finally {
    await close();
  }
});

test('compare: a polite, visually hidden description names each pane and matches its metrics', async () => {
  const ready = () => window.flockpathCompare !== undefined && document.querySelectorAll('.pane canvas').length === 2;
  for (const lang of ['en', 'zh']) {
    const { page, errors, close } = await openPath(`compare.html?lang=${lang}`, { ready });
    try {
      await page.evaluate(async () => {
        await window.flockpathCompare.pause();
        await window.flockpathCompare.reset();
        await window.flockpathCompare.step(600);
      });
      const steps = await page.evaluate(async () => (await window.flockpathCompare.settled(), window.flockpathCompare.steps()));
      assert.deepEqual([...new Set(steps)], [600]);
      // Rewritten at most every few seconds: wait for the words of step 600 (arrivals and collisions by then).
      const stepWords = lang === 'en' ? 'Step 600, paused.' : '第 600 步，已暂停。';
      await page.waitForFunction((words) => {
        const ps = [...document.querySelectorAll('#compare-description p[data-pane]')];
        return ps.length === 2 && ps.every((p) => p.textContent.includes(words));
      }, stepWords, { timeout: 20_000 });
      const facts = await page.evaluate(() => {
        const el = document.getElementById('compare-description');
        const box = el.getBoundingClientRect();
        return {
          live: el.getAttribute('aria-live'),
          box: [box.width, box.height],
          scene: el.querySelector('p:not([data-pane])').textContent,
          paragraphs: [...el.querySelectorAll('p[data-pane]')].map((p) => ({ pane: p.dataset.pane, text: p.textContent })),
          panes: window.flockpathCompare.panes(),
          metrics: window.flockpathCompare.metrics(),
          planners: [...document.querySelectorAll('.pane .pane-label')].map((n) => n.textContent),
        };
      });
      assert.equal(facts.live, 'polite');
      assert.ok(facts.box[0] <= 1 && facts.box[1] <= 1, `visually hidden: ${facts.box}`);
      assert.match(facts.scene, lang === 'en' ? /^2 panes run this scene side by side/ : /^2 个窗格并排运行此场景/, facts.scene);
      assert.equal(facts.paragraphs.length, facts.panes.length);
      assert.notEqual(facts.planners[0], facts.planners[1], 'the two panes differ in planner');
      assert.ok(facts.metrics.some((m) => m.arrived_share > 0 || m.collisions_agent_agent > 0), 'figures worth matching');
      facts.paragraphs.forEach((p, i) => {
        const n = (key) => facts.metrics[i][key].toLocaleString('en-US');
        const m = facts.metrics[i];
        const percent = `${Math.round(m.arrived_share * 100)}%`;
        assert.equal(p.pane, facts.panes[i].pane);
        // The pane's name and its planner (the label the pane's header shows, in the page's language).
        const head = lang === 'en' ? `Pane ${p.pane}, ${facts.planners[i]}:` : `窗格 ${p.pane}，${facts.planners[i]}：`;
        assert.ok(p.text.startsWith(head), `${head} | ${p.text}`);
        const expected = lang === 'en'
          ? [`${percent} of ${n('agents')} agent`, `${n('collisions_last_step')} pair`, `${n('collisions_agent_agent')} in all`,
            `${n('penetrations_agent_obstacle')} obstacle penetration`, m.stuck_agents === 0 ? 'No agent stuck.' : `${n('stuck_agents')} agent`]
          : [percent, n('agents'), n('collisions_agent_agent')];
        for (const words of expected) assert.ok(p.text.includes(words), `pane ${p.pane} says “${words}”: ${p.text}`);
      });
      assertNoUnexpectedErrors(errors);
    } finally {
      await close();
    }
  }
});

test('<flock-path> (embed.html, course notes): the canvas has a role and a name and a live description', async () => {
  for (const [file, ready] of [['embed.html', () => window.flockpathEmbed !== undefined], ['examples/course-notes.html', allElementsRunning]]) {
    const { page, errors, close } = await openPath(file, { ready });
    try {
      const count = await page.evaluate(() => document.querySelectorAll('flock-path').length);
      assert.equal(await page.getByRole('img', { name: 'Simulated crowd' }).count(), count, `${file}: every element's canvas`);
      // Each element: its description (in its shadow root) names its own scene's obstacles and
      // step (paused, so the step it says stays the element's).
      await page.evaluate(() => document.querySelectorAll('flock-path').forEach((el) => el.pause()));
      for (let i = 0; i < count; i += 1) {
        await page.waitForFunction((index) => {
          const el = document.querySelectorAll('flock-path')[index];
          const text = el.shadowRoot.querySelector('.scene-description')?.textContent ?? '';
          return text.includes(`Step ${el.steps.toLocaleString('en-US')},`);
        }, i);
        const facts = await page.evaluate((index) => {
          const el = document.querySelectorAll('flock-path')[index];
          const region = el.shadowRoot.querySelector('.scene-description');
          const canvas = el.shadowRoot.querySelector('canvas');
          return {
            live: region.getAttribute('aria-live'),
            describedBy: canvas.getAttribute('aria-describedby') === region.id,
            text: region.textContent,
            obstacles: el.scene().obstacles.length,
            groups: el.scene().groups.length,
            size: [region.getBoundingClientRect().width, region.getBoundingClientRect().height],
          };
        }, i);
        assert.equal(facts.live, 'polite');
        assert.ok(facts.describedBy, 'the canvas is described by it');
        assert.ok(facts.size[0] <= 1 && facts.size[1] <= 1, `visually hidden: ${facts.size}`);
        const obstacles = facts.obstacles === 0 ? /No obstacles\./ : new RegExp(`${facts.obstacles} obstacles?:`);
        assert.match(facts.text, obstacles, facts.text);
        assert.match(facts.text, facts.groups === 1 ? /1 group:/ : new RegExp(`${facts.groups} groups:`), facts.text);
        assert.match(facts.text, /of [\d,]+ agents? arrived\./, facts.text);
      }
      assertNoUnexpectedErrors(errors);
    } finally {
      await close();
    }
  }
});
