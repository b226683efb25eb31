#!/usr/bin/env bash
# Builds the notebook widget's Python package (python/): copies the anywidget module
# (www/js/widget.js), the <flock-path> element, js/core/ and the wasm from www/ into
# python/flockpath/static/ (gitignored package data; no bundler: the same files the page serves).
# Then `pip install ./python` installs it. Builds the wasm first when it is missing or stale
# (scripts/build-wasm.sh: a no-op when nothing changed). About a second when the wasm is built.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/build-wasm.sh

static=python/flockpath/static
rm -rf "$static"
mkdir -p "$static/js" "$static/pkg"
# Only what the widget loads: the element and its imports, not the pages or the precompressed copies.
cp www/js/widget.js www/js/flock-path.js "$static/js/"
rsync -a --exclude '*.br' --exclude '*.gz' www/js/core "$static/js/" 2>/dev/null \
  || { cp -r www/js/core "$static/js/" && find "$static/js/core" \( -name '*.br' -o -name '*.gz' \) -delete; }
cp www/pkg/flockpath.js www/pkg/flockpath_bg.wasm "$static/pkg/"
printf '[build-python] %s: %s files\n' "$static" "$(find "$static" -type f | wc -l)" >&2
