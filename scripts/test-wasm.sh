#!/usr/bin/env bash
# Runs the wasm-bindgen browser tests (tests/web.rs, tests/web_*.rs) in headless Chromium and checks that they ran:
# `wasm-pack test --chrome` skips a file without `run_in_browser` and still exits 0.
# Chromium's flags come from webdriver.json; chromedriver is /usr/bin/chromedriver on PATH.
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="$HOME/.cargo/bin:$PATH"

# Every browser test file: tests/web.rs (the playground's API) and tests/web_*.rs (one per page,
# e.g. web_tune.rs). Each must carry `run_in_browser`.
files=(tests/web.rs tests/web_*.rs)
args=()
for f in "${files[@]}"; do
  [ -f "$f" ] && args+=(--test "$(basename "$f" .rs)")
done

log=$(mktemp)
trap 'rm -f "$log"' EXIT
wasm-pack test --headless --chrome -- "${args[@]}" 2>&1 | tee "$log"

# The runner prints "test result: ok. N passed; M failed; ..." once per file: every file must
# report, with at least one test passed.
results=$(grep -c 'test result: ok\.' "$log" || true)
passed=$(sed -n 's/.*test result: ok\. \([0-9]*\) passed.*/\1/p' "$log" | awk '{s += $1} END {print s + 0}')
empty=$(sed -n 's/.*test result: ok\. \([0-9]*\) passed.*/\1/p' "$log" | grep -cx 0 || true)
if [ "$results" -ne "$(( ${#args[@]} / 2 ))" ] || [ "$empty" -ne 0 ] || [ "$passed" -eq 0 ]; then
  echo "[test-wasm] expected browser tests in each of ${files[*]}; $results files reported, $empty ran none" >&2
  exit 1
fi
echo "[test-wasm] $passed browser tests passed in $results files"
