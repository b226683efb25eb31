// The shell's layers (README "Structure"): www/js/core/ is shared by every page and by
// flock-path.js and imports only core/; a page folder (play/, compare/, lab/, tune/, embed/,
// bench/, …) imports core/, its own folder and flock-path.js (the element, at its public URL),
// never another page's folder. Read from the sources' import lines; no browser needed.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readdir, readFile } from 'node:fs/promises';
import path from 'node:path';
import { ROOT } from './helpers.mjs';

const JS = path.join(ROOT, 'www', 'js');

async function sources(dir = JS) {
  const out = [];
  for (const entry of await readdir(dir, { withFileTypes: true })) {
    const full = path.join(dir, entry.name);
    if (entry.isDirectory()) out.push(...(await sources(full)));
    else if (entry.name.endsWith('.js')) out.push(full);
  }
  return out;
}

/** Every static (`import … from '…'`, `import '…'`), re-export and dynamic import's target. */
export function importsOf(text) {
  const found = [];
  const patterns = [/^\s*import\s[^'"]*?from\s*['"]([^'"]+)['"]/gm, /^\s*import\s*['"]([^'"]+)['"]/gm,
    /^\s*export\s[^'"]*?from\s*['"]([^'"]+)['"]/gm, /\bimport\(\s*['"]([^'"]+)['"]\s*\)/g,
    /new URL\(\s*['"](\.{1,2}\/[^'"]+\.js)['"]\s*,\s*import\.meta\.url\)/g];
  for (const pattern of patterns) for (const m of text.matchAll(pattern)) found.push(m[1]);
  return found;
}

/** The layer of a file under www/js: 'core', a page folder's name, or 'element' (flock-path.js). */
function layerOf(file) {
  const rel = path.relative(JS, file);
  if (rel.startsWith('..')) return rel.startsWith(path.join('..', 'pkg')) ? 'pkg' : 'outside';
  const parts = rel.split(path.sep);
  if (parts.length === 1) return parts[0] === 'flock-path.js' ? 'element' : `root:${parts[0]}`;
  return parts[0];
}

/** Why `from` may not import `to` (layers), or null when it may. */
function violation(from, to) {
  if (to === 'pkg') return null;
  if (from === 'core') return to === 'core' ? null : 'core imports only core/';
  if (from === 'element') return to === 'core' ? null : 'flock-path.js imports only core/';
  if (to === 'core' || to === from || to === 'element') return null;
  return `a page folder imports only core/, its own folder and flock-path.js, not ${to}/`;
}

async function edges() {
  const list = [];
  for (const file of await sources()) {
    const text = await readFile(file, 'utf8');
    for (const spec of importsOf(text)) {
      if (!spec.startsWith('.')) {
        list.push({ file, spec, target: null });
        continue;
      }
      list.push({ file, spec, target: path.resolve(path.dirname(file), spec) });
    }
  }
  return list;
}

test('the import scanner finds every kind of import line', () => {
  const text = [
    "import { a } from '../core/a.js';",
    "import b from './b.js';",
    "import '../flock-path.js';",
    "export { c } from './c.js';",
    "const m = await import('../../pkg/flockpath.js');",
    "new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });",
    "import {\n  d,\n  e,\n} from '../tune/d.js';",
  ].join('\n');
  assert.deepEqual(importsOf(text).sort(), [
    '../../pkg/flockpath.js', '../core/a.js', '../flock-path.js', '../tune/d.js', './b.js', './c.js', './worker.js',
  ].sort());
});

test('the layer rule refuses page → other page and core → page', () => {
  assert.match(violation('compare', 'play'), /not play\//);
  assert.match(violation('core', 'play'), /core imports only core/);
  assert.match(violation('core', 'element'), /core imports only core/);
  assert.match(violation('element', 'embed'), /flock-path\.js imports only core/);
  assert.equal(violation('embed', 'element'), null);
  assert.equal(violation('play', 'core'), null);
  assert.equal(violation('lab', 'lab'), null);
});

test('www/js: no page imports another page, core and flock-path.js import only core/', async () => {
  const all = await edges();
  assert.ok(all.length > 50, `found ${all.length} imports: the scanner reads the sources`);
  const problems = [];
  for (const { file, spec, target } of all) {
    const rel = path.relative(ROOT, file);
    if (target === null) {
      problems.push(`${rel} imports ${spec}: only relative imports (the folder works offline, under any sub-path)`);
      continue;
    }
    const from = layerOf(file);
    const to = layerOf(target);
    if (to === 'outside' || to.startsWith('root:')) {
      problems.push(`${rel} imports ${spec}: outside core/, the page folders and flock-path.js`);
      continue;
    }
    const why = violation(from, to);
    if (why) problems.push(`${rel} imports ${spec}: ${why}`);
  }
  assert.deepEqual(problems, []);
});

test('every page folder uses the core (the shared modules are really shared)', async () => {
  const all = await edges();
  const pages = new Set((await readdir(JS, { withFileTypes: true })).filter((e) => e.isDirectory() && e.name !== 'core').map((e) => e.name));
  for (const page of pages) {
    const usesCore = all.some(({ file, target }) => layerOf(file) === page && target && layerOf(target) === 'core');
    const usesElement = all.some(({ file, target }) => layerOf(file) === page && target && layerOf(target) === 'element');
    // A page that is only <flock-path> (embed/) reaches the core through the element.
    assert.ok(usesCore || usesElement, `${page}/ imports nothing from core/`);
  }
});
