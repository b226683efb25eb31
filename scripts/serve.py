#!/usr/bin/env python3
"""Serves www/ for the flockpath playground and for pages on other sites that embed it.

    python3 scripts/serve.py [--port N] [--bind ADDR] [--directory DIR]

Like `python3 -m http.server`, threaded, plus what a page on another origin needs to load the
`<flock-path>` module, its imports and the wasm: `Access-Control-Allow-Origin: *` on every
response, and fixed MIME types (`text/javascript` for modules, `application/wasm` so browsers can
compile the wasm while it downloads) whatever the system's mime.types says. The first line on
stdout is `serve.py: serving DIR at http://ADDR:PORT/` (the real port when --port is 0).
"""

import argparse
import functools
import http.server
import os
import sys

MIME_TYPES = {
    ".js": "text/javascript; charset=utf-8",
    ".mjs": "text/javascript; charset=utf-8",
    ".wasm": "application/wasm",
    ".html": "text/html; charset=utf-8",
    ".css": "text/css; charset=utf-8",
    ".json": "application/json",
    ".svg": "image/svg+xml",
    ".png": "image/png",
}


class Handler(http.server.SimpleHTTPRequestHandler):
    extensions_map = {**http.server.SimpleHTTPRequestHandler.extensions_map, **MIME_TYPES}

    def end_headers(self):
        # Module scripts and fetch() from another origin are CORS requests: without this header
        # the browser refuses them. The files are public, so any origin may read them.
        self.send_header("Access-Control-Allow-Origin", "*")
        # Revalidate on every load: a rebuilt wasm must not meet a cached flockpath.js.
        self.send_header("Cache-Control", "no-cache")
        super().end_headers()

    def do_OPTIONS(self):
        # A preflight (only sent when a host adds custom request headers): allow reads.
        self.send_response(204)
        self.send_header("Access-Control-Allow-Methods", "GET, HEAD, OPTIONS")
        self.send_header("Access-Control-Allow-Headers", "*")
        self.send_header("Content-Length", "0")
        self.end_headers()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--port", type=int, default=0, help="port (default 0: a free one)")
    parser.add_argument("--bind", default="127.0.0.1", help="address (default 127.0.0.1)")
    default_dir = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "www")
    parser.add_argument("--directory", default=default_dir, help="folder to serve (default www/)")
    args = parser.parse_args()

    directory = os.path.realpath(args.directory)
    if not os.path.isdir(directory):
        sys.exit(f"serve.py: --directory {args.directory} is not a folder")
    handler = functools.partial(Handler, directory=directory)
    try:
        server = http.server.ThreadingHTTPServer((args.bind, args.port), handler)
    except OSError as error:
        sys.exit(f"serve.py: cannot listen on {args.bind}:{args.port}: {error.strerror}")
    host, port = server.server_address[:2]
    print(f"serve.py: serving {directory} at http://{host}:{port}/", flush=True)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass
    finally:
        server.server_close()


if __name__ == "__main__":
    main()
