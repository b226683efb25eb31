// Export → "LMS package (SCORM 1.2)": the activity on screen as a zip an LMS imports. The page
// fetches its own files (the service worker's precache list says which exist; the core picks
// those a package takes), and the core writes the manifest, the launch page and the zip
// (src/package/scorm.rs, the same bytes as `flockpath scorm`). This module only fetches and
// downloads.

import { messageOf } from '../core/errors.js';
import { download } from '../core/download.js';
import { formatNumber, t } from '../core/i18n.js';
import { fileStem } from './share.js';

/** The page folder (two up from js/play/). */
const FOLDER = new URL('../../', import.meta.url);

/** The files of this build (www/pkg/precache.js, written by scripts/build-wasm.sh). */
async function buildFiles() {
  await import(new URL('pkg/precache.js', FOLDER).href);
  const files = self.FLOCKPATH_PRECACHE?.files;
  if (!Array.isArray(files)) throw new Error('pkg/precache.js lists no files: run bash scripts/build-wasm.sh');
  return files;
}

/** The package's bytes for the link `link` (`s=…&lock=…`), made by the core. */
export async function scormPackage(module, link) {
  // A link with nothing to grade is refused before 3 MB of files are fetched.
  module.scorm_check_link(link);
  const wanted = JSON.parse(module.scorm_page_files(JSON.stringify(await buildFiles())));
  const parts = await Promise.all(
    wanted.map(async (name) => {
      const response = await fetch(new URL(name, FOLDER));
      if (!response.ok) throw new Error(`${name}: HTTP ${response.status}`);
      return new Uint8Array(await response.arrayBuffer());
    }),
  );
  const all = new Uint8Array(parts.reduce((n, p) => n + p.length, 0));
  let at = 0;
  for (const part of parts) {
    all.set(part, at);
    at += part.length;
  }
  const listed = wanted.map((name, i) => [name, parts[i].length]);
  return module.scorm_package_zip(link, JSON.stringify(listed), all);
}

/**
 * Wires the Export dialog's "LMS package (SCORM 1.2)" button. The package carries the Share
 * dialog's "For students" options (`share.classroomOptions()`: they start as the page's own).
 */
export function setupScormExport(app, status, share = null) {
  const button = document.getElementById('export-scorm');
  if (!button) return;
  button.addEventListener('click', async () => {
    button.disabled = true;
    status.textContent = t('export.scorm_building');
    try {
      const scene = app.guard((sim) => sim.scene_string(), { rethrow: true }).value;
      const options = share ? share.classroomOptions().fragment : app.classroom?.fragment;
      const link = `s=${scene}${options ? `&${options}` : ''}`;
      const zip = await scormPackage(app.module, link);
      const name = `${fileStem(app.scene)}-scorm.zip`;
      download(name, new Blob([zip], { type: 'application/zip' }));
      status.textContent = t('export.downloading_size', { name, kib: formatNumber(Math.ceil(zip.length / 1024)) });
    } catch (error) {
      status.textContent = t('export.not_exported', { reason: messageOf(error) });
    } finally {
      button.disabled = false;
    }
  });
}
