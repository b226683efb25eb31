#!/usr/bin/env bash
# Tests of the notebook widget (issue 28): makes the venv (scripts/setup-python.sh), builds the
# package (scripts/build-python.sh, which builds the wasm if stale) and installs it into the venv
# when it changed, runs its pytest suite (no browser), then the end-to-end test in a real
# JupyterLab driven by headless Chromium (tests/notebook/). About a minute warm, most of it
# JupyterLab starting and the two widgets loading.
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
  echo "[test-python] pip install ./python" >&2
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
