#!/usr/bin/env bash
# Installs what is missing, builds the wasm module in release, and serves www/ on 127.0.0.1 with
# scripts/static-server.mjs (CORS headers, the wasm MIME type and compressed responses, so
# <flock-path> works from other sites and a first visit downloads under 1 MB).
# PORT=8080 picks the port; by default the system picks a free one (a fixed port may be taken).
# Stays in the foreground; Ctrl+C stops the server.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
bash scripts/build-wasm.sh

# The server prints "static-server: serving DIR at http://127.0.0.1:N/" first, then a line per
# request.
coproc SERVER { exec node scripts/static-server.mjs --port "${PORT:-0}" --bind 127.0.0.1 --directory www 2>&1; }
server_pid=$SERVER_PID
# Coproc descriptors are not inherited by background jobs: keep a plain copy of the output end.
exec {server_out}<&"${SERVER[0]}"
trap 'kill "$server_pid" 2>/dev/null || true' EXIT INT TERM

if ! IFS= read -r first_line <&"$server_out"; then
  echo "serve.sh: the web server did not start" >&2
  exit 1
fi
port=$(sed -n 's|^static-server: serving .* at http://127\.0\.0\.1:\([0-9][0-9]*\)/$|\1|p' <<<"$first_line")
if [ -z "$port" ]; then
  echo "serve.sh: could not read the port from: $first_line" >&2
  exit 1
fi

printf '\n  flockpath playground: http://127.0.0.1:%s/\n\n  (Ctrl+C stops the server)\n\n' "$port"

# Pass the request log through (and keep the pipe drained), until the server exits.
cat <&"$server_out" &
wait "$server_pid"
