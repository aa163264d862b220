"""Loops a blind tester of issue 25 found reported unclearly: a page that redirects to itself (was
``http_302``) and a sitemap index that lists itself (was status ``ok`` with no error). Real HTTP on
loopback (a server written here), a real DuckDB file."""

from __future__ import annotations

import threading
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

import pytest
import requests

from kb.catalog import KnowledgeBase
from kb.errors import FetchError
from scrapers.fetch_policy import FetchPolicy
from scrapers.fetcher import PoliteFetcher, fetch_error_kind
from scrapers.ingest import run_ingestion
from scrapers.sources import parse_sources


class _Loops(BaseHTTPRequestHandler):
    def log_message(self, *args):  # quiet
        pass

    def do_GET(self):  # noqa: N802 - the http.server API
        base = f"http://127.0.0.1:{self.server.server_address[1]}"
        if self.path == "/robots.txt":
            body, kind = b"User-agent: *\nAllow: /\n", "text/plain"
        elif self.path == "/self":
            self.send_response(302)
            self.send_header("Location", "/self")
            self.send_header("Content-Length", "0")
            self.end_headers()
            return
        elif self.path == "/index.xml":
            body = (f'<?xml version="1.0"?><sitemapindex xmlns="http://www.sitemaps.org/schemas/sitemap/0.9">'
                    f"<sitemap><loc>{base}/index.xml</loc></sitemap></sitemapindex>").encode()
            kind = "application/xml"
        else:
            self.send_response(404)
            self.send_header("Content-Length", "0")
            self.end_headers()
            return
        self.send_response(200)
        self.send_header("Content-Type", kind)
        self.send_header("Content-Length", str(len(body)))
        self.end_headers()
        self.wfile.write(body)


@pytest.fixture
def server():
    srv = ThreadingHTTPServer(("127.0.0.1", 0), _Loops)
    threading.Thread(target=srv.serve_forever, daemon=True).start()
    yield f"http://127.0.0.1:{srv.server_address[1]}"
    srv.shutdown()
    srv.server_close()


def test_a_page_that_redirects_to_itself_is_a_redirect_loop(server):
    with requests.Session() as session:
        fetcher = PoliteFetcher(session, policy=FetchPolicy(delay_s=0, max_retries=0))
        with pytest.raises(FetchError) as info:
            fetcher.fetch(f"{server}/self")
    assert fetch_error_kind(info.value) == "redirect_loop" and "redirects to itself" in str(info.value)


def test_a_sitemap_index_that_lists_itself_is_recorded(server, tmp_path):
    kb = KnowledgeBase.open(tmp_path / "catalog.duckdb")
    text = (f'[defaults]\ndelay_s = 0\nmax_retries = 0\n[[stores]]\nname = "loops"\nbase_url = "{server}"\n'
            'sitemaps = ["{base_url}/index.xml"]\n')
    with requests.Session() as session:
        report = run_ingestion(kb, parse_sources(text), session=session)
    assert [e["reason"] for e in report.errors] == ["sitemap_loop: a sitemap index lists a sitemap already read"]
    assert report.status == "failed" and report.pages == 0  # nothing was read, and it says why
