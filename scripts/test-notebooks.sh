#!/usr/bin/env bash
# Tests of the notebook widget (issue 28): makes the venv (scripts/setup-python.sh), builds the
# package (scripts/build-python.sh, which builds the wasm if stale) and installs it into the venv
# when it changed, runs its pytest suite (no browser), the end-to-end test in a real JupyterLab
# driven by headless Chromium (tests/notebook/), then builds the MyST example with mystmd (npm,
# installed into examples/myst-course-notes/) and runs its page in Chromium (tests/myst/).
# About 50 s warm, most of it JupyterLab starting and the widgets loading.
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="$HOME/.cargo/bin:$PATH"

bash scripts/setup-python.sh
bash scripts/build-python.sh

# `pip install ./python` takes ~15 s: only when the package's files differ from the installed ones.
stamp=.venv-python/.flockpath-installed
sum=$(find python -path python/build -prune -o -path '*/__pycache__' -prune -o -name '*.egg-info' -prune -o -type f -print0 \
  | sort -z | xargs -0 sha256sum | sha256sum | cut -d' ' -f1)
if [ ! -f "$stamp" ] || [ "$(cat "$stamp")" != "$sum" ]; then
  echo "[test-notebooks] pip install ./python" >&2
  .venv-python/bin/python -m pip install --quiet --disable-pip-version-check ./python
  rm -rf python/build python/*.egg-info
  printf '%s' "$sum" > "$stamp"
fi

(cd python && ../.venv-python/bin/python -m pytest -q tests)

if [ ! -d node_modules/playwright-core ]; then
  npm ci --no-audit --no-fund --loglevel=error
fi
mkdir -p test-artifacts
node --test --test-concurrency=1 tests/notebook/*.test.mjs

myst=examples/myst-course-notes
if [ ! -x "$myst/node_modules/.bin/myst" ] || [ "$myst/package-lock.json" -nt "$myst/node_modules/.package-lock.json" ]; then
  echo "[test-notebooks] installing mystmd into $myst" >&2
  npm ci --prefix "$myst" --no-audit --no-fund --loglevel=error
fi
node --test --test-concurrency=1 tests/myst/*.test.mjs
