// Exports of the current run: paths (CSV, JSON, Maya MEL, Blender Python, PedPy text), a JuPedSim
// script and SVG trails from the Sim's recording (each made by the core, as the CLI makes it), a
// PNG snapshot of the canvas, and a WebM video (MediaRecorder on the canvas stream) with a
// recording indicator. The recording's budget and any thinning are stated on screen.

import { messageOf, showMessage } from '../core/errors.js';
import { download } from '../core/download.js';
import { fileStem } from './share.js';
import { formatNumber, onLanguageChange, setAttr, setText, t } from '../core/i18n.js';
import { withDuration } from './webm-duration.js';
import { setupScormExport } from './export-scorm.js';

const $ = (id) => document.getElementById(id);

const MIB = 1024 * 1024;
/** How often the recording line refreshes while playing (ms, display only). */
const INFO_REFRESH_MS = 500;

const PATH_EXPORTS = {
  csv: { ext: 'csv', type: 'text/csv', make: (sim) => sim.export_paths_csv() },
  json: { ext: 'paths.json', type: 'application/json', make: (sim) => sim.export_paths_json() },
  mel: { ext: 'mel', type: 'text/plain', make: (sim, o) => sim.export_maya_mel(o.fps, o.scale) },
  py: { ext: 'py', type: 'text/x-python', make: (sim, o) => sim.export_blender_py(o.fps, o.scale) },
  svg: { ext: 'svg', type: 'image/svg+xml', make: (sim) => sim.export_trails_svg() },
  pedpy: { ext: 'pedpy.txt', type: 'text/plain', make: (sim) => sim.export_pedpy_text() },
  jupedsim: { ext: 'jupedsim.py', type: 'text/x-python', make: (sim) => sim.export_jupedsim_script() },
};

const ordinal = (n) => (n === 2 ? t('export.2nd') : n === 3 ? t('export.3rd') : t('export.nth', { n }));

/** One line about the recording, and the thinning note (null when not thinned). */
export function describeRecording(info) {
  const steps = info.last_step ?? 0;
  const line = t('export.recorded', {
    frames: formatNumber(info.frames),
    steps: formatNumber(steps),
    agents: formatNumber(info.agents),
    mib: Math.round(info.budget_bytes / MIB),
    capacity: formatNumber(info.capacity_steps),
  });
  const note = info.thinned > 0
    ? t('export.thinned', { mib: Math.round(info.budget_bytes / MIB), ordinal: ordinal(info.every) })
    : null;
  return { line, note };
}

export function setupExport(app, canvas, share = null) {
  const dialog = $('export-dialog');
  const status = $('export-status');
  const info = $('recording-info');
  const thinned = $('recording-thinned');

  const refreshInfo = () => {
    const result = app.guard((sim) => JSON.parse(sim.recording_json()));
    if (!result.ok) return;
    const { line, note } = describeRecording(result.value);
    if (info.textContent !== line) info.textContent = line;
    $('export-recording').textContent = line;
    thinned.hidden = note === null;
    if (note !== null && thinned.textContent !== note) thinned.textContent = note;
  };
  app.addEventListener('stepped', refreshInfo);
  app.addEventListener('scene', refreshInfo);
  setInterval(() => {
    if (app.playing && !app.crashed) refreshInfo();
  }, INFO_REFRESH_MS);
  refreshInfo();
  onLanguageChange(refreshInfo);

  const options = () => ({ fps: Number($('export-fps').value), scale: Number($('export-scale').value) });

  $('export').addEventListener('click', () => {
    refreshInfo();
    status.textContent = '';
    dialog.showModal();
  });

  for (const button of dialog.querySelectorAll('[data-export]')) {
    button.addEventListener('click', async () => {
      const kind = button.dataset.export;
      const stem = fileStem(app.scene);
      if (kind === 'png') {
        const steps = app.guard((sim) => sim.steps()).value ?? 0;
        const name = `${stem}-step-${steps}.png`;
        worldOnly(app, canvas).toBlob((blob) => {
          if (!blob) {
            showMessage(t('export.png_failed'));
            return;
          }
          download(name, blob);
          status.textContent = t('share.downloading', { name });
        }, 'image/png');
        return;
      }
      const spec = PATH_EXPORTS[kind];
      // Made by the simulation worker (it holds the recording).
      const result = await app.guard((sim) => spec.make(sim, options()));
      if (!result.ok) {
        status.textContent = t('export.not_exported', { reason: messageOf(result.error) });
        return;
      }
      const name = `${stem}.${spec.ext}`;
      download(name, result.value, spec.type);
      status.textContent = t('export.downloading_size', { name, kib: formatNumber(Math.ceil(result.value.length / 1024)) });
    });
  }

  setupVideo(app, canvas, status);
  setupScormExport(app, status, share);
}

/**
 * The world's part of the scene canvas as a canvas of its own: the PNG shows the scene, not the
 * grey letterbox the canvas has where its shape differs from the world's. The view (`scale`,
 * `offset_x`, `offset_y`: world px → canvas px) is the renderer's, read from the mirror.
 */
function worldOnly(app, canvas) {
  const view = app.guard((sim) => sim.view()).value;
  const { width = 0, height = 0 } = app.scene ?? {};
  if (!view || !(width > 0 && height > 0)) return canvas;
  const [scale, offsetX, offsetY] = view;
  const x = Math.max(0, Math.round(offsetX));
  const y = Math.max(0, Math.round(offsetY));
  const w = Math.min(canvas.width - x, Math.round(width * scale));
  const h = Math.min(canvas.height - y, Math.round(height * scale));
  if (w <= 0 || h <= 0) return canvas;
  const out = document.createElement('canvas');
  out.width = w;
  out.height = h;
  out.getContext('2d').drawImage(canvas, x, y, w, h, 0, 0, w, h);
  return out;
}

/** WebM capture of the canvas while the simulation runs, with the REC indicator over the canvas corner. */
function setupVideo(app, canvas, status) {
  const button = $('record-webm');
  const indicator = $('recording-indicator');
  const clock = $('recording-time');
  let recorder = null;
  let timer = null;

  const supported = typeof MediaRecorder !== 'undefined' && typeof canvas.captureStream === 'function';
  if (!supported) {
    button.disabled = true;
    setAttr(button, 'title', 'export.no_recorder');
    return;
  }
  const mimeType = ['video/webm;codecs=vp9', 'video/webm;codecs=vp8', 'video/webm']
    .find((t) => MediaRecorder.isTypeSupported(t));

  const stop = () => {
    if (recorder && recorder.state !== 'inactive') recorder.stop();
  };
  const start = () => {
    let stream;
    try {
      stream = canvas.captureStream(30);
      recorder = new MediaRecorder(stream, mimeType ? { mimeType } : undefined);
    } catch (error) {
      status.textContent = t('export.record_failed', { reason: messageOf(error) });
      return;
    }
    const chunks = [];
    const started = performance.now();
    recorder.addEventListener('dataavailable', (e) => {
      if (e.data.size > 0) chunks.push(e.data);
    });
    recorder.addEventListener('stop', async () => {
      const recordedMs = performance.now() - started;
      clearInterval(timer);
      for (const track of stream.getTracks()) track.stop();
      indicator.hidden = true;
      setText(button, 'export.record');
      button.classList.remove('recording');
      recorder = null;
      const name = `${fileStem(app.scene)}.webm`;
      // With its length written in (MediaRecorder leaves it out): players show it and can seek.
      const bytes = new Uint8Array(await new Blob(chunks).arrayBuffer());
      download(name, new Blob([withDuration(bytes, recordedMs)], { type: 'video/webm' }));
      status.textContent = t('share.downloading', { name });
      app.dispatchEvent(new Event('video-saved'));
    });
    recorder.start(250);
    indicator.hidden = false;
    setText(button, 'export.stop');
    button.classList.add('recording');
    clock.textContent = '0:00';
    timer = setInterval(() => {
      const s = Math.floor((performance.now() - started) / 1000);
      clock.textContent = `${Math.floor(s / 60)}:${String(s % 60).padStart(2, '0')}`;
    }, 250);
    if (!app.playing) app.setPlaying(true);
    // Close the dialog so the canvas being recorded is in view.
    $('export-dialog').close();
  };
  button.addEventListener('click', () => (recorder ? stop() : start()));
  // The indicator doubles as the stop button once the dialog is closed.
  setAttr(indicator, 'title', 'export.rec_title');
  indicator.style.cursor = 'pointer';
  indicator.addEventListener('click', stop);
  app.addEventListener('crash', stop);
}
