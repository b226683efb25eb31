// Presentation mode (issue 27 §2): for a class watching a projector. The Present button (or P)
// makes the stage fill the screen: the Fullscreen API where the browser allows it, else (a
// refused request, a headless browser, an iframe without allowfullscreen) a fixed layer over the
// whole viewport. Over the canvas: the metric headline (arrived share, collisions) in large type,
// and a bar of large Play/Pause, Step, Reset, Speed and zoom controls that fades after
// IDLE_MS without pointer movement and comes back on movement, a key or focus inside it.
// Esc leaves, as does the browser leaving fullscreen (its own Esc, F11). The rest of the page is
// inert meanwhile, so Tab and a screen reader stay within what shows.

import { onPage } from '../core/keys.js';
import { formatNumber, onLanguageChange, setAttr, setText, t } from '../core/i18n.js';
import { KEY_FACTOR } from './zoom.js';

const $ = (id) => document.getElementById(id);
/** The controls fade after this long without pointer movement (ms). */
export const IDLE_MS = 2000;
/** How often the headline's numbers may change (ms). */
const HEADLINE_MS = 250;

const el = (tag, props = {}, children = []) => {
  const node = Object.assign(document.createElement(tag), props);
  node.append(...children);
  return node;
};

/** A bar button labelled by a strings key (text, and a title saying its key). */
function barButton(id, key, titleKey) {
  const button = el('button', { type: 'button', id });
  setText(button, key);
  if (titleKey) setAttr(button, 'title', titleKey);
  return button;
}

/** Wires the Present button, the P key and the presentation layer over `stage`. */
export function setupPresent(app, stage) {
  const present = $('present');
  if (!present || !stage) return null;

  const arrived = el('strong', { className: 'present-figure', id: 'present-arrived' });
  const collisions = el('strong', { className: 'present-figure', id: 'present-collisions' });
  const arrivedWord = setText(el('span', { className: 'present-word' }), 'present.arrived');
  const collisionsWord = setText(el('span', { className: 'present-word' }), 'present.collisions');
  const headline = el('div', { className: 'present-headline', id: 'present-headline' }, [
    el('p', {}, [arrived, ' ', arrivedWord]),
    el('p', {}, [collisions, ' ', collisionsWord]),
  ]);
  setAttr(headline, 'aria-label', 'present.headline');
  headline.setAttribute('role', 'group');

  const play = barButton('present-play', 'playback.play', 'playback.play_title');
  const step = barButton('present-step', 'playback.step', 'playback.step_title');
  const reset = barButton('present-reset', 'playback.reset', 'playback.reset_title');
  const speed = el('input', { type: 'range', id: 'present-speed' });
  const speedValue = el('output', { id: 'present-speed-value', htmlFor: 'present-speed' });
  const speedLabel = el('label', { className: 'present-speed' }, [setText(el('span'), 'playback.speed'), speed, speedValue]);
  const zoomOut = barButton('present-zoom-out', 'zoom.out', 'zoom.out_title');
  const fit = barButton('present-fit', 'zoom.fit', 'zoom.fit_title');
  const zoomIn = barButton('present-zoom-in', 'zoom.in', 'zoom.in_title');
  const exit = barButton('present-exit', 'present.exit', 'present.exit_title');
  const bar = el('div', { className: 'present-bar', id: 'present-bar' }, [play, step, reset, speedLabel, zoomOut, fit, zoomIn, exit]);
  bar.setAttribute('role', 'toolbar');
  setAttr(bar, 'aria-label', 'present.toolbar');
  const layer = el('div', { className: 'present-layer', id: 'present-layer', hidden: true }, [headline, bar]);
  stage.append(layer);

  // The bar's buttons press the page's own (the same effects, locks and all).
  const mainSpeed = $('spf');
  play.addEventListener('click', () => $('play').click());
  step.addEventListener('click', () => $('step').click());
  reset.addEventListener('click', () => $('reset').click());
  zoomOut.addEventListener('click', () => app.zoom?.zoomBy(1 / KEY_FACTOR));
  zoomIn.addEventListener('click', () => app.zoom?.zoomBy(KEY_FACTOR));
  fit.addEventListener('click', () => app.zoom?.fit());
  exit.addEventListener('click', () => leave());
  for (const name of ['min', 'max', 'step']) speed.setAttribute(name, mainSpeed.getAttribute(name));
  const showSpeed = () => {
    speed.value = mainSpeed.value;
    speedValue.textContent = $('spf-value').textContent;
    speed.setAttribute('aria-valuetext', speedValue.textContent);
    speed.disabled = mainSpeed.disabled;
  };
  speed.addEventListener('input', () => {
    mainSpeed.value = speed.value;
    mainSpeed.dispatchEvent(new Event('input', { bubbles: true }));
    showSpeed();
  });
  mainSpeed.addEventListener('input', showSpeed);
  const showPlay = () => {
    setText(play, app.playing ? 'playback.pause' : 'playback.play');
    play.setAttribute('aria-pressed', String(app.playing));
  };
  app.addEventListener('playing', showPlay);

  const showHeadline = () => {
    const metrics = app.guard((sim) => JSON.parse(sim.metrics_json())).value;
    const share = metrics?.arrived_share;
    const text = Number.isFinite(share) ? t('present.percent', { n: formatNumber(Math.round(share * 100)) }) : '–';
    if (arrived.textContent !== text) arrived.textContent = text;
    const hits = metrics?.collisions_agent_agent;
    const count = Number.isFinite(hits) ? formatNumber(hits) : '–';
    if (collisions.textContent !== count) collisions.textContent = count;
  };

  // Fading: idle after IDLE_MS without pointer movement; focus inside the bar keeps it shown.
  let idleTimer = null;
  const wake = () => {
    layer.classList.remove('idle');
    clearTimeout(idleTimer);
    idleTimer = setTimeout(() => layer.classList.add('idle'), IDLE_MS);
  };

  let presenting = false;
  let fullscreen = false;
  let headlineTimer = null;
  /** Elements made inert while presenting, to be given back. */
  let inerted = [];
  const onPointer = () => wake();

  /** Where the focus goes when the presentation ends (null: the page itself). */
  let returnTo = null;
  const enter = async ({ byPointer = false } = {}) => {
    if (presenting) return;
    presenting = true;
    // Back to Present when it was pressed by keyboard, to the canvas when P was pressed there;
    // else the page itself (P on a clicked button: a focus given back by script would no longer
    // count as the pointer's, and the button would keep S, R and 1–7 from the shortcuts).
    const at = document.activeElement;
    returnTo = !byPointer && (at === present || at?.tagName === 'CANVAS') ? at : null;
    document.documentElement.classList.add('presenting');
    stage.classList.add('presenting');
    layer.hidden = false;
    present.setAttribute('aria-pressed', 'true');
    // Everything but the stage is out of reach (Tab, screen readers) while it covers the page.
    inerted = [];
    for (let node = stage; node && node !== document.body; node = node.parentElement) {
      for (const sibling of node.parentElement.children) {
        if (sibling !== node && !sibling.inert && !['SCRIPT', 'STYLE'].includes(sibling.tagName)) {
          sibling.inert = true;
          inerted.push(sibling);
        }
      }
    }
    showPlay();
    showSpeed();
    showHeadline();
    headlineTimer = setInterval(showHeadline, HEADLINE_MS);
    document.addEventListener('pointermove', onPointer, true);
    document.addEventListener('pointerdown', onPointer, true);
    wake();
    play.focus({ preventScroll: true });
    try {
      if (stage.requestFullscreen && document.fullscreenEnabled !== false) {
        await stage.requestFullscreen({ navigationUI: 'hide' });
        fullscreen = document.fullscreenElement === stage;
      }
    } catch {
      // Refused (no user gesture, a headless browser, an iframe without allowfullscreen): the
      // fixed layer over the viewport stands in.
      fullscreen = false;
    }
    app.dispatchEvent(new Event('present'));
  };

  const leave = () => {
    if (!presenting) return;
    presenting = false;
    document.documentElement.classList.remove('presenting');
    stage.classList.remove('presenting');
    layer.hidden = true;
    layer.classList.remove('idle');
    present.setAttribute('aria-pressed', 'false');
    for (const node of inerted) node.inert = false;
    inerted = [];
    clearInterval(headlineTimer);
    clearTimeout(idleTimer);
    document.removeEventListener('pointermove', onPointer, true);
    document.removeEventListener('pointerdown', onPointer, true);
    // The focus goes back where it was (`returnTo`); after a mouse click on Present, to the page
    // itself (a focused Present button would take the next Space and present again, where the
    // teacher meant to play). Leaving fullscreen (the browser's Esc first, then this) can drop it
    // a frame later, once the hidden bar loses it: set again then.
    const back = returnTo;
    const refocus = () => {
      const at = document.activeElement;
      if (presenting || !(at === null || at === document.body || layer.contains(at))) return;
      if (back?.isConnected && back !== document.body) back.focus({ preventScroll: true });
      else at?.blur?.();
    };
    if (fullscreen && document.fullscreenElement === stage) document.exitFullscreen?.().then(refocus, refocus);
    fullscreen = false;
    if (back?.isConnected && back !== document.body) back.focus({ preventScroll: true });
    else document.activeElement?.blur?.();
    requestAnimationFrame(() => requestAnimationFrame(refocus));
    setTimeout(refocus, 250);
    app.dispatchEvent(new Event('present'));
  };

  // A mouse or touch click has a click count (`detail`); Enter or Space on the button has none.
  present.addEventListener('click', (e) => enter({ byPointer: e.detail > 0 }));
  // The browser left fullscreen (its Esc, F11): the presentation ends with it.
  document.addEventListener('fullscreenchange', () => {
    if (presenting && fullscreen && document.fullscreenElement !== stage) leave();
  });
  // Capture phase: Esc leaves before the editor treats it as "cancel", from any focus.
  document.addEventListener('keydown', (e) => {
    if (!presenting) {
      if ((e.key === 'p' || e.key === 'P') && !e.altKey && !e.ctrlKey && !e.metaKey && !e.defaultPrevented && onPage(e)) {
        e.preventDefault();
        enter();
      }
      return;
    }
    wake();
    if (e.key === 'Escape' && !e.target.closest?.('dialog[open]')) {
      e.preventDefault();
      e.stopPropagation();
      leave();
    } else if (e.key === 'Tab' && !e.altKey && !e.ctrlKey && !e.metaKey) {
      // Tab goes round the presentation (the page behind is inert; past its end the browser's
      // own bar would take the focus).
      const reachable = [...stage.querySelectorAll('button, input, canvas[tabindex], [tabindex="0"]')].filter(
        (node) => !node.disabled && node.getClientRects().length > 0 && !node.closest('[hidden], [inert]'),
      );
      const at = reachable.indexOf(document.activeElement);
      const next = e.shiftKey ? (at <= 0 ? reachable.at(-1) : null) : at === reachable.length - 1 || at < 0 ? reachable[0] : null;
      if (next) {
        e.preventDefault();
        next.focus();
      }
    }
  }, true);
  bar.addEventListener('focusin', wake);
  onLanguageChange(() => {
    if (!presenting) return;
    showPlay();
    showSpeed();
    showHeadline();
  });

  return { enter, leave, presenting: () => presenting };
}
