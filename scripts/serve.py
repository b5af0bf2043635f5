#!/usr/bin/env python3
"""Serves the cnets site (scripts/web.sh's folder) with its compressed copies.

    python3 scripts/serve.py [FOLDER] [PORT]     # defaults: target/web 8000; port 0 = any free one

A static file server (Python's standard library only) that answers a request for `name` with
`name.br` (Content-Encoding: br) or `name.gz` (gzip) when the browser accepts that encoding and
the copy sits beside the file, with the original file's Content-Type (`application/wasm` for the
module, so the browser compiles it while it downloads) and `Vary: Accept-Encoding`. The first
visit then transfers about 4 MB instead of 17 MB. Prints `Serving HTTP on HOST port N (…)` once
it listens (scripts/test-web.sh reads the port from it).
"""

import functools
import http.server
import os
import sys

# The encodings tried, best first: (token in Accept-Encoding, file suffix).
ENCODINGS = (("br", ".br"), ("gzip", ".gz"))


def accepted(header):
    """The encodings an Accept-Encoding header accepts (q=0 refuses one)."""
    tokens = set()
    for part in (header or "").split(","):
        name, _, params = part.strip().partition(";")
        q = params.strip()
        if q.startswith("q=") and q[2:].strip() in ("0", "0.0", "0.00", "0.000"):
            continue
        if name:
            tokens.add(name.strip().lower())
    return tokens


class Handler(http.server.SimpleHTTPRequestHandler):
    """SimpleHTTPRequestHandler that prefers a precompressed copy of a regular file."""

    extensions_map = {
        **http.server.SimpleHTTPRequestHandler.extensions_map,
        ".wasm": "application/wasm",
        ".js": "text/javascript",
        ".mjs": "text/javascript",
        ".ron": "text/plain; charset=utf-8",
    }

    def send_head(self):
        path = self.translate_path(self.path)
        if os.path.isdir(path) and self.path.split("?", 1)[0].endswith("/"):
            path = os.path.join(path, "index.html")
        if os.path.isfile(path):
            tokens = accepted(self.headers.get("Accept-Encoding"))
            for token, suffix in ENCODINGS:
                copy = path + suffix
                if token in tokens and os.path.isfile(copy):
                    return self.send_copy(path, copy, token)
        return super().send_head()

    def send_copy(self, path, copy, token):
        """Headers for `copy` (the compressed `path`); returns the open file."""
        try:
            f = open(copy, "rb")
        except OSError:
            return super().send_head()
        size = os.fstat(f.fileno()).st_size
        self.send_response(200)
        self.send_header("Content-Type", self.guess_type(path))
        self.send_header("Content-Encoding", token)
        self.send_header("Content-Length", str(size))
        self.send_header("Vary", "Accept-Encoding")
        self.send_header("Last-Modified", self.date_time_string(os.path.getmtime(copy)))
        self.end_headers()
        return f

    def end_headers(self):
        if not self._headers_buffer or b"Vary:" not in b"".join(self._headers_buffer):
            self.send_header("Vary", "Accept-Encoding")
        super().end_headers()


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else "target/web"
    port = int(sys.argv[2]) if len(sys.argv) > 2 else 8000
    host = os.environ.get("CNETS_SERVE_HOST", "127.0.0.1")
    if not os.path.isdir(folder):
        sys.exit(f"serve.py: {folder} is not a folder (build the site with scripts/web.sh)")
    handler = functools.partial(Handler, directory=folder)
    with http.server.ThreadingHTTPServer((host, port), handler) as server:
        bound = server.server_address[1]
        print(f"Serving HTTP on {host} port {bound} (http://{host}:{bound}/) ...", flush=True)
        try:
            server.serve_forever()
        except KeyboardInterrupt:
            pass


if __name__ == "__main__":
    main()
