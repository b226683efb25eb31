#!/usr/bin/env bash
# Runs the wasm-bindgen browser tests (tests/web.rs) in headless Chromium and checks that they ran:
# `wasm-pack test --chrome` skips a file without `run_in_browser` and still exits 0.
# Chromium's flags come from webdriver.json; chromedriver is /usr/bin/chromedriver on PATH.
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="$HOME/.cargo/bin:$PATH"

log=$(mktemp)
trap 'rm -f "$log"' EXIT
wasm-pack test --headless --chrome -- --test web 2>&1 | tee "$log"

# The runner prints "test result: ok. N passed; M failed; ..." for the file.
passed=$(sed -n 's/.*test result: ok\. \([0-9]*\) passed.*/\1/p' "$log" | tail -1)
if [ -z "$passed" ] || [ "$passed" -eq 0 ]; then
  echo "[test-wasm] no browser test ran (expected the tests in tests/web.rs)" >&2
  exit 1
fi
echo "[test-wasm] $passed browser tests passed"
