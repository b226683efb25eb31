#!/usr/bin/env bash
# Benchmarks, native and in the browser, pinned to one core (taskset -c 0) so figures compare:
#   1. `flockpath bench`: ns per agent-step of World::step at 1k/10k/100k agents, the O(N²)
#      baseline, render ms per frame;
#   2. the same scenes in wasm in headless Chromium (www/bench.html), the wasm/native ratio and
#      the 10,000-agent frame time (step + render + putImageData);
#   3. the real page (www/index.html) as users meet it: fps, Pause latency, main-thread profile and
#      metrics() cost per planner at 1k/10k/100k agents, spread and packed (scripts/bench-page.mjs;
#      about 10 minutes; --quick: Boids at 1k and 10k only);
#   4. a tuning run on the Tune page (scripts/bench-tune-browser.mjs; not in --quick);
#   5. the playground's cold load: first frame, main-thread CPU, bytes (scripts/bench-cold-load.mjs).
# Usage: scripts/bench.sh [--quick|--smoke]
#   --quick: short runs, rough figures.
#   --smoke: every benchmark at a hundredth of its sizes, one short repetition, with the debug
#            build the tests already made: checks that every benchmark still runs (the README's
#            test command runs it); its figures mean nothing. Figures go to target/bench-smoke/.
# Figures land in target/bench-native.json, target/bench-wasm.json, target/bench-page.json,
# target/bench-tune.json and target/bench-cold-load.json. This prints, never fails on speed:
# benchmarks are not tests (a benchmark that cannot run fails it).
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="$HOME/.cargo/bin:$PATH"

mode=full
case "${1:-}" in
  --quick) mode=quick ;;
  --smoke) mode=smoke ;;
  "") ;;
  *) echo "usage: scripts/bench.sh [--quick|--smoke]" >&2; exit 2 ;;
esac

pin=(taskset -c 0)
command -v taskset >/dev/null || { echo "[bench] taskset not found: running unpinned" >&2; pin=(); }

out=target
if [ "$mode" = smoke ]; then
  out=target/bench-smoke
  mkdir -p "$out"
  cargo build --quiet --bin flockpath
  bin=target/debug/flockpath
  sizes=(10 100 1000)
  planner_sizes=(10 100)
  native_args=(--smoke)
  browser_args=(--smoke)
  page_args=(--seconds 0.5 --planners boids --sizes 100 --no-profile)
  tune_args=(--population 4 --generations 1 --frames 20)
  cold_args=(--runs 1)
else
  cargo build --release --quiet
  bin=target/release/flockpath
  sizes=(1000 10000 100000)
  planner_sizes=(1000 10000)
  native_args=()
  browser_args=()
  page_args=()
  tune_args=()
  cold_args=()
  if [ "$mode" = quick ]; then
    native_args=(--quick)
    browser_args=(--quick)
    page_args=(--seconds 1 --planners boids --sizes 1000,10000)
    cold_args=(--runs 3)
  fi
fi

echo "[bench] native"
"${pin[@]}" "$bin" bench "${native_args[@]}" --json "$out/bench-native.json"

echo "[bench] scenes for the browser: www/bench/density-N.json"
for n in "${sizes[@]}"; do
  "$bin" density-scene "$n" > "www/bench/density-$n.json"
done
# The per-planner rows of the native bench, as scenes for the same table in wasm.
"$bin" density-scene --planners > www/bench/planners.txt
while read -r planner; do
  for n in "${planner_sizes[@]}"; do
    "$bin" density-scene "$n" --planner "$planner" > "www/bench/planner-$planner-$n.json"
  done
done < www/bench/planners.txt

bash scripts/build-wasm.sh
if [ ! -d node_modules/playwright-core ]; then
  npm ci --no-audit --no-fund --loglevel=error
fi
echo "[bench] wasm in headless Chromium"
"${pin[@]}" node scripts/bench-browser.mjs "${browser_args[@]}" --native "$out/bench-native.json" \
  --json "$out/bench-wasm.json"

echo "[bench] the real page (index.html) in headless Chromium"
# bench-page.mjs and bench-cold-load.mjs start Chromium through taskset themselves.
node scripts/bench-page.mjs "${page_args[@]}" --json "$out/bench-page.json"

if [ "$mode" != quick ]; then
  echo "[bench] a tuning run on the Tune page"
  "${pin[@]}" node scripts/bench-tune-browser.mjs "${tune_args[@]}" --json "$out/bench-tune.json"
fi

echo "[bench] cold load of the playground"
node scripts/bench-cold-load.mjs "${cold_args[@]}" --json "$out/bench-cold-load.json"
