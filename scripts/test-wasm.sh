#!/usr/bin/env bash
# Runs the wasm-bindgen browser tests (tests/web.rs, tests/web_lab.rs) in headless Chromium and
# checks that each file ran: `wasm-pack test --chrome` skips a file without `run_in_browser` and
# still exits 0. Chromium's flags come from webdriver.json; chromedriver is /usr/bin/chromedriver.
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="$HOME/.cargo/bin:$PATH"

log=$(mktemp)
trap 'rm -f "$log"' EXIT
total=0
for file in web web_lab; do
  wasm-pack test --headless --chrome -- --test "$file" 2>&1 | tee "$log"
  # The runner prints "test result: ok. N passed; M failed; ..." for the file.
  passed=$(sed -n 's/.*test result: ok\. \([0-9]*\) passed.*/\1/p' "$log" | tail -1)
  if [ -z "$passed" ] || [ "$passed" -eq 0 ]; then
    echo "[test-wasm] no browser test ran in tests/$file.rs" >&2
    exit 1
  fi
  total=$((total + passed))
done
echo "[test-wasm] $total browser tests passed"
