"""The demo storefront: a small HTTP server on loopback serving :data:`PRODUCTS` in every format.

Routes: ``/`` (links to everything), ``/robots.txt`` (a Disallow and a Crawl-delay), ``/sitemap.xml``,
each product's page (see :attr:`DemoProduct.path`), ``/products/<handle>.json`` for the Shopify-style ones,
a duplicate route with a canonical link, a 301 from an old URL, a page that answers 503 with Retry-After
once, and the broken pages of :data:`BROKEN_PAGES` (malformed JSON-LD, 500, slow, 50 MB, absurd values,
not a product, disallowed). ``/search?q=&page=`` and ``/search.json?q=`` search every product, including
:data:`SEARCH_ONLY_PRODUCTS`, which no sitemap or page lists (see :mod:`scrapers.demo_store.search`);
``search_fault`` makes the search slow or answer 500, ``disallow_search`` puts it under a robots.txt
Disallow, so tests can meet the stores a lookup must skip.

Every 200 page has an ``ETag`` (hash of the body) and a ``Last-Modified`` (the product's ``updated``), and
conditional requests get ``304 Not Modified``. :meth:`DemoStore.update_product` changes a product while the
server runs (a new version of the page, a new ETag), and :attr:`DemoStore.log` records every request, so
tests can check what a crawler sent.
"""

from __future__ import annotations

import dataclasses
import email.utils
import hashlib
import threading
import time
from dataclasses import dataclass
from datetime import UTC, datetime
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from urllib.parse import parse_qs, urlsplit

from scrapers.demo_store import search, store_pages, templates
from scrapers.demo_store.products import (
    BROKEN_PAGES,
    DUPLICATE_ROUTES,
    FLAKY_PATH,
    FLAKY_PRODUCT,
    PRODUCTS,
    SEARCH_ONLY_PRODUCTS,
    TWIN_PRODUCTS,
    BrokenPage,
    DemoProduct,
)

__all__ = ["DemoStore", "RequestLogEntry"]

HUGE_BYTES = 50 * 1024 * 1024
#: What ``search_fault`` may be: the search answers after ``slow_s`` seconds, or always with a 500.
SEARCH_FAULTS = ("slow", "http_500")


@dataclass(frozen=True)
class RequestLogEntry:
    method: str
    path: str
    status: int
    user_agent: str | None
    if_none_match: str | None
    if_modified_since: str | None
    started: float
    finished: float


class _Server(ThreadingHTTPServer):
    daemon_threads = True
    allow_reuse_address = True
    store: DemoStore

    def handle_error(self, request, client_address) -> None:
        """Clients that hang up (size caps, timeouts) are normal here; anything else is printed."""
        import sys

        if not isinstance(sys.exc_info()[1], (ConnectionError, TimeoutError)):
            super().handle_error(request, client_address)


class _Handler(BaseHTTPRequestHandler):
    protocol_version = "HTTP/1.1"
    # Headers and body go out in separate writes; with Nagle on, each keep-alive response would wait
    # for the client's delayed ACK (~40 ms).
    disable_nagle_algorithm = True
    server: _Server

    def log_message(self, format: str, *args) -> None:  # noqa: A002 - keep the test output clean
        pass

    def do_HEAD(self) -> None:  # noqa: N802
        self._serve(head=True)

    def do_GET(self) -> None:  # noqa: N802
        self._serve(head=False)

    def _serve(self, *, head: bool) -> None:
        store = self.server.store
        started = time.monotonic()
        self._left = False
        with store._lock:
            store._in_flight += 1
            store.max_in_flight = max(store.max_in_flight, store._in_flight)
        status = 500
        try:
            status = store._respond(self, head=head)
        except (BrokenPipeError, ConnectionResetError):
            status = 499  # the client went away (e.g. a size cap): fine
        finally:
            self.leave()
            with store._lock:
                store.log.append(
                    RequestLogEntry(
                        self.command,
                        self.path,
                        status,
                        self.headers.get("User-Agent"),
                        self.headers.get("If-None-Match"),
                        self.headers.get("If-Modified-Since"),
                        started,
                        time.monotonic(),
                    )
                )

    def leave(self) -> None:
        """Count this request as answered; called before the last bytes go out, so that a client that
        sends its next request after reading this answer can never be seen as overlapping it."""
        if not self._left:
            self._left = True
            with self.server.store._lock:
                self.server.store._in_flight -= 1


class DemoStore:
    """The demo storefront, served from a background thread.

    >>> with DemoStore(port=0) as store:      # doctest: +SKIP
    ...     requests.get(store.url("/sitemap.xml"))

    ``port=0`` picks a free port (see :attr:`port`). ``crawl_delay`` is what robots.txt asks of crawlers
    (None leaves the line out); ``slow_s`` is how long the slow page takes; ``huge_bytes`` the size of the
    huge page, generated while streaming (never held in memory). ``search_fault`` (one of
    :data:`SEARCH_FAULTS`) breaks the search; ``disallow_search`` disallows it in robots.txt;
    ``search_only`` are the products only the search finds.
    """

    def __init__(
        self,
        host: str = "127.0.0.1",
        port: int = 0,
        *,
        crawl_delay: float | None = 0.25,
        slow_s: float = 3.0,
        huge_bytes: int = HUGE_BYTES,
        products: tuple[DemoProduct, ...] = PRODUCTS,
        search_only: tuple[DemoProduct, ...] = SEARCH_ONLY_PRODUCTS,
        search_fault: str | None = None,
        disallow_search: bool = False,
    ):
        if search_fault is not None and search_fault not in SEARCH_FAULTS:
            raise ValueError(f"search_fault must be one of {', '.join(SEARCH_FAULTS)}, not {search_fault!r}")
        self.host = host
        self.requested_port = port
        self.crawl_delay = crawl_delay
        self.slow_s = slow_s
        self.huge_bytes = huge_bytes
        self.products: dict[str, DemoProduct] = {
            p.handle: p for p in (*products, FLAKY_PRODUCT, *TWIN_PRODUCTS)
        }
        self.search_only: dict[str, DemoProduct] = {p.handle: p for p in search_only}
        self.search_fault = search_fault
        self.disallow_search = disallow_search
        self.broken: dict[str, BrokenPage] = {b.path: b for b in BROKEN_PAGES}
        self.log: list[RequestLogEntry] = []
        self.max_in_flight = 0
        self._in_flight = 0
        self._lock = threading.Lock()
        self._flaky_served: set[str] = set()
        self._cache: dict[str, tuple[bytes, str]] = {}
        self._server: _Server | None = None
        self._port: int | None = None
        self._thread: threading.Thread | None = None

    # ------------------------------------------------------------------ lifecycle
    def start(self) -> DemoStore:
        if self._server is not None:
            return self
        server = _Server((self.host, self.requested_port), _Handler)
        server.store = self
        self._server = server
        self._port = server.server_address[1]
        self._thread = threading.Thread(target=server.serve_forever, name="demo-store", daemon=True)
        self._thread.start()
        return self

    def stop(self) -> None:
        if self._server is not None:
            self._server.shutdown()
            self._server.server_close()
            self._server = None

    def __enter__(self) -> DemoStore:
        return self.start()

    def __exit__(self, *exc: object) -> None:
        self.stop()

    def serve_forever(self) -> None:
        """Run in the foreground until interrupted (the CLI)."""
        self.start()
        try:
            while True:
                time.sleep(3600)
        except KeyboardInterrupt:
            pass
        finally:
            self.stop()

    @property
    def port(self) -> int:
        if self._port is None:
            raise RuntimeError("the demo store has not been started")
        return self._port

    @property
    def base_url(self) -> str:
        return f"http://{self.host}:{self.port}"

    def url(self, path: str) -> str:
        return self.base_url + path

    # ------------------------------------------------------------------ content
    def product_pages(self) -> dict[str, DemoProduct]:
        """path -> product, for every product page (not the broken ones, not duplicates)."""
        return {p.path: p for p in self.products.values()}

    def sitemap_paths(self) -> list[str]:
        return [*self.product_pages(), *DUPLICATE_ROUTES, *self.broken]

    def update_product(self, handle: str, **changes) -> DemoProduct:
        """Publish a new version of a product's page (e.g. ``mass=400``); its ETag and date change."""
        with self._lock:
            old = self.products[handle]
            stamp = email.utils.format_datetime(datetime.now(UTC).replace(microsecond=0), usegmt=True)
            new = dataclasses.replace(old, updated=stamp, **changes)
            self.products[handle] = new
            self._cache.clear()
        return new

    def _render(self, path: str) -> tuple[bytes, str, str] | None:
        """(body, content type, last-modified) of a cacheable 200 page, or None."""
        base = self.base_url
        pages = self.product_pages()
        prod = pages.get(path) or next((p for p in self.search_only.values() if p.path == path), None)
        if prod is None and path in DUPLICATE_ROUTES and not path.startswith("/old/"):
            prod = self.products[DUPLICATE_ROUTES[path]]
        if prod is not None:
            return templates.render_product(prod, base).encode(), "text/html; charset=utf-8", prod.updated
        if path.startswith("/products/") and path.endswith(".json"):
            handle = path[len("/products/") : -len(".json")]
            prod = self.products.get(handle)
            if prod is not None and prod.fmt == "shopify":
                return (
                    templates.render_shopify_json(prod, base).encode(),
                    "application/json; charset=utf-8",
                    prod.updated,
                )
            return None
        if path == "/robots.txt":
            lines = ["User-agent: *", "Disallow: /private/", "Disallow: /cart"]
            if self.disallow_search:
                lines.append("Disallow: /search")
            if self.crawl_delay is not None:
                lines.append(f"Crawl-delay: {self.crawl_delay:g}")
            lines += ["", f"Sitemap: {base}/sitemap.xml", ""]
            return "\n".join(lines).encode(), "text/plain; charset=utf-8", _EPOCH
        if path == "/sitemap.xml":
            entries = [(p, "2026-11-02") for p in self.sitemap_paths()]
            return store_pages.render_sitemap(entries, base).encode(), "application/xml; charset=utf-8", _EPOCH
        if path == "/":
            links = [(p, prod.title) for p, prod in pages.items()]
            return store_pages.render_home(links, base).encode(), "text/html; charset=utf-8", _EPOCH
        broken = self.broken.get(path)
        if broken is not None and broken.kind in ("malformed_jsonld", "absurd", "not_product", "disallowed"):
            return store_pages.render_broken(broken, base).encode(), "text/html; charset=utf-8", _EPOCH
        return None

    def searchable(self) -> list[DemoProduct]:
        """Every product the search looks through: the listed ones and the search-only ones."""
        return [*self.products.values(), *self.search_only.values()]

    def _search(self, h: _Handler, path: str, query: str, *, head: bool) -> int:
        """The search routes (never cached: every query is its own page)."""
        if self.search_fault == "http_500":
            return _send(h, 500, b"<h1>Search is unavailable</h1>", "text/html", head=head)
        if self.search_fault == "slow":
            time.sleep(self.slow_s)
        params = parse_qs(query)
        q = (params.get("q") or [""])[0]
        with self._lock:
            hits = search.find(self.searchable(), q)
        if path == "/search.json":
            body = search.render_results_json(hits, q, self.base_url).encode()
            return _send(h, 200, body, "application/json; charset=utf-8", head=head)
        try:
            page = int((params.get("page") or ["1"])[0])
        except ValueError:
            page = 1
        body = search.render_results(hits, q, page, self.base_url).encode()
        return _send(h, 200, body, "text/html; charset=utf-8", head=head)

    def _respond(self, h: _Handler, *, head: bool) -> int:
        parts = urlsplit(h.path)
        path = parts.path
        if path in ("/search", "/search.json"):
            return self._search(h, path, parts.query, head=head)
        broken = self.broken.get(path)
        if broken is not None and broken.kind == "http_500":
            return _send(h, 500, b"<h1>Internal Server Error</h1>", "text/html", head=head)
        if broken is not None and broken.kind == "slow":
            time.sleep(self.slow_s)
            body = store_pages.render_broken(broken, self.base_url).encode()
            return _send(h, 200, body, "text/html; charset=utf-8", head=head)
        if broken is not None and broken.kind == "huge":
            return self._send_huge(h, head=head)
        if path in DUPLICATE_ROUTES and path.startswith("/old/"):
            target = self.products[DUPLICATE_ROUTES[path]].path
            return _send(h, 301, b"", "text/html", head=head, extra={"Location": target})
        if path == FLAKY_PATH:
            with self._lock:
                first = path not in self._flaky_served
                self._flaky_served.add(path)
            if first:
                return _send(
                    h, 503, b"<h1>Busy, try again</h1>", "text/html", head=head, extra={"Retry-After": "1"}
                )
        with self._lock:
            cached = self._cache.get(path)
        if cached is None:
            rendered = self._render(path)
            if rendered is None:
                return _send(h, 404, b"<h1>Not found</h1>", "text/html", head=head)
            body, ctype, updated = rendered
            etag = '"' + hashlib.sha256(body).hexdigest()[:20] + '"'
            with self._lock:
                self._cache[path] = (body, ctype, updated, etag)
        else:
            body, ctype, updated, etag = cached
        headers = {"ETag": etag, "Last-Modified": updated, "Cache-Control": "max-age=0"}
        inm = h.headers.get("If-None-Match")
        ims = h.headers.get("If-Modified-Since")
        if inm is not None:
            if etag in [t.strip() for t in inm.split(",")] or inm.strip() == "*":
                return _send(h, 304, b"", ctype, head=True, extra=headers)
        elif ims is not None and _not_after(updated, ims):
            return _send(h, 304, b"", ctype, head=True, extra=headers)
        return _send(h, 200, body, ctype, head=head, extra=headers)

    def _send_huge(self, h: _Handler, *, head: bool) -> int:
        """A page far over any sane size cap, streamed chunked without a Content-Length."""
        h.send_response(200)
        h.send_header("Content-Type", "text/html; charset=utf-8")
        h.send_header("Transfer-Encoding", "chunked")
        h.leave()
        h.end_headers()
        if head:
            return 200
        row = b"<tr><td>Assorted item</td><td>10 x 10 x 10 cm</td><td>100 g</td></tr>\n" * 256
        opening = b"<!DOCTYPE html><html><body><h1>Full catalogue</h1><table>\n"
        h.wfile.write(f"{len(opening):x}\r\n".encode() + opening + b"\r\n")
        sent = len(opening)
        while sent < self.huge_bytes:
            h.wfile.write(f"{len(row):x}\r\n".encode() + row + b"\r\n")
            sent += len(row)
        h.wfile.write(b"0\r\n\r\n")
        return 200


_EPOCH = "Sun, 01 Nov 2026 00:00:00 GMT"


def _not_after(updated: str, since: str) -> bool:
    try:
        return email.utils.parsedate_to_datetime(updated) <= email.utils.parsedate_to_datetime(since)
    except (TypeError, ValueError):
        return False


def _send(h: _Handler, status: int, body: bytes, ctype: str, *, head: bool, extra: dict | None = None) -> int:
    h.send_response(status)
    h.send_header("Content-Type", ctype)
    for k, v in (extra or {}).items():
        h.send_header(k, v)
    if status != 304:
        h.send_header("Content-Length", str(len(body)))
    h.leave()
    h.end_headers()
    if not head and status != 304:
        h.wfile.write(body)
    return status
