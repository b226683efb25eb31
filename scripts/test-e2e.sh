#!/usr/bin/env bash
# End-to-end tests of the page: builds the wasm module if it is missing or stale, then runs
# tests/e2e/*.test.mjs with `node --test` (playwright-core drives Debian's Chromium; nothing is
# downloaded). Screenshots land in test-artifacts/. Exits non-zero on failure.
set -euo pipefail
cd "$(dirname "$0")/.."

# build-wasm.sh is a no-op (under a second) when nothing it depends on changed.
bash scripts/build-wasm.sh

if [ ! -d node_modules/playwright-core ]; then
  echo "[test-e2e] installing npm packages" >&2
  npm ci --no-audit --no-fund --loglevel=error
fi

mkdir -p test-artifacts
# One file per scenario; run them one at a time: the machine has 2 cores and each test starts
# a browser.
node --test --test-concurrency=1 tests/e2e/
