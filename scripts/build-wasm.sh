#!/usr/bin/env bash
# Builds the page's wasm module into www/pkg (release, wasm-opt -O, SIMD) and prints its size.
# Idempotent: skips the build when nothing under src/, Cargo.toml, Cargo.lock or .cargo/ changed,
# nor scripts/jupedsim_runs.py (the JuPedSim export includes it word for word), since the last one (stamp file www/pkg/.build-stamp). Pass --force to rebuild anyway.
# Either way it then rewrites www/pkg/precache.js (scripts/precache.mjs): the offline service
# worker's file list and version, which follow every change to www/ too, and the precompressed
# copies of www/ (scripts/precompress.mjs), rewritten only where a file changed.
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="$HOME/.cargo/bin:$PATH"

out=www/pkg
wasm="$out/flockpath_bg.wasm"
stamp="$out/.build-stamp"

force=0
[ "${1:-}" = "--force" ] && force=1

# A fingerprint of every input: a changed, added or removed file changes it.
inputs_hash() {
  find src Cargo.toml Cargo.lock .cargo scripts/jupedsim_runs.py -type f -print0 | sort -z | xargs -0 sha256sum | sha256sum | cut -d' ' -f1
}

hash=$(inputs_hash)
if [ $force = 0 ] && [ -f "$wasm" ] && [ -f "$out/flockpath.js" ] && [ -f "$stamp" ] \
   && [ "$(cat "$stamp")" = "$hash" ]; then
  echo "[build-wasm] up to date ($(stat -c %s "$wasm") bytes): $wasm"
  node scripts/precache.mjs
  node scripts/precompress.mjs
  exit 0
fi

# wasm-opt is disabled in Cargo.toml's wasm-pack metadata: wasm-pack would otherwise try to
# download its own, and Debian's binaryen is too old for current wasm-bindgen output.
wasm-pack build --release --target web --out-dir www/pkg --no-typescript
rm -f "$out/.gitignore" "$out/package.json" "$out/README.md"

# Rust's wasm32 target emits these post-MVP features; wasm-opt must be told it may keep them.
node_modules/.bin/wasm-opt -O \
  --enable-simd --enable-bulk-memory --enable-nontrapping-float-to-int --enable-sign-ext \
  --enable-mutable-globals --enable-reference-types --enable-multivalue \
  "$wasm" -o "$wasm.opt"
mv "$wasm.opt" "$wasm"

echo "$hash" > "$stamp"
raw=$(stat -c %s "$wasm")
gz=$(gzip -9 -c "$wasm" | wc -c)
echo "[build-wasm] $wasm: $raw bytes ($gz gzipped)"
node scripts/precache.mjs
# Brotli and gzip copies beside every page, script and the wasm, for servers that send them.
node scripts/precompress.mjs
