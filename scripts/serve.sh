#!/usr/bin/env bash
# Installs what is missing, builds the wasm module in release, and serves www/ on 127.0.0.1.
# PORT=8080 picks the port; by default the system picks a free one (a fixed port may be taken).
# Stays in the foreground; Ctrl+C stops the server.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
bash scripts/build-wasm.sh

# python prints "Serving HTTP on 127.0.0.1 port N (http://127.0.0.1:N/) ..." first; -u keeps that
# line unbuffered so the real port can be read when PORT=0.
coproc SERVER { exec python3 -u -m http.server "${PORT:-0}" --bind 127.0.0.1 -d www 2>&1; }
server_pid=$SERVER_PID
# Coproc descriptors are not inherited by background jobs: keep a plain copy of the output end.
exec {server_out}<&"${SERVER[0]}"
trap 'kill "$server_pid" 2>/dev/null || true' EXIT INT TERM

if ! IFS= read -r first_line <&"$server_out"; then
  echo "serve.sh: the web server did not start" >&2
  exit 1
fi
port=$(sed -n 's/.* port \([0-9][0-9]*\) .*/\1/p' <<<"$first_line")
if [ -z "$port" ]; then
  echo "serve.sh: could not read the port from: $first_line" >&2
  exit 1
fi

printf '\n  flockpath playground: http://127.0.0.1:%s/\n\n  (Ctrl+C stops the server)\n\n' "$port"

# Pass the request log through (and keep the pipe drained), until the server exits.
cat <&"$server_out" &
wait "$server_pid"
