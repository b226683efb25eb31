#!/usr/bin/env bash
# Benchmarks, native and in the browser, pinned to one core (taskset -c 0) so figures compare:
#   1. `flockpath bench`: ns per agent-step of World::step at 1k/10k/100k agents, the O(N²)
#      baseline, render ms per frame;
#   2. the same scenes in wasm in headless Chromium (www/bench.html), the wasm/native ratio and
#      the 10,000-agent frame time (step + render + putImageData);
#   3. the real page (www/index.html) as users meet it: fps, Pause latency, main-thread profile and
#      metrics() cost per planner at 1k/10k/100k agents, spread and packed (scripts/bench-page.mjs;
#      about 10 minutes; --quick: Boids at 1k and 10k only).
# Usage: scripts/bench.sh [--quick]   (--quick: short runs, rough figures, for CI smoke)
# Figures land in target/bench-native.json, target/bench-wasm.json and target/bench-page.json. This prints, never fails
# on speed: benchmarks are not tests.
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="$HOME/.cargo/bin:$PATH"

quick=()
[ "${1:-}" = "--quick" ] && quick=(--quick)

pin=(taskset -c 0)
command -v taskset >/dev/null || { echo "[bench] taskset not found: running unpinned" >&2; pin=(); }

cargo build --release --quiet
bin=target/release/flockpath

echo "[bench] native"
"${pin[@]}" "$bin" bench "${quick[@]}" --json target/bench-native.json

echo "[bench] scenes for the browser: www/bench/density-N.json"
for n in 1000 10000 100000; do
  "$bin" density-scene "$n" > "www/bench/density-$n.json"
done
# The per-planner rows of the native bench, as scenes for the same table in wasm.
"$bin" density-scene --planners > www/bench/planners.txt
while read -r planner; do
  for n in 1000 10000; do
    "$bin" density-scene "$n" --planner "$planner" > "www/bench/planner-$planner-$n.json"
  done
done < www/bench/planners.txt

bash scripts/build-wasm.sh
if [ ! -d node_modules/playwright-core ]; then
  npm ci --no-audit --no-fund --loglevel=error
fi
echo "[bench] wasm in headless Chromium"
"${pin[@]}" node scripts/bench-browser.mjs "${quick[@]}" --native target/bench-native.json \
  --json target/bench-wasm.json

echo "[bench] the real page (index.html) in headless Chromium"
page_args=()
[ ${#quick[@]} -gt 0 ] && page_args=(--seconds 1 --planners boids --sizes 1000,10000)
# bench-page.mjs starts Chromium through taskset itself.
node scripts/bench-page.mjs "${page_args[@]}" --json target/bench-page.json
