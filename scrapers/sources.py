"""The sources file: which stores the ingestion job reads, and how politely.

A ``sources.toml`` lists stores under ``[[stores]]``; ``[defaults]`` holds settings every store inherits::

    [defaults]
    delay_s = 1.0            # minimum gap between two requests to one host (robots Crawl-delay can raise it)
    read_timeout_s = 30.0
    max_retries = 3

    [[stores]]
    name = "demo"
    base_url = "http://127.0.0.1:8765"
    sitemaps = ["{base_url}/sitemap.xml"]   # or leave out: the Sitemap lines of robots.txt are used
    urls = []                               # pages to fetch besides the sitemap's
    include = ["/p/", "/products/"]         # keep only URLs whose path contains one of these (regexes)
    exclude = ["/cart"]
    adapter = "auto"                        # or "shopify": fetch /products/<handle>.json instead of the page
    max_pages = 1000
    search = "{base_url}/search?q={query}"  # optional: the store's search, for on-demand lookups
    search_results = 3                      # product pages a lookup reads from one store's results
    max_page_s = 30.0                       # a page's total deadline (connect + headers + body, retries)
    budget_s = 3600.0                       # the store's time per run; then its other pages are skipped

``max_page_s`` and ``budget_s`` (and ``objrecall ingest --page-deadline`` / ``--store-budget``, which
override every store's) bound what a slow or hostile store costs the run (:mod:`scrapers.deadlines`).

``search`` is a URL template with ``{query}`` where the search words go (URL-encoded); its answer may be
an HTML results page (product links, ``rel="next"`` pagination) or JSON (objects with a ``url``), see
:mod:`scrapers.store_search`. Only ``objrecall recall --lookup`` uses it; the nightly job never searches.
``{base_url}`` in any URL is replaced by the store's ``base_url`` (which ``objrecall ingest --base-url``
overrides, so one file serves a demo store on any port). Every key is checked: an unknown key, a wrong type
or an impossible value is a :class:`~kb.errors.SourcesError` naming the file, the store and the key.
"""

from __future__ import annotations

import re
import tomllib
from dataclasses import dataclass, field, fields
from pathlib import Path
from typing import Any
from urllib.parse import quote_plus, urlsplit

from kb.errors import SourcesError
from scrapers.fetcher import FetchPolicy

__all__ = [
    "ADAPTER_HINTS",
    "DEFAULT_MAX_PAGES",
    "DEFAULT_STORE_BUDGET_S",
    "DEFAULT_SEARCH_RESULTS",
    "Sources",
    "StoreSource",
    "load_sources",
    "parse_sources",
]

#: What ``adapter`` may say: "auto" lets the extractors recognise the page; "shopify" fetches each
#: ``/products/<handle>`` page's JSON twin ``/products/<handle>.json`` instead.
ADAPTER_HINTS = ("auto", "shopify")
DEFAULT_MAX_PAGES = 1000
DEFAULT_SEARCH_RESULTS = 3
#: A store's time per run (seconds from its first request): once spent, its other pages are not fetched.
DEFAULT_STORE_BUDGET_S = 3600.0
#: Where the search words go in a ``search`` template.
QUERY_FIELD = "{query}"

_POLICY_KEYS = {
    "delay_s": float,
    "connect_timeout_s": float,
    "read_timeout_s": float,
    "max_bytes": int,
    "max_redirects": int,
    "max_retries": int,
    "backoff_s": float,
    "max_retry_after_s": float,
    "max_page_s": float,
    "obey_robots": bool,
}
_STORE_KEYS = {
    "name": str,
    "base_url": str,
    "sitemaps": list,
    "urls": list,
    "include": list,
    "exclude": list,
    "adapter": str,
    "max_pages": int,
    "search": str,
    "search_results": int,
    "budget_s": float,
    **_POLICY_KEYS,
}
_DEFAULT_KEYS = {
    k: v for k, v in _STORE_KEYS.items() if k not in ("name", "base_url", "sitemaps", "urls", "search")
}


@dataclass(frozen=True)
class StoreSource:
    """One store to crawl (see the module docstring for the keys)."""

    name: str
    base_url: str
    sitemaps: tuple[str, ...] = ()
    urls: tuple[str, ...] = ()
    include: tuple[str, ...] = ()
    exclude: tuple[str, ...] = ()
    adapter: str = "auto"
    max_pages: int = DEFAULT_MAX_PAGES
    policy: FetchPolicy = field(default_factory=FetchPolicy)
    search: str | None = None
    search_results: int = DEFAULT_SEARCH_RESULTS
    budget_s: float = DEFAULT_STORE_BUDGET_S

    def search_url(self, query: str) -> str:
        """The store's search URL for ``query`` (words URL-encoded); the store must have a ``search``."""
        if self.search is None:
            raise SourcesError(f"store {self.name!r} has no search")
        return self.search.replace(QUERY_FIELD, quote_plus(query))

    def wants(self, url: str) -> bool:
        """True if ``url`` passes the include/exclude patterns (matched against the URL's path+query)."""
        parts = urlsplit(url)
        target = parts.path + (f"?{parts.query}" if parts.query else "")
        if self.include and not any(re.search(p, target) for p in self.include):
            return False
        return not any(re.search(p, target) for p in self.exclude)

    def to_dict(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "base_url": self.base_url,
            "sitemaps": list(self.sitemaps),
            "urls": list(self.urls),
            "adapter": self.adapter,
            "delay_s": self.policy.delay_s,
            "max_page_s": self.policy.max_page_s,
            "budget_s": self.budget_s,
            "search": self.search,
        }


@dataclass(frozen=True)
class Sources:
    stores: tuple[StoreSource, ...]
    origin: str = "<sources>"

    def describe(self) -> str:
        """One line for the ingestion-runs table (readable by anyone with SQL access: ``objrecall sql``,
        ``POST /sql``): the sources file's name, never its path on the server, and the store names."""
        return f"{file_name(self.origin)}: " + ", ".join(s.name for s in self.stores)


def file_name(origin: str) -> str:
    """The last part of a path (``/srv/app/stores.toml`` -> ``stores.toml``, also with backslashes)."""
    return re.split(r"[/\\]", origin)[-1] or origin


def _fail(origin: str, where: str, message: str) -> SourcesError:
    return SourcesError(f"{origin}: {where}: {message}" if where else f"{origin}: {message}")


def _check_type(origin: str, where: str, key: str, value: Any, kind: type) -> Any:
    if kind is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise _fail(origin, where, f"{key} must be a number, not {value!r}")
        return float(value)
    if kind is int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise _fail(origin, where, f"{key} must be a whole number, not {value!r}")
        return value
    if kind is list:
        if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
            raise _fail(origin, where, f"{key} must be a list of strings")
        return value
    if not isinstance(value, kind):
        raise _fail(origin, where, f"{key} must be a {kind.__name__}, not {value!r}")
    return value


def _check_url(origin: str, where: str, key: str, url: str) -> str:
    parts = urlsplit(url)
    if parts.scheme not in ("http", "https") or not parts.netloc:
        raise _fail(origin, where, f"{key}: {url!r} is not an http(s) URL")
    return url


def _known(origin: str, where: str, table: dict[str, Any], allowed: dict[str, type]) -> None:
    unknown = sorted(set(table) - set(allowed))
    if unknown:
        raise _fail(origin, where, f"unknown key {unknown[0]!r} (known: {', '.join(sorted(allowed))})")


@dataclass(frozen=True)
class _Overrides:
    """What the command line sets for every store (None: each store's own value)."""

    base_url: str | None = None
    delay_s: float | None = None
    max_page_s: float | None = None
    budget_s: float | None = None

    def check(self, origin: str) -> None:
        if self.base_url is not None:
            _check_url(origin, "--base-url", "base_url", self.base_url)
        if self.delay_s is not None and self.delay_s < 0:
            raise _fail(origin, "--delay", "delay must be >= 0")
        if self.max_page_s is not None and not self.max_page_s > 0:
            raise _fail(origin, "--page-deadline", "the page deadline must be > 0 seconds")
        if self.budget_s is not None and not self.budget_s > 0:
            raise _fail(origin, "--store-budget", "the store budget must be > 0 seconds")


def parse_sources(
    text: str,
    *,
    origin: str = "<sources>",
    base_url: str | None = None,
    delay_s: float | None = None,
    max_page_s: float | None = None,
    budget_s: float | None = None,
) -> Sources:
    """Parse and check a sources file's text. ``base_url``, ``delay_s``, ``max_page_s`` (the page deadline)
    and ``budget_s`` (the store budget) override every store's."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise _fail(origin, "", f"not valid TOML ({err})") from None
    _known(origin, "", data, {"defaults": dict, "stores": list})
    defaults = data.get("defaults", {})
    if not isinstance(defaults, dict):
        raise _fail(origin, "", "[defaults] must be a table")
    _known(origin, "[defaults]", defaults, _DEFAULT_KEYS)
    stores_raw = data.get("stores")
    if not isinstance(stores_raw, list) or not stores_raw:
        raise _fail(origin, "", "no stores: add at least one [[stores]] table")
    overrides = _Overrides(base_url, delay_s, max_page_s, budget_s)
    overrides.check(origin)
    stores: list[StoreSource] = []
    seen: set[str] = set()
    for i, raw in enumerate(stores_raw, start=1):
        stores.append(_store(origin, i, raw, defaults, overrides, seen))
    return Sources(tuple(stores), origin)


def _store(origin: str, i: int, raw: object, defaults: dict, overrides: _Overrides, seen: set[str]) -> StoreSource:
    """The ``i``-th ``[[stores]]`` table, checked, over ``defaults`` and under ``overrides``; its name is
    added to ``seen`` (the names of the stores before it)."""
    if not isinstance(raw, dict):
        raise _fail(origin, f"store {i}", "must be a table")
    where = f"store {i}" + (f" ({raw['name']!r})" if isinstance(raw.get("name"), str) else "")
    _known(origin, where, raw, _STORE_KEYS)
    merged = {**defaults, **raw}
    values = {k: _check_type(origin, where, k, v, _STORE_KEYS[k]) for k, v in merged.items()}
    for key in ("name", "base_url"):
        if not values.get(key):
            raise _fail(origin, where, f"missing {key}")
    if values["name"] in seen:
        raise _fail(origin, where, f"two stores are named {values['name']!r}")
    seen.add(values["name"])
    base = (overrides.base_url or values["base_url"]).rstrip("/")
    _check_url(origin, where, "base_url", base)

    def expand(url: str, key: str) -> str:
        return _check_url(origin, where, key, url.replace("{base_url}", base))

    sitemaps = tuple(expand(u, "sitemaps") for u in values.get("sitemaps", []))
    urls = tuple(expand(u, "urls") for u in values.get("urls", []))
    for key in ("include", "exclude"):
        for pattern in values.get(key, []):
            try:
                re.compile(pattern)
            except re.error as err:
                raise _fail(origin, where, f"{key}: {pattern!r} is not a valid regex ({err})") from None
    adapter = values.get("adapter", "auto")
    if adapter not in ADAPTER_HINTS:
        raise _fail(origin, where, f"adapter {adapter!r} unknown (one of {', '.join(ADAPTER_HINTS)})")
    max_pages = values.get("max_pages", DEFAULT_MAX_PAGES)
    if max_pages <= 0:
        raise _fail(origin, where, "max_pages must be > 0")
    search = values.get("search")
    if search is not None:
        if QUERY_FIELD not in search:
            raise _fail(origin, where, f"search: {search!r} has no {QUERY_FIELD} for the search words")
        _check_url(origin, where, "search", expand(search.replace(QUERY_FIELD, "q"), "search"))
        search = search.replace("{base_url}", base)
    search_results = values.get("search_results", DEFAULT_SEARCH_RESULTS)
    if search_results <= 0:
        raise _fail(origin, where, "search_results must be > 0")
    budget = overrides.budget_s if overrides.budget_s is not None else values.get("budget_s", DEFAULT_STORE_BUDGET_S)
    if not budget > 0:
        raise _fail(origin, where, "budget_s must be > 0")
    return StoreSource(
        name=values["name"],
        base_url=base,
        sitemaps=sitemaps,
        urls=urls,
        include=tuple(values.get("include", [])),
        exclude=tuple(values.get("exclude", [])),
        adapter=adapter,
        max_pages=max_pages,
        policy=_policy(origin, where, values, overrides),
        search=search,
        search_results=search_results,
        budget_s=budget,
    )


def _policy(origin: str, where: str, values: dict, overrides: _Overrides) -> FetchPolicy:
    policy_values = {k: values[k] for k in _POLICY_KEYS if k in values}
    if overrides.delay_s is not None:
        policy_values["delay_s"] = overrides.delay_s
    if overrides.max_page_s is not None:
        policy_values["max_page_s"] = overrides.max_page_s
    try:
        return FetchPolicy(**policy_values)
    except ValueError as err:
        raise _fail(origin, where, str(err)) from None


def load_sources(
    path: str | Path,
    *,
    base_url: str | None = None,
    delay_s: float | None = None,
    max_page_s: float | None = None,
    budget_s: float | None = None,
) -> Sources:
    """Read and check a sources file (see :func:`parse_sources`)."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise SourcesError(f"{path}: no such sources file") from None
    except (OSError, UnicodeDecodeError) as err:
        raise SourcesError(f"{path}: cannot be read ({err})") from None
    return parse_sources(
        text, origin=str(path), base_url=base_url, delay_s=delay_s, max_page_s=max_page_s, budget_s=budget_s
    )


assert {f.name for f in fields(FetchPolicy)} >= set(_POLICY_KEYS)
