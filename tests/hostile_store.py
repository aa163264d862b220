"""A loopback store of hostile pages (as a blind tester's store served them): negative and absurd values,
names that are over-long, markup only, with NUL or invalid UTF-8. ``with HostileStore() as store:`` serves
them on 127.0.0.1 with a sitemap; :func:`sources` is a sources file for :func:`scrapers.ingest.run_ingestion`."""

from __future__ import annotations

import json
import threading
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

from scrapers.sources import parse_sources


def product_page(name: str, dims: str = "10 x 8 x 8 cm", mass: str = "300 g", title: str = "x") -> str:
    """A page stating the product three ways: JSON-LD (``width`` holding the whole size, as the tester's
    store wrote it), a spec table and a description."""
    data = {
        "@context": "https://schema.org", "@type": "Product", "name": name,
        "description": f"Size {dims}. Weight {mass}.",
        "weight": {"@type": "QuantitativeValue", "value": mass.split()[0], "unitCode": "GRM"},
        "width": dims, "material": "ceramic",
    }  # fmt: skip
    return (
        f'<html><head><title>{title}</title><script type="application/ld+json">{json.dumps(data)}</script>'
        f"</head><body><h1>{name}</h1><table><tr><th>Dimensions</th><td>{dims}</td></tr><tr><th>Weight</th>"
        f"<td>{mass}</td></tr></table></body></html>"
    )


PAGES: dict[str, bytes] = {
    "/p/good": product_page("Plain Mug", "9 x 9 x 10 cm", "320 g").encode(),
    "/p/negative": product_page("Negative Plate", "-27 x 27 x 2 cm", "-600 g").encode(),
    "/p/absurd": product_page("Giant Teacup", "5000 x 8 x 8 cm", "300 g").encode(),
    "/p/longname": product_page("Z" * 5000, "12 x 6 x 3 cm", "100 g").encode(),
    "/p/markup": product_page("<script>alert('x')</script><img src=x onerror=alert(1)> Hostile Mug").encode(),
    "/p/scriptonly": product_page("<script>alert('x')</script>", title="<b></b>").encode(),
    "/p/nul": b"<html><body><h1>Nul\x00 Jar</h1>Dimensions: 10 x 10 x 12 cm. Weight: 350 g</body></html>",
    "/p/notutf8": b"<html><body><h1>Caf\xe9 Mug \xff\xfe</h1>Dimensions: 9 x 9 x 10 cm, 320 g</body></html>",
}


class _Handler(BaseHTTPRequestHandler):
    def log_message(self, format: str, *args) -> None:  # noqa: A002
        pass

    def do_GET(self) -> None:  # noqa: N802
        store: HostileStore = self.server.store  # type: ignore[attr-defined]
        if self.path == "/robots.txt":
            body, ctype, status = b"User-agent: *\nAllow: /\n", "text/plain", 200
        elif self.path == "/sitemap.xml":
            locs = "".join(f"<url><loc>{store.base_url}{p}</loc></url>" for p in store.pages)
            body = f'<?xml version="1.0"?><urlset xmlns="http://www.sitemaps.org/schemas/sitemap/0.9">{locs}</urlset>'
            body, ctype, status = body.encode(), "application/xml", 200
        elif self.path in store.pages:
            body, ctype, status = store.pages[self.path], "text/html; charset=utf-8", 200
        else:
            body, ctype, status = b"nope", "text/plain", 404
        self.send_response(status)
        self.send_header("Content-Type", ctype)
        self.send_header("Content-Length", str(len(body)))
        self.end_headers()
        self.wfile.write(body)


class HostileStore:
    """The pages of :data:`PAGES` (or ``pages``) on a loopback port chosen by the system."""

    def __init__(self, pages: dict[str, bytes] | None = None) -> None:
        self.pages = dict(PAGES if pages is None else pages)
        self._server = ThreadingHTTPServer(("127.0.0.1", 0), _Handler)
        self._server.store = self  # type: ignore[attr-defined]
        self._thread = threading.Thread(target=self._server.serve_forever, daemon=True)

    @property
    def base_url(self) -> str:
        return f"http://127.0.0.1:{self._server.server_address[1]}"

    def __enter__(self) -> HostileStore:
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._server.shutdown()
        self._server.server_close()


def sources(store: HostileStore, origin: str = "hostile.toml"):
    text = (
        "[defaults]\ndelay_s = 0\nread_timeout_s = 5.0\nmax_retries = 0\n"
        '[[stores]]\nname = "hostile"\nbase_url = "http://127.0.0.1:1"\nsitemaps = ["{base_url}/sitemap.xml"]\n'
    )
    return parse_sources(text, origin=origin, base_url=store.base_url)
