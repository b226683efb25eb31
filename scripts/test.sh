#!/usr/bin/env bash
# Runs every test: formatting and lints, native unit/integration/doc tests, wasm tests in headless
# Chromium, the end-to-end page tests, and a smoke run of every benchmark. Installs whatever is
# missing first (scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="$HOME/.cargo/bin:$PATH"

# Each section says when it starts (seconds since the run began), so a slow phase shows in the log.
section() { printf '\n=== %s (at %d s) ===\n' "$*" "$SECONDS"; }

section "setup"
bash scripts/setup.sh

section "format and lints"
cargo fmt --check
cargo clippy --all-targets -- -D warnings
cargo clippy --lib --target wasm32-unknown-unknown -- -D warnings

section "native tests"
cargo test --all-targets
cargo test --doc

section "wasm tests (headless Chromium)"
bash scripts/test-wasm.sh

section "end-to-end tests (headless Chromium)"
bash scripts/test-e2e.sh

# Every benchmark script at a hundredth of its sizes: they keep running (figures mean nothing).
section "benchmark smoke run"
bash scripts/bench.sh --smoke

section "all tests passed"
