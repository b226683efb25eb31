#!/usr/bin/env bash
# Installs everything the build and the tests need, skipping what is already present.
# Idempotent and offline-safe: nothing downloads its own binaries at run time (see README).
# Warm run: well under a second.
set -euo pipefail
cd "$(dirname "$0")/.."

log() { printf '[setup] %s\n' "$*" >&2; }

# The exact wasm-bindgen version Cargo.lock pins: wasm-pack only uses a wasm-bindgen-cli on PATH
# when it matches, otherwise it tries (and here fails) to download its own.
bindgen_version() {
  awk '/^name = "wasm-bindgen"$/ { getline; gsub(/"/, "", $3); print $3; exit }' Cargo.lock
}

export PATH="$HOME/.cargo/bin:$PATH"

if ! rustup target list --installed 2>/dev/null | grep -qx wasm32-unknown-unknown; then
  log "adding the wasm32-unknown-unknown target"
  rustup target add wasm32-unknown-unknown
fi

if [ ! -f Cargo.lock ]; then
  log "generating Cargo.lock"
  cargo generate-lockfile
fi

want_bindgen=$(bindgen_version)
have_bindgen=$(wasm-bindgen --version 2>/dev/null | awk '{print $2}' || true)
if [ "$have_bindgen" != "$want_bindgen" ]; then
  log "installing wasm-bindgen-cli $want_bindgen (about 3 minutes the first time)"
  # Without --locked: the CLI's own lockfile pins a crate release the registry does not serve.
  cargo install wasm-bindgen-cli --version "$want_bindgen"
fi

if ! wasm-pack --version 2>/dev/null | grep -q '0.15.1'; then
  log "installing wasm-pack 0.15.1 (about 2 minutes the first time)"
  cargo install wasm-pack --version 0.15.1 --locked
fi

if [ ! -x /usr/bin/chromium ] || [ ! -x /usr/bin/chromedriver ]; then
  log "installing Debian's chromium and chromium-driver"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq chromium chromium-driver >/dev/null
fi

# npm packages: playwright-core (no browser download), binaryen (wasm-opt), axe-core, and
# scorm-again (the LMS-side SCORM runtime the SCORM package's e2e test reports to).
if [ ! -d node_modules/playwright-core ] || [ ! -x node_modules/.bin/wasm-opt ] \
   || [ ! -f node_modules/scorm-again/dist/scorm12.js ] \
   || [ package-lock.json -nt node_modules/.package-lock.json ]; then
  log "installing npm packages"
  if [ -f package-lock.json ]; then
    npm ci --no-audit --no-fund --loglevel=error
  else
    npm install --no-audit --no-fund --loglevel=error
  fi
fi

log "ready"
