// The stand-in theme's page: renders one page of a `myst build --site` output (content/<page>.json,
// beside this file) as the MyST book theme would for what the example uses: headings, paragraphs
// and `{anywidget}` nodes. Each anywidget node's module is imported by its URL and its
// `render({ model, el })` called with a model made from the node's JSON alone: no kernel, no
// Jupyter, as in a static Jupyter Book page. The model is the anywidget front-end contract
// (get, set, on, off, save_changes, send); set() fires `change:<key>` as hosts do.

/** A kernel-less anywidget model over `state` (the directive's JSON). */
function staticModel(state) {
  const values = { ...state };
  const listeners = new Map();
  const emit = (name, ...args) => {
    for (const fn of listeners.get(name) ?? []) fn(...args);
  };
  return {
    get: (key) => values[key],
    set(key, value) {
      values[key] = value;
      emit(`change:${key}`, value);
    },
    on(name, fn) {
      if (!listeners.has(name)) listeners.set(name, new Set());
      listeners.get(name).add(fn);
    },
    off(name, fn) {
      listeners.get(name)?.delete(fn);
    },
    // Nothing to save to or send to without a kernel.
    save_changes() {},
    send() {},
    /** For the test: what the widget wrote (a copy). */
    snapshot: () => structuredClone(values),
  };
}

function text(node) {
  if (node.value) return node.value;
  return (node.children ?? []).map(text).join('');
}

async function renderNode(node, into, widgets) {
  if (node.type === 'heading') {
    into.append(Object.assign(document.createElement(`h${node.depth}`), { textContent: text(node) }));
  } else if (node.type === 'paragraph') {
    into.append(Object.assign(document.createElement('p'), { textContent: text(node) }));
  } else if (node.type === 'anywidget') {
    const el = Object.assign(document.createElement('div'), { className: 'anywidget' });
    into.append(el);
    const model = staticModel(node.model ?? {});
    widgets.push(model);
    const module = await import(node.esm);
    await (module.default ?? module).render({ model, el });
  } else {
    for (const child of node.children ?? []) await renderNode(child, into, widgets);
  }
}

const name = new URLSearchParams(location.search).get('page') ?? 'index';
const content = await (await fetch(`content/${name}.json`)).json();
/** Every widget's model, in page order (read by tests/myst/book.test.mjs). */
window.mystWidgets = [];
const page = document.getElementById('page');
page.append(Object.assign(document.createElement('h1'), { textContent: content.frontmatter?.title ?? name }));
await renderNode(content.mdast, page, window.mystWidgets);
