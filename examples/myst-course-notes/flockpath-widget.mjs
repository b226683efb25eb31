// flockpath's notebook widget for this book. mystmd copies the module an {anywidget} directive
// names into the built site (a remote one too: it downloads it), alone; flockpath's module loads
// its element, js/core/ and the wasm relative to itself, so this one line imports it from where
// flockpath is hosted (that server must allow CORS: README, "Hosting"). Change the URL to yours.
export { default } from 'https://example.org/flockpath/js/widget.js';
