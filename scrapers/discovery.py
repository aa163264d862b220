"""Discovery, the ingestion job's first stage: which of a store's pages to fetch this run.

A store's listed URLs and its sitemaps (or, with neither, the Sitemap lines of its robots.txt), sitemap
indexes followed, each sitemap parsed as a stream, filtered by the store's include/exclude patterns,
de-duplicated and capped at ``max_pages``. Every problem (an unreadable or looping sitemap, a time-out) is
an event with its reason, never an exception: discovery gives what it could find.
"""

from __future__ import annotations

import re
from contextlib import AbstractContextManager, nullcontext
from urllib.parse import urlsplit

from kb.errors import FetchError
from scrapers.crawl import STORE_UNRESPONSIVE, TimeoutStreak, unresponsive_reason
from scrapers.fetcher import PoliteFetcher, fetch_error_kind
from scrapers.sources import StoreSource

__all__ = ["MAX_SITEMAPS", "MAX_SITEMAP_URLS", "discover_urls", "sitemap_locs"]

#: Sitemaps read for one store in one run (sitemap indexes included).
MAX_SITEMAPS = 50
#: URLs read from one sitemap (the sitemaps protocol's own limit); the rest are left with a reason.
MAX_SITEMAP_URLS = 50_000
_SHOPIFY_PRODUCT = re.compile(r"^/products/[^/.]+/?$")


def sitemap_locs(body: bytes, cap: int = MAX_SITEMAP_URLS) -> tuple[str, list[str], bool]:
    """(root kind, the first ``cap`` <loc> texts, whether more were left) of a sitemap or sitemap index,
    parsed as a stream (elements freed as read); entities and network access disabled."""
    import io

    from lxml import etree

    kind, locs, more = "", [], False
    events = etree.iterparse(
        io.BytesIO(body), events=("start", "end"), resolve_entities=False, no_network=True, huge_tree=False
    )
    for event, el in events:
        if event == "start":
            kind = kind or etree.QName(el).localname
            continue
        if etree.QName(el).localname == "loc" and el.text and el.text.strip():
            if len(locs) >= cap:
                more = True
                break
            locs.append(el.text.strip())
        if el.getparent() is not None and etree.QName(el).localname in ("url", "sitemap"):
            el.clear()
            while el.getprevious() is not None:
                del el.getparent()[0]
    return kind, locs, more


def discover_urls(
    fetcher: PoliteFetcher,
    store: StoreSource,
    events: list[tuple[str, str, str]],
    *,
    until: float | None = None,
    work: AbstractContextManager | None = None,
    streak: TimeoutStreak | None = None,
) -> list[str]:
    """The page URLs to fetch for ``store``, in order, de-duplicated, filtered and capped.

    Problems (an unreadable sitemap) are appended to ``events`` as (url, stage, reason) and skipped. Every
    fetch ends by ``until`` (the store's budget end, a monotonic time of the fetcher's clock) if given.
    ``work`` (a :class:`~scrapers.crawl.WorkSlots`) is held while a sitemap is parsed, not while fetched.
    Each sitemap fetch counts in ``streak`` (the store's time-outs in a row): once it has given up, the
    other sitemaps are not read (an event ``store_unresponsive`` each).
    """
    streak = streak or TimeoutStreak()
    urls: list[str] = list(store.urls)
    sitemaps = list(store.sitemaps)
    if not sitemaps and not urls:
        try:
            sitemaps = fetcher.sitemaps(store.base_url + "/", store.policy, until=until)
        except FetchError as err:
            events.append(
                (store.base_url + "/robots.txt", "discover", f"{fetch_error_kind(err)}: {err.reason}")
            )
    seen_maps: set[str] = set()
    while sitemaps and len(seen_maps) < MAX_SITEMAPS:
        sitemap = sitemaps.pop(0)
        if sitemap in seen_maps:
            events.append((sitemap, "discover", "sitemap_loop: a sitemap index lists a sitemap already read"))
            continue
        seen_maps.add(sitemap)
        found = _read_sitemap(fetcher, store, sitemap, events, until, work, streak)
        if found is not None:
            kind, locs = found
            (sitemaps if kind == "sitemapindex" else urls).extend(locs)
    return _page_urls(store, urls)


def _read_sitemap(
    fetcher: PoliteFetcher,
    store: StoreSource,
    sitemap: str,
    events: list[tuple[str, str, str]],
    until: float | None,
    work: AbstractContextManager | None,
    streak: TimeoutStreak,
) -> tuple[str, list[str]] | None:
    """One sitemap fetched and parsed: (its kind, its locations), or None with the reason in ``events``."""
    if streak.gave_up:
        why = unresponsive_reason(store, streak.count, "sitemaps and pages")
        events.append((sitemap, "discover", f"{STORE_UNRESPONSIVE}: {why}"))
        return None
    try:
        result = fetcher.fetch(sitemap, policy=store.policy, until=until)
    except FetchError as err:
        streak.record(fetch_error_kind(err))
        events.append((sitemap, "discover", f"{fetch_error_kind(err)}: {err.reason}"))
        return None
    streak.record(None)
    try:
        with work or nullcontext():
            kind, locs, more = sitemap_locs(result.body or b"")
    except Exception as err:  # noqa: BLE001 - lxml's XMLSyntaxError and friends: a bad sitemap is skipped
        events.append((sitemap, "discover", f"bad_sitemap: {type(err).__name__}: {err}"))
        return None
    if more:
        events.append((sitemap, "discover", f"sitemap_truncated: more than {MAX_SITEMAP_URLS} URLs; the first kept"))
    return kind, list(locs)


def _page_urls(store: StoreSource, urls: list[str]) -> list[str]:
    """``urls`` as the store's product pages to fetch: Shopify products as their JSON, de-duplicated, the
    store's include/exclude patterns applied, at most ``max_pages``."""
    out: list[str] = []
    seen: set[str] = set()
    for url in urls:
        if store.adapter == "shopify" and _SHOPIFY_PRODUCT.match(urlsplit(url).path):
            url = url.rstrip("/") + ".json"
        if url in seen or not store.wants(url):
            continue
        seen.add(url)
        out.append(url)
        if len(out) >= store.max_pages:
            break
    return out
