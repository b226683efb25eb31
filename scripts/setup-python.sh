#!/usr/bin/env bash
# The Python environment of the notebook widget (python/): a venv in .venv-python with anywidget,
# pytest and JupyterLab from PyPI (the end-to-end test starts a real JupyterLab). Idempotent: when
# the venv holds the versions below it does nothing (well under a second). Prints nothing but
# "[setup-python] …" lines on stderr.
set -euo pipefail
cd "$(dirname "$0")/.."

VENV=.venv-python
# Pinned so the tests see the same hosts every time; bump together with a test run.
PACKAGES=(anywidget==0.11.0 pytest==9.2.0 jupyterlab==4.6.6)
STAMP="$VENV/.flockpath-packages"

log() { printf '[setup-python] %s\n' "$*" >&2; }

if [ -x "$VENV/bin/python" ] && [ -f "$STAMP" ] && [ "$(cat "$STAMP")" = "${PACKAGES[*]}" ]; then
  exit 0
fi

if [ ! -x "$VENV/bin/python" ]; then
  log "creating $VENV"
  # Debian's own python3 keeps venv in a package of its own.
  if ! python3 -m venv "$VENV" 2>/dev/null; then
    log "installing Debian's python3-venv"
    rm -rf "$VENV"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq python3-venv >/dev/null
    python3 -m venv "$VENV"
  fi
fi
log "installing ${PACKAGES[*]} from PyPI (about a minute the first time)"
"$VENV/bin/python" -m pip install --quiet --disable-pip-version-check "${PACKAGES[@]}"
printf '%s' "${PACKAGES[*]}" > "$STAMP"
log "ready"
