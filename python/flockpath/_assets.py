"""Serves the package's copy of www/ (the widget module, its imports and the wasm) to the browser.

An anywidget host loads a widget's module from a string (a blob: URL), against which no relative
import resolves; flockpath's module imports the element, js/core/ and the wasm relative to itself
(the same files the page serves). So the kernel serves them over HTTP on 127.0.0.1 with CORS
headers (the element's cross-origin support then starts its worker from a blob, as on any course
page), and the widget's loader imports js/widget.js from there by URL. This reaches a browser on
the kernel's machine (JupyterLab, Notebook 7, VS Code, marimo run locally); elsewhere (Colab, a
remote JupyterHub) set ``FlockPath.assets_url`` to a flockpath site served with CORS.
"""

from __future__ import annotations

import functools
import http.server
import threading
from pathlib import Path

#: Where scripts/build-python.sh copies the built files.
STATIC_DIR = Path(__file__).parent / "static"

#: The files the widget cannot run without, relative to STATIC_DIR.
REQUIRED = ("js/widget.js", "js/flock-path.js", "pkg/flockpath.js", "pkg/flockpath_bg.wasm")


class AssetsMissing(RuntimeError):
    """The package was installed without the built wasm and JS (see scripts/build-python.sh)."""


def missing_files(static_dir: Path = STATIC_DIR) -> list[str]:
    """The required files absent from ``static_dir`` (empty: all there)."""
    return [name for name in REQUIRED if not (static_dir / name).is_file()]


class _Handler(http.server.SimpleHTTPRequestHandler):
    """Static files with CORS (the notebook page is on another port) and the wasm's MIME type."""

    extensions_map = {
        **http.server.SimpleHTTPRequestHandler.extensions_map,
        ".js": "text/javascript",
        ".mjs": "text/javascript",
        ".wasm": "application/wasm",
    }

    def end_headers(self) -> None:
        self.send_header("Access-Control-Allow-Origin", "*")
        # A rebuilt package is picked up on the next load, not after a stale cache expires.
        self.send_header("Cache-Control", "no-cache")
        super().end_headers()

    def log_message(self, format: str, *args: object) -> None:  # noqa: A002 (the base's name)
        # Quiet: every request would otherwise be printed into the notebook's log.
        pass


_lock = threading.Lock()
_server: http.server.ThreadingHTTPServer | None = None


def assets_url(static_dir: Path = STATIC_DIR) -> str:
    """The URL of the served www/ copy, ending in ``/``: one server per kernel, started on first use.

    Raises AssetsMissing, naming the files and the build command, when the package has no build.
    """
    global _server
    missing = missing_files(static_dir)
    if missing:
        raise AssetsMissing(
            f"flockpath's built files are missing from {static_dir} ({', '.join(missing)}): "
            "run `bash scripts/build-python.sh` in the flockpath repository, then "
            "`pip install ./python` again"
        )
    with _lock:
        if _server is None:
            handler = functools.partial(_Handler, directory=str(static_dir))
            _server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
            _server.daemon_threads = True
            threading.Thread(target=_server.serve_forever, name="flockpath-assets", daemon=True).start()
        host, port = _server.server_address[:2]
    return f"http://{host}:{port}/"
