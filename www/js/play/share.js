// The share dialog: the link, an iframe snippet (embed.html), a `<flock-path>` snippet, scene JSON
// download, and loading a scene JSON by file picker or by dropping it on the canvas.

import { download } from '../core/download.js';
import { messageOf, showMessage } from '../core/errors.js';
import { shareUrl, writeSceneToLocation } from '../core/url.js';
import { setupShareLock } from './share-lock.js';
import { setupShareActivity } from './share-activity.js';
import { t } from '../core/i18n.js';

const $ = (id) => document.getElementById(id);

/** A file name from the scene's name: letters, digits and dashes. */
export function fileStem(scene) {
  const stem = String(scene.name ?? '').toLowerCase().replace(/[^a-z0-9]+/g, '-').replace(/^-|-$/g, '');
  return stem || 'scene';
}

/** HTML-attribute escaping for the snippets. */
const attr = (text) => text.replace(/&/g, '&amp;').replace(/"/g, '&quot;').replace(/</g, '&lt;');

/**
 * The `<flock-path>` snippet's script runs this when the module cannot load (blocked by CORS or a
 * Content-Security-Policy, 404, offline): no flockpath code runs then, so the snippet itself turns
 * its fallback text ("Loading…", shown until the element upgrades) into the reason, in the
 * language the snippet was made in.
 */
function moduleErrorHandler() {
  const quote = (text) => `'${text.replace(/\\/g, '\\\\').replace(/'/g, "\\'")}'`;
  const [before, after = ''] = t('share.snippet_module_error').split('{url}');
  return (
    "document.querySelectorAll('flock-path:not(:defined) [data-flockpath-status]').forEach((p) => " +
    `{ p.textContent = ${quote(before)} + this.src + ${quote(after)}; })`
  );
}

/** Height of the embed page's control bar on one line (px; `<flock-path controls>`). */
const EMBED_BAR_PX = 38;

/**
 * The snippets for the current scene string (absolute URLs: they are pasted into other sites).
 * `classroom`: the teacher's options from share-lock.js, `{fragment, attributes}`.
 */
export function snippets(sceneString, { autoplay = true, page = location.href, classroom = null, world = null } = {}) {
  const options = classroom?.fragment ? `&${classroom.fragment}` : '';
  const link = shareUrl(sceneString, page) + options;
  const embed = new URL('embed.html', page);
  embed.hash = `s=${sceneString}${autoplay ? '&autoplay=1' : ''}${options}`;
  const module = new URL('js/flock-path.js', page);
  // The frame keeps the world's aspect ratio at any width up to 720 px, plus the embed's control
  // bar (a fixed height: padding in % of the width plus px), so a narrow column shows no grey
  // bands above and below the world as a fixed 720×480 frame squeezed to 100% width did.
  const aspect = world && world.width > 0 && world.height > 0 ? (100 * world.height) / world.width : (100 * 2) / 3;
  const iframe =
    `<div style="max-width:720px"><div style="position:relative;padding-top:calc(${aspect.toFixed(3)}% + ${EMBED_BAR_PX}px)">` +
    `<iframe src="${attr(embed.href)}" style="position:absolute;inset:0;width:100%;height:100%;border:0" ` +
    `title="${attr(t('share.snippet_iframe_title'))}" allowfullscreen loading="lazy"></iframe></div></div>`;
  // The element's children are fallback content: shown until the module upgrades it (then its
  // shadow DOM replaces them), and all a reader sees when scripts do not run at all. Inline
  // elements only: a Markdown tool that wraps the element in <p> would end it at a child <p>.
  const component =
    `<script type="module" src="${attr(module.href)}" onerror="${attr(moduleErrorHandler())}"></script>\n` +
    `<flock-path scene="${attr(sceneString)}"${autoplay ? ' autoplay' : ''}${classroom?.attributes ?? ' controls'} height="400px">\n` +
    `  <span data-flockpath-status>${attr(t('share.snippet_loading'))}</span>\n` +
    `  <a href="${attr(link)}">${attr(t('share.snippet_open'))}</a>\n` +
    '</flock-path>';
  return { link, iframe, component };
}

async function copy(text, status, what) {
  try {
    await navigator.clipboard.writeText(text);
    status.textContent = t('share.copied', { what });
  } catch {
    status.textContent = t('share.copy_refused', { what });
  }
}

/** Reads a dropped or picked file and loads it as a scene (undoable; errors go to the banner). */
async function loadFile(app, file) {
  let text;
  try {
    text = await file.text();
  } catch (error) {
    showMessage(t('share.file_unreadable', { name: file.name, reason: messageOf(error) }));
    return false;
  }
  const result = await app.load(text);
  if (!result.ok) showMessage(t('share.file_refused', { name: file.name, reason: messageOf(result.error) }));
  return result.ok;
}

export function setupShare(app) {
  const dialog = $('share-dialog');
  const status = $('share-status');
  const autoplay = $('share-autoplay');
  const lock = setupShareLock(app, () => fill());
  const fill = () => {
    const result = app.guard((sim) => sim.scene_string());
    if (!result.ok) return null;
    const world = { width: app.scene.width, height: app.scene.height };
    const s = snippets(result.value, { autoplay: autoplay.checked, classroom: lock.options(), world });
    $('share-link').value = s.link;
    $('share-link-size').textContent = t('share.link_size', { n: s.link.length });
    $('share-iframe').value = s.iframe;
    $('share-component').value = s.component;
    return result.value;
  };
  $('share').addEventListener('click', () => {
    const value = fill();
    if (value === null) return;
    writeSceneToLocation(value);
    status.textContent = '';
    dialog.showModal();
    $('share-link').select();
  });
  autoplay.addEventListener('change', fill);
  app.addEventListener('scene', () => {
    if (dialog.open) fill();
  });
  $('copy-link').addEventListener('click', () => copy($('share-link').value, status, t('share.what_link')));
  $('copy-iframe').addEventListener('click', () => copy($('share-iframe').value, status, t('share.what_iframe')));
  $('copy-component').addEventListener('click', () => copy($('share-component').value, status, t('share.what_component')));
  $('download-scene').addEventListener('click', () => {
    const result = app.guard((sim) => sim.scene_json());
    if (!result.ok) return;
    const name = `${fileStem(app.scene)}.json`;
    download(name, `${result.value}\n`, 'application/json');
    status.textContent = t('share.downloading', { name });
  });
  // The activity form (prompt, prediction, goal), above the status line.
  setupShareActivity(app);
  const picker = $('scene-file');
  $('open-scene').addEventListener('click', () => picker.click());
  picker.addEventListener('change', async () => {
    const file = picker.files?.[0];
    picker.value = '';
    if (file && (await loadFile(app, file))) {
      status.textContent = t('share.loaded', { name: file.name });
      dialog.close();
    }
  });

  // Drag and drop a scene file onto the canvas.
  const stage = $('stage');
  const hint = $('drop-hint');
  const hasFiles = (e) => [...(e.dataTransfer?.types ?? [])].includes('Files');
  stage.addEventListener('dragover', (e) => {
    if (!hasFiles(e)) return;
    e.preventDefault();
    e.dataTransfer.dropEffect = 'copy';
    hint.hidden = false;
  });
  stage.addEventListener('dragleave', (e) => {
    if (!stage.contains(e.relatedTarget)) hint.hidden = true;
  });
  stage.addEventListener('drop', async (e) => {
    if (!hasFiles(e)) return;
    e.preventDefault();
    hint.hidden = true;
    const file = e.dataTransfer.files[0];
    if (file) await loadFile(app, file);
  });
  // The Export dialog's LMS package carries the same "For students" options as the link.
  return { classroomOptions: () => lock.options() };
}
