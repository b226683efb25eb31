// Printing a page with live scenes: a canvas prints blank or stale (the print layout resizes it,
// which clears it, and no animation frame runs to draw it again), so right before printing each
// `<flock-path>` element and each visible canvas of the page gets a still image of what it shows
// now (canvas.toDataURL into an <img>), shown instead of the canvas under `@media print` only, and
// removed after printing. flock-path.js imports this module (so course notes on any site print);
// the playground and the other pages include it with a <script type="module"> tag.
//
// Triggers: `beforeprint` / `afterprint`, and the `print` media query turning on / off (browsers
// that print without the events; after `beforeprint` it keeps the stills already taken).
//
// Styles are constructed sheets (document and each element's shadow root), and inline positions
// are set through the CSSOM, so a host page's Content-Security-Policy without 'unsafe-inline'
// does not refuse them.

const STILL_CLASS = 'flockpath-print-still';
const MARK = 'data-flockpath-print';

const CSS = `
.${STILL_CLASS} { display: none; }
@media print {
  canvas[${MARK}] { display: none !important; }
  .${STILL_CLASS} { display: block !important; object-fit: contain; }
}
`;

let sheet = null;

/** Adds the print sheet to a document or shadow root once. */
function adopt(root) {
  if (!('adoptedStyleSheets' in root) || typeof CSSStyleSheet.prototype.replaceSync !== 'function') return;
  if (!sheet) {
    sheet = new CSSStyleSheet();
    sheet.replaceSync(CSS);
  }
  if (!root.adoptedStyleSheets.includes(sheet)) root.adoptedStyleSheets = [...root.adoptedStyleSheets, sheet];
}

/** Puts a still of `canvas` right after it, sized and placed as the canvas is. */
function still(canvas) {
  if (!canvas.width || !canvas.height) return null;
  let url;
  try {
    url = canvas.toDataURL('image/png');
  } catch {
    return null; // A tainted canvas cannot be read: it prints as it is.
  }
  const img = document.createElement('img');
  img.className = STILL_CLASS;
  img.alt = canvas.getAttribute('aria-label') ?? 'Simulation snapshot';
  img.src = url;
  const style = getComputedStyle(canvas);
  if (style.position === 'absolute' || style.position === 'fixed') {
    img.style.position = 'absolute';
    for (const side of ['top', 'right', 'bottom', 'left']) img.style[side] = style[side];
    img.style.width = '100%';
    img.style.height = '100%';
  } else {
    img.style.width = `${canvas.getBoundingClientRect().width}px`;
    img.style.maxWidth = '100%';
    img.style.height = 'auto';
  }
  canvas.setAttribute(MARK, '');
  canvas.after(img);
  return img;
}

/** The canvases to freeze: each element's scene canvas and the page's own visible canvases. */
function targets() {
  const list = [];
  for (const el of document.querySelectorAll('flock-path')) {
    const canvas = el.shadowRoot?.querySelector('canvas');
    if (!canvas) continue;
    adopt(el.shadowRoot);
    list.push(canvas);
  }
  for (const canvas of document.querySelectorAll('canvas')) {
    // Decoration and input layers (the editor's overlay: `data-no-print`) print nothing of their own.
    if (canvas.getAttribute('aria-hidden') === 'true' || canvas.hasAttribute('data-no-print') || canvas.hasAttribute(MARK)) continue;
    if (canvas.getClientRects().length === 0) continue; // not displayed
    list.push(canvas);
  }
  return list;
}

let prepared = false;

/** Replaces the canvases by stills for printing; returns the images added. */
export function preparePrint() {
  releasePrint();
  prepared = true;
  adopt(document);
  return targets()
    .map(still)
    .filter((img) => img !== null);
}

/** Removes the stills and shows the canvases again. */
export function releasePrint() {
  prepared = false;
  const roots = [document, ...[...document.querySelectorAll('flock-path')].map((el) => el.shadowRoot).filter(Boolean)];
  for (const root of roots) {
    for (const img of root.querySelectorAll(`.${STILL_CLASS}`)) img.remove();
    for (const canvas of root.querySelectorAll(`canvas[${MARK}]`)) canvas.removeAttribute(MARK);
  }
}

if (!window.flockpathPrint) {
  window.flockpathPrint = { preparePrint, releasePrint };
  addEventListener('beforeprint', preparePrint);
  addEventListener('afterprint', releasePrint);
  const media = matchMedia('print');
  // After `beforeprint` the print layout may already have cleared the canvases: keep its stills.
  media.addEventListener?.('change', (event) => {
    if (!event.matches) releasePrint();
    else if (!prepared) preparePrint();
  });
}
