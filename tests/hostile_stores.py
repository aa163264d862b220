"""Hostile stores on loopback (issue 25), written here: each serves good product pages in ``mode = "good"``
and misbehaves in ``mode = "hostile"``, so a test ingests once well, then again hostile, and checks that
every page gets a recorded reason while the catalog stays as it was.

- :class:`PageStore`: one host whose pages misbehave (:data:`PAGE_KINDS`): a slow drip (of the body, of
  the status line, of the headers, of a chunk-size line; a byte every 50 ms, each within any read
  time-out), endless and
  circular redirects, redirects to another port (closed) and another host (``localhost``), gzip and deflate
  bombs, a page of 1 million nested elements, 10,000 JSON-LD blocks, a wrong and a missing charset, a 200
  whose body is an error page;
- ``PageStore(robots_hang_s=...)``: its robots.txt hangs (its pages are behind it);
- ``PageStore(sitemap_urls=1_000_000)``: its sitemap lists a million URLs.

:func:`sources_text` writes a sources file for a set of them (small deadlines so the tests stay fast).
"""

from __future__ import annotations

import gzip
import json
import socket
import threading
import time
import zlib
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

from hostile_store import product_page

#: The hostile page kinds of a :class:`PageStore`, each at ``/p/<kind>``. No two drips in a row: a store
#: whose pages time out twice in a row gives up its other pages (``store_unresponsive``,
#: ``scrapers/crawl.py``), and here every kind is to be read for its own reason.
PAGE_KINDS = (
    "drip",
    "redirect-endless",
    "drip-status",
    "redirect-circle",
    "drip-headers",
    "redirect-other-port",
    "drip-chunked",
    "redirect-other-host",
    "gzip-bomb",
    "deflate-bomb",
    "nested",
    "jsonld-10000",
    "wrong-charset",
    "missing-charset",
    "error-page",
)

#: The drip's pace: one byte every 50 ms, always within any read time-out.
DRIP_INTERVAL_S = 0.05

BOMB_BYTES = 64 * 1024 * 1024  # decoded size of the bombs (64 MiB of zeros; ~64 KiB on the wire)


def good_page(kind: str) -> bytes:
    name = f"Hostile {kind.replace('-', ' ').title()} Mug"
    return product_page(name, "9 x 9 x 10 cm", "320 g").encode()


def closed_port() -> int:
    """A loopback port nothing listens on (bound, then released)."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class _Handler(BaseHTTPRequestHandler):
    protocol_version = "HTTP/1.1"

    def log_message(self, format: str, *args) -> None:  # noqa: A002
        pass

    def _send(self, status: int, body: bytes, ctype: str = "text/html; charset=utf-8", **headers: str) -> None:
        self.send_response(status)
        if ctype:
            self.send_header("Content-Type", ctype)
        for key, value in headers.items():
            self.send_header(key.replace("_", "-"), value)
        self.send_header("Content-Length", str(len(body)))
        self.end_headers()
        self.wfile.write(body)

    def do_GET(self) -> None:  # noqa: N802
        store: PageStore = self.server.store  # type: ignore[attr-defined]
        store.requests += 1
        store.seen.setdefault(self.path, time.monotonic())
        store.peers.add(self.client_address[1])
        try:
            store.answer(self)
        except OSError:  # the client gave up (a deadline): nothing to do
            pass


class PageStore:
    """A loopback store (see the module docstring); ``mode`` may be switched between runs."""

    def __init__(self, *, robots_hang_s: float = 0.0, sitemap_urls: int = 0, drip_s: float = 60.0) -> None:
        self.mode = "good"
        self.robots_hang_s, self.sitemap_urls, self.drip_s = robots_hang_s, sitemap_urls, drip_s
        self.requests = 0
        self.seen: dict[str, float] = {}  # path -> monotonic time of its first request
        self.peers: set[int] = set()  # the client ports that asked: one per connection
        self.dead_port = closed_port()
        self._server = ThreadingHTTPServer(("127.0.0.1", 0), _Handler)
        self._server.daemon_threads = True
        self._server.store = self  # type: ignore[attr-defined]
        self._thread = threading.Thread(target=self._server.serve_forever, daemon=True)
        self._bombs: dict[str, bytes] = {}
        self._huge_sitemap: bytes | None = None

    @property
    def port(self) -> int:
        return self._server.server_address[1]

    @property
    def base_url(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def page_paths(self) -> list[str]:
        if self.sitemap_urls:
            return [f"/p/s{i}" for i in range(3)]
        if self.robots_hang_s:
            return ["/p/behind-robots"]
        return [f"/p/{kind}" for kind in PAGE_KINDS]

    def __enter__(self) -> PageStore:
        if self.sitemap_urls:  # built before any run: the server's own time is not the client's to measure
            mode, self.mode = self.mode, "hostile"
            self._sitemap()
            self.mode = mode
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._server.shutdown()
        self._server.server_close()

    # -- answers --------------------------------------------------------------------------------------
    def answer(self, h: _Handler) -> None:
        path = h.path
        kind = path[3:].split("?", 1)[0]  # a query (``?n=2``) names another page of the same kind
        if path == "/robots.txt":
            if self.mode == "hostile" and self.robots_hang_s:
                time.sleep(self.robots_hang_s)
            h._send(200, b"User-agent: *\nAllow: /\n", "text/plain")
        elif path == "/sitemap.xml":
            h._send(200, self._sitemap(), "application/xml")
        elif path.startswith("/p/") and self.mode == "hostile" and not path.startswith("/p/s"):
            self._hostile(h, kind)
        elif path.startswith("/p/") or path == "/moved":
            h._send(200, good_page("redirect-other-host" if path == "/moved" else kind))
        else:
            h._send(404, b"nope", "text/plain")

    def _sitemap(self) -> bytes:
        hostile = self.mode == "hostile" and bool(self.sitemap_urls)
        if hostile and self._huge_sitemap is not None:
            return self._huge_sitemap
        paths = self.page_paths()
        if hostile:
            paths = [f"/p/s{i}" for i in range(self.sitemap_urls)]
        base = self.base_url
        locs = "".join(f"<url><loc>{base}{p}</loc></url>" for p in paths)
        body = (
            '<?xml version="1.0"?><urlset xmlns="http://www.sitemaps.org/schemas/sitemap/0.9">'
            f"{locs}</urlset>"
        ).encode()
        if hostile:
            self._huge_sitemap = body
        return body

    def _drip(self, h: _Handler, kind: str) -> None:
        """Drip a byte every :data:`DRIP_INTERVAL_S` for ``drip_s``: of the body (``drip``), of the status
        line's reason phrase (``drip-status``: http.client reads the line whole, up to 64 KiB), of header
        lines after the status line (``drip-headers``), or of a chunk-size line after the headers
        (``drip-chunked``: leading zeros, which the chunked coding allows)."""
        h.close_connection = True
        head = {
            "drip": b"HTTP/1.1 200 OK\r\nContent-Type: text/html; charset=utf-8\r\n\r\n",
            "drip-status": b"HTTP/1.1 200 ",
            "drip-headers": b"HTTP/1.1 200 OK\r\n",
            "drip-chunked": b"HTTP/1.1 200 OK\r\nContent-Type: text/html\r\nTransfer-Encoding: chunked\r\n\r\n",
        }[kind]
        drops = {"drip": b" ", "drip-status": b"O", "drip-chunked": b"0"}
        lines = b"".join(b"X-Drip-%d: v\r\n" % i for i in range(90))  # under http.client's 100 headers
        h.wfile.write(head)
        h.wfile.flush()
        end, i = time.monotonic() + self.drip_s, 0
        while time.monotonic() < end:
            h.wfile.write(lines[i % len(lines) : i % len(lines) + 1] if kind == "drip-headers" else drops[kind])
            h.wfile.flush()
            i += 1
            time.sleep(DRIP_INTERVAL_S)

    def _bomb(self, encoding: str) -> bytes:
        if encoding not in self._bombs:
            zeros = b"\0" * BOMB_BYTES
            self._bombs[encoding] = gzip.compress(zeros, 9) if encoding == "gzip" else zlib.compress(zeros, 9)
        return self._bombs[encoding]

    def _hostile(self, h: _Handler, kind: str) -> None:  # noqa: C901 - one branch per hostile page
        if kind.startswith("drip"):
            self._drip(h, kind)
        elif kind.startswith("redirect-endless"):
            n = int(kind.rsplit("/", 1)[-1]) if "/" in kind else 0
            h._send(302, b"", "", Location=f"/p/redirect-endless/{n + 1}")
        elif kind in ("redirect-circle", "redirect-circle-b"):
            h._send(302, b"", "", Location="/p/redirect-circle-b" if kind == "redirect-circle" else "/p/redirect-circle")
        elif kind == "redirect-other-port":
            h._send(301, b"", "", Location=f"http://127.0.0.1:{self.dead_port}/p/redirect-other-port")
        elif kind == "redirect-other-host":
            h._send(301, b"", "", Location=f"http://localhost:{self.port}/moved")
        elif kind in ("gzip-bomb", "deflate-bomb"):
            encoding = kind.split("-")[0]
            h._send(200, self._bomb(encoding), Content_Encoding=encoding)
        elif kind == "nested":  # 1 million nested elements, under the size cap (5 MB)
            h._send(200, b"<html><body><h1>Nested Mug</h1>" + b"<div>" * 1_000_000 + b"</body></html>")
        elif kind == "jsonld-10000":
            blocks = "".join(
                f'<script type="application/ld+json">{json.dumps({"@type": "WebPage", "name": f"Block {i}"})}</script>'
                for i in range(10_000)
            )
            h._send(200, f"<html><head>{blocks}</head><body><h1>Ten Thousand</h1></body></html>".encode())
        elif kind == "wrong-charset":  # the good page, says Shift_JIS, with windows-1252 words added
            body = good_page(kind).replace(b"</body>", "<p>Caf\u00e9 Gr\u00fc\u00dfe \u20ac</p></body>".encode("cp1252"))
            h._send(200, body, "text/html; charset=shift_jis")
        elif kind == "missing-charset":  # the good page, no charset anywhere, latin-1 words added
            body = good_page(kind).replace(b"</body>", "<p>Cr\u00e8me br\u00fbl\u00e9e</p></body>".encode("latin-1"))
            h._send(200, body, "text/html")
        elif kind == "error-page":  # a 200 whose body is a "page not found"
            h._send(200, b"<html><head><title>404 Not Found</title></head><body><h1>Not Found</h1></body></html>")
        else:
            h._send(404, b"nope", "text/plain")


def sources_text(stores: dict[str, PageStore], *, deadline_s: float = 1.0, extra: str = "") -> str:
    """A sources file: one ``[[stores]]`` per named store, no delay, no retries, a small page deadline."""
    text = f"[defaults]\ndelay_s = 0\nread_timeout_s = 5.0\nmax_retries = 1\nbackoff_s = 0\nmax_page_s = {deadline_s}\n"
    for name, store in stores.items():
        text += (
            f'[[stores]]\nname = "{name}"\nbase_url = "{store.base_url}"\n'
            'sitemaps = ["{base_url}/sitemap.xml"]\n'
        )
        if store.sitemap_urls:
            # it tests the URL cap, not the page deadline: its ~55 MB body gets the default deadline, so a
            # slower machine (CI) does not turn the cap into a time-out
            text += "max_pages = 3\nmax_bytes = 67108864\nmax_page_s = 30.0\n"
    return text + extra
